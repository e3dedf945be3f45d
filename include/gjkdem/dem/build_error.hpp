#pragma once
// What building a world refuses (world_builder.hpp, and the model's own
// checks of what a builder is given: round_region.hpp).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gjkdem::dem {

/// What the builder refuses; the message names the body, wall or material.
struct BuildError : std::runtime_error {
  explicit BuildError(const std::string& what, std::vector<std::uint32_t> at = {})
      : std::runtime_error(what), bodies(std::move(at)) {}
  /// A field's rule broken: what() reads "<subject>: <key> <rule>"; a reader
  /// that knows where the field was written (a scene's line) names it by
  /// `key` and `rule` instead.
  BuildError(const std::string& subject, const std::string& field, const std::string& broken)
      : std::runtime_error(subject + ": " + field + " " + broken), key(field), rule(broken) {}
  std::vector<std::uint32_t> bodies;  ///< indices of the bodies at fault, when there are
  std::string key;   ///< the field at fault, as a scene names it in its table ("" when none)
  std::string rule;  ///< what the field must be ("must lie in (-1, 0.5)")
};

}  // namespace gjkdem::dem
