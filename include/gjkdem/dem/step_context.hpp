#pragma once
// What one step passes between its stages, apart from the world's state
// (world.hpp) and the scratch it reuses (step_workspace.hpp): the step's own
// values, which begin_step sets and finish_step reads (as Box2D's
// b2StepContext), and, in a domain run, the domain's role (domains.hpp).
// Neither survives a step's end: a checkpoint holds neither.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gjkdem/math/real.hpp"

namespace gjkdem::dem {

/// Kinetic energy a deforming cell's field gave one body (joules), listed
/// by a domain for rank 0 to sum in id order (periodic.hpp).
struct FieldWork {
  std::uint64_t id;
  Real joules;
};

/// A domain's part in a domain run (domains.hpp). A whole world has none:
/// it owns every body, inserts its inflows' bodies in begin_step and adds
/// the cell's work on its bodies to its own wall_work.
struct DomainRole {
  /// 1 for each body this domain does not own (other domains' bodies seen
  /// here, the fixed bodies every domain holds); pairs of two such bodies
  /// are not listed.
  std::vector<std::uint8_t> foreign;
  /// The largest reach of the whole world's moving bodies (a domain holds
  /// only some; shortest_period takes it).
  Real whole_reach = 0;
  /// The kinetic energy a deforming cell's field gave each body this domain
  /// owns this step, by a change of the field (control_cell) and by a wrap
  /// (wrap_bodies); rank 0 sums each in id order, as those functions do in
  /// a whole world (add_field_work).
  std::vector<FieldWork> field_work, wrap_work;
  /// Per bond of World::bonds: 1 while every rank knows it holds; a bond
  /// this domain breaks is told to the others (sync_bonds, domains.hpp).
  std::vector<std::uint8_t> bonds_told;

  bool owns(std::size_t i) const noexcept { return foreign.empty() || !foreign[i]; }
};

/// The values of one step, from begin_step to finish_step.
struct StepContext {
  Real dt = 0;                     ///< s
  DomainRole* domain = nullptr;    ///< null: the world is whole
  std::size_t kicked_bodies = 0;   ///< bodies that took the first half kick (inflows insert after them)
  std::size_t inserted = 0;        ///< bodies the inflows inserted
  Real power_before = 0;           ///< driven walls' power at the step's start
};

}  // namespace gjkdem::dem
