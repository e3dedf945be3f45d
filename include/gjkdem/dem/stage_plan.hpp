#pragma once
// The stages of a step as one ordered table: what each does, in which phase,
// in which file, what it reads and what it writes. step.cpp keeps the fixed
// core (the kicks and the drift of begin_step and finish_step) and walks the
// table for everything between: a force evaluation runs its stages of the
// phases BeforeForces to AfterForces in order, and a whole world's step ends
// with those of AfterStep. A feature that adds physics (heat, a fluid's
// coupling) adds its rows. docs/architecture.md's stage list is printed from
// this table (stage_plan_markdown; tests/dem/stage_plan_test.cpp compares).
#include <span>
#include <string>
#include <string_view>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

enum class StagePhase {
  Integrate,     ///< begin_step's fixed core: kicks, drift, the cell, inflows, motions (not walked: listed)
  BeforeForces,  ///< a force evaluation's set-up: loads reset, boxes, candidates, the contact list
  PerContact,    ///< each contact alone, in parallel, writing only its own slot
  Reduce,        ///< sums over the contacts, in the contact list's order (the same bits for any thread count)
  AfterForces,   ///< the evaluation's end: the second half kick (fixed core)
  AfterStep,     ///< at the step's end, on its forces (a whole world's; a domain run does them together)
};

/// What the stages of one force evaluation share: the world, its role in
/// a domain run (null: whole), the time since the last evaluation (0 at
/// the start), and what earlier stages found for later ones.
struct ForceEvaluation {
  World& world;
  const DomainRole* domain = nullptr;
  Real dt = 0;
  int threads = 1;
  std::size_t box_updates = 0;  ///< boxes remade (the candidates are found again when any was)
  bool bonds_held = false;      ///< an intact bond carries its pair's load
};

/// A stage: its function (null for the fixed core, which step.cpp runs
/// itself) stops the step with a report other than Ok.
struct Stage {
  std::string_view name;
  StagePhase phase;
  std::string_view file;    ///< where it is written (src/dem/)
  std::string_view reads;   ///< what of the world it reads
  std::string_view writes;  ///< what it writes
  StepReport (*run)(ForceEvaluation&) = nullptr;
};

/// Every stage of a step, in order.
std::span<const Stage> stage_plan() noexcept;

/// The plan as docs/architecture.md shows it: a Markdown table (stage,
/// phase, file, reads, writes).
std::string stage_plan_markdown();

std::string_view phase_name(StagePhase phase) noexcept;

}  // namespace gjkdem::dem
