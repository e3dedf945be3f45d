#pragma once
// The DEM world: what it is made of (settings, shape templates, materials and
// their pair table, motions, inflows), its state (bodies, the pair store, the
// clock, the plane walls where they are, the periodic cell, the broad
// phase's resume cache: what a checkpoint holds), and the scratch of a step
// (step_workspace.hpp). Plain data and free functions, no global state: a
// domain of an MPI decomposition is a World holding its own bodies, with
// its role passed beside it (step_context.hpp). Worlds are made by
// WorldBuilder (world_builder.hpp), which checks what it is given; a World
// assembled by hand must keep the invariants the builder documents.
//
// One step (dt): begin_step and finish_step (step.cpp) keep the fixed core
// (kicks, drift, the cell, inflows, motions) and walk the stage plan
// between (stage_plan.hpp: every stage in order, its phase, its file, what
// it reads and writes; docs/architecture.md prints it).
//
// Threads: boxes, the sweep's strips, narrow phase and laws run in parallel
// (OpenMP), each contact writing only its own slot; forces are then summed in
// the fixed order of the contact list (sorted by pair of ids), so a run gives
// the same bits for any thread count.
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/bonds.hpp"
#include "gjkdem/dem/inflow.hpp"
#include "gjkdem/dem/material.hpp"
#include "gjkdem/dem/motion.hpp"
#include "gjkdem/dem/pair_state.hpp"
#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/step_context.hpp"
#include "gjkdem/dem/step_workspace.hpp"
#include "gjkdem/dem/world_settings.hpp"

namespace gjkdem::dem {

/// What the last force evaluation found.
struct StepStats {
  Real elastic_energy = 0;  ///< stored in the contact springs and the bonds (J)
  int contacts = 0;         ///< touching contacts
  int wall_contacts = 0;    ///< of which with a plane wall or a fixed body
  int box_updates = 0;      ///< moving bodies whose box was recomputed
  int inserted = 0;         ///< bodies the inflows inserted in this step
  int broken = 0;           ///< grains that broke at the end of this step (breakage.hpp)
  int bonds_broken = 0;     ///< bonds that broke in this evaluation (bonds.hpp)
  Real wall_power = 0;      ///< power of the driven walls and bodies on the others (W)
};

enum class StepStatus {
  Ok,
  UnsupportedPair,  ///< the contact model has no computation for this pair of shapes
  CellTooShort,     ///< a deforming periodic cell became shorter than shortest_period (periodic.hpp)
  ThroughWall,      ///< a body lies wholly beyond a plane wall, or its centre crossed a mesh wall piece (id_a the wall or piece, id_b the body)
  Engulfed,         ///< a body lies wholly inside a surface grain, or one inside it (ids of the two)
  Pierced,          ///< a body passed through a surface grain, or one through it: their overlap has no net contact area (ids of the two)
  ThroughBody,      ///< two convex bodies pass through each other: a centre inside the other (ids of the two)
};

/// The outcome of a step; on failure the pair at fault (ids), or for
/// CellTooShort the axis (id_a) and the shortest width allowed (m).
struct StepReport {
  StepStatus status = StepStatus::Ok;
  std::uint64_t id_a = 0, id_b = 0;
  Real shortest = 0;
};

/// What the broad phase keeps from step to step that a continued run needs
/// to find the same candidates (a checkpoint saves it): the box anchors
/// (each box is remade from its anchor with the same bits) and, in a
/// periodic world, the cell the candidates were found in (images lie one of
/// its periods away).
struct SearchCache {
  BoxCache boxes;
  PeriodicCell cell;
  /// The next candidate search takes the cell as it is now: set when a box
  /// was remade, a body wrapped or a tilt was taken back (and in a fresh
  /// world). A search for any other reason (a restored checkpoint, a
  /// domain's new ghosts) keeps the search cell, as the run that did not
  /// stop, or the whole world, has it.
  bool renew_cell = true;
};

/// A body the user named: trace.csv logs it at every output, and messages
/// call it by that name.
struct BodyName {
  std::uint64_t id = 0;  ///< Body::id
  std::string name;
};

struct World {
  // Made by the builder, constant during a run (but for the fragments'
  // templates breakage appends).
  WorldSettings settings;
  std::vector<ShapeTemplate> templates;
  std::vector<Material> materials;
  MaterialTable material_pairs;   ///< from materials and settings.model
  std::vector<PrescribedMotion> motions;  ///< of driven walls and bodies (motion.hpp)
  std::vector<DrivenBody> driven;         ///< the bodies with a motion, as given
  std::vector<Inflow> inflows;            ///< regions inserting bodies during a run (inflow.hpp)
  std::vector<BodyName> names;            ///< the bodies given a name (BodyDef::name), in the order added: traced
  // State: what a checkpoint holds, or what is remade from it (the planes'
  // placement, forces_current).
  std::vector<Body> bodies;       ///< in increasing id order
  std::vector<PairState> pairs;   ///< sorted by key: every pair whose boxes overlap
  Real time = 0;                  ///< s
  /// The plane walls as given and, for the driven ones, placed where their
  /// motion has them at `time` (place_driven; not saved: placed again).
  std::vector<PlaneWall> planes;
  bool forces_current = false;    ///< bodies' forces belong to the current positions
  Real wall_work = 0;             ///< work done on the bodies by driven walls and bodies so far (J)
  /// What the splits of broken grains put into the contacts so far (J): at
  /// each split, the contacts' elastic energy evaluated on the fragments less
  /// what it was on the grains, at the same positions (breakage.hpp; negative
  /// where a split let energy go). The energy balance counts it as supplied.
  Real split_energy = 0;
  /// Bodies may carry applied loads (Body::applied_force): each force
  /// evaluation adds them and each kick counts their work. Set by a run with
  /// a step listener (run.hpp) and by Python's views of the applied loads;
  /// off, neither costs a step anything.
  bool applied_loads = false;
  std::vector<InflowState> inflow_states;  ///< one per inflow
  /// Grains broken so far (breakage.hpp): each split added a body, and
  /// the fragments' templates follow the builder's in `templates`.
  std::uint64_t broken = 0;
  /// The bonds of bonded assemblies (bonds.hpp), intact and broken, sorted
  /// by their bodies' ids: made by the builder, each then only breaks.
  std::vector<Bond> bonds;
  CellState cell;  ///< the periodic cell now, its rate and stress (periodic.hpp)
  StepStats stats;
  SearchCache search;  ///< the broad phase's cache a bit-exact resume needs
  // Results of the last force evaluation, which outputs read.
  StepResults results;
  // Scratch of a step, kept between steps to reuse its memory.
  StepWorkspace work;
};

/// Advances the (whole) world by dt (s). Stops at the first failure and
/// reports it (the world is then left mid-step).
StepReport step(World& world, Real dt);

/// The two halves of step(), between which a domain run moves bodies
/// between domains (domains.hpp): begin_step kicks by half a step, drifts,
/// wraps periodic bodies, advances the clock, runs the inflows (a whole
/// world's) and places the driven bodies; finish_step evaluates the forces
/// and kicks the second half. `context` carries dt, the domain's role (null
/// for a whole world) and what begin_step leaves for finish_step.
StepReport begin_step(World& world, StepContext& context);
StepReport finish_step(World& world, StepContext& context);

/// Evaluates the forces of the current state if they are not current
/// (`domain`: the world's role in a domain run; null for a whole world).
StepReport compute_forces_now(World& world, const DomainRole* domain = nullptr);

/// Puts the driven walls and bodies where their motions have them at
/// world.time, with their velocities (motion.hpp).
void place_driven(World& world);

/// The largest reach of the moving bodies (those the inflows insert
/// included; in a domain, of the whole world's: DomainRole::whole_reach).
Real largest_reach(const World& world, const DomainRole* domain = nullptr) noexcept;

/// The shortest width a periodic cell may have across each periodic axis:
/// four times the largest reach with its box skin (periodic.hpp).
Real shortest_period(const World& world, const DomainRole* domain = nullptr) noexcept;

Transform shape_pose(const World& world, const Body& body) noexcept;
Real mass_of(const World& world, const Body& body) noexcept;
/// Principal moments of inertia (kg m^2).
Vec3 principal_moments(const World& world, const Body& body) noexcept;
/// Angular velocity (rad/s, world frame) of a body; zero for fixed bodies.
Vec3 angular_velocity_of(const World& world, const Body& body) noexcept;

/// Kinetic energy (J) of all bodies.
Real kinetic_energy(const World& world) noexcept;

/// Potential energy of gravity (J), zero at the world origin.
Real potential_energy(const World& world) noexcept;

/// The elastic energy of the last force evaluation's touching contacts (J),
/// added in list order (World::stats.elastic_energy less the bonds'); a
/// domain run's whole is whole_contact_energy (domains.hpp).
Real contact_energy(const World& world) noexcept;

/// A critical time step estimate (s): the shortest contact duration between
/// two of the world's bodies divided by 20, or for the Hertz law the Rayleigh
/// time step times 0.2 over the Mindlin factor sqrt(7 (1 - nu) / (2 - nu))
/// (docs/dem.md); the bodies inflows will insert count.
/// Infinite without moving bodies.
Real critical_time_step(const World& world);

}  // namespace gjkdem::dem
