#pragma once
// The guards as the run loop applies them (run_loop.cpp).
#include <span>
#include <string>

#include "gjkdem/dem/run.hpp"

namespace gjkdem::dem::detail {

/// Checks the guards: the message that stops the run, or "" to go on (a
/// warning is told to the observers once until it changes kind). Unless the
/// guards are off, it also warns, once a run, of contacts deeper than
/// kLawRangeRel of their bodies' radius, beyond what the laws hold for.
class GuardCheck {
 public:
  std::string operator()(const World& world, const RunState& state, const RunGuards& guards,
                         std::span<RunObserver* const> observers);

 private:
  std::string last_warning_;
  bool told_deep_ = false;
};

}  // namespace gjkdem::dem::detail
