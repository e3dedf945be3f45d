#pragma once
// The DEM world: shape templates shared by many bodies, materials, bodies with
// global ids, plane walls, the contact history that travels with the pair of
// ids, and one explicit time step. Plain data, free functions, no global
// state: a domain of an MPI decomposition is a World holding its own bodies.
//
// Friction: an incremental tangential spring per persistent contact (Mindlin's
// stiffness 8 G* sqrt(R* delta) for Hertz, 2/7 of the normal stiffness for the
// linear and volume laws), turned into the current tangent plane each step and
// capped by Coulomb's mu F_n (sliding). Under the volume law the contact area
// also resists relative spin about the normal (a twisting spring capped by
// 2/3 mu F_n r, r the radius of a disc of the contact's area).
//
// One step (dt): broad phase on boxes from support functions, narrow phase per
// candidate pair (penetration by GJK/EPA for the Hertz and linear laws; the
// overlap region for the volume law), forces and moments, then a
// kick-drift-kick update: velocities and world angular momenta get half a
// step of force and torque, positions drift a full step and orientations
// rotate by the symplectic free-rotation splitting (rigid_rotation.hpp),
// forces are recomputed and the second half kick applied.
//
// Threads: boxes, the broad phase's strips, narrow phase and force laws run
// in parallel (OpenMP), each pair writing only its own slot; forces are then
// summed in the fixed order of the sorted pair list, so a run gives the same
// bits for any thread count.
//
// Walls: planes are half-spaces (half_space.hpp). Box containers and triangle
// meshes are fixed bodies; the pieces of one wall share a `group`, and under
// the Hertz and linear laws the contacts of a body with one group are merged
// by cluster_contacts (a body lying across two coplanar triangles feels one
// contact, not two).
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "gjkdem/collide/gjk_cache.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/dem/broad_phase.hpp"
#include "gjkdem/dem/mass_properties.hpp"

namespace gjkdem::dem {

struct Material {
  std::string name;
  Real density = 2500;          ///< kg/m^3
  Real youngs_modulus = 1e7;    ///< Pa
  Real poisson_ratio = 0.25;
  Real restitution = 0.5;       ///< normal coefficient of restitution, (0, 1]
  Real friction = 0.5;          ///< Coulomb coefficient, >= 0
};

enum class ContactModel { Hertz, Linear, Volume };

/// The volume law between two bodies (plane walls always use k V, which is
/// conservative there, see half_space.hpp):
/// - Normalized: F = k V along the unit normal S_A / |S_A| (issue 4's F = k V;
///   a potential force only while |S_A| stays constant, as in flat contacts);
/// - Potential: F = (k / A_ref) V S_A, the gradient of U = k V^2 / (2 A_ref),
///   so collisions keep their energy exactly up to the integrator. A_ref is
///   the smaller moving body's volume to the power 2/3 (a cube's face: a cube
///   lying flat on a larger body feels k V under both forms).
enum class VolumeForm { Normalized, Potential };

/// A shape and its mass properties per unit density, computed once and
/// shared by every body made from it.
struct ShapeTemplate {
  Shape shape;                   ///< in its own local frame
  MassProperties unit_mass;      ///< per unit density, in the shape's frame
  PrincipalAxes principal;       ///< of unit_mass.inertia
  /// Radius of curvature for the Hertz law (m): exact for spheres and capsules;
  /// for other shapes the radius of the sphere of equal volume (documented
  /// approximation for polyhedra).
  Real curvature_radius = 0;
};

ShapeTemplate make_template(const Shape& shape);

/// A template for fixed wall pieces (flat triangles have no volume): no mass,
/// and its principal frame is the shape's own frame.
ShapeTemplate make_wall_template(const Shape& shape);

/// Tangential and twisting springs of a persistent contact, kept by the body with the
/// smaller id of the pair, so it travels with that particle between domains.
struct ContactHistory {
  std::uint64_t other = 0;  ///< id of the other body (or plane wall)
  Vec3 spring;              ///< accumulated tangential displacement (m), world frame
  Real twist = 0;           ///< accumulated relative spin about the normal (rad), volume law
  Vec3 roll;                ///< accumulated relative rocking (rad), world frame, volume law between bodies
  bool touched = false;     ///< seen in the current evaluation (stale entries are dropped)
};

struct Body {
  std::uint64_t id = 0;          ///< global id, stable across domains and restarts
  std::uint32_t shape = 0;       ///< index into World::templates
  std::uint32_t material = 0;    ///< index into World::materials
  std::uint32_t group = 0;       ///< > 0: a piece of a wall (contacts with one group are merged)
  bool fixed = false;            ///< never moves (walls, obstacles)
  Vec3 position;                 ///< centre of mass, world (m)
  Quat orientation;              ///< principal frame -> world
  Vec3 velocity;                 ///< m/s
  Vec3 angular_momentum;         ///< world frame, about the centre of mass (kg m^2/s)
  Vec3 force, torque;            ///< accumulated in the current evaluation
  std::vector<ContactHistory> history;  ///< tangential springs of this body's contacts with larger ids
};

/// An infinite plane wall: material on the side opposite to `normal`.
struct PlaneWall {
  std::uint64_t id = 0;       ///< global id, distinct from every body's (it keys contact histories)
  Vec3 point;
  Vec3 normal;                ///< unit, pointing out of the wall
  std::uint32_t material = 0;
};

/// One candidate contact of a force evaluation: a pair of bodies (a, b), or a
/// plane wall a and body b. The narrow phase fills the geometry, the force
/// law the rest; each slot is written by one thread only. `active`: touching
/// (after merging the contacts of a wall).
struct StepContact {
  std::uint32_t a = 0, b = 0;
  bool a_is_plane = false;
  bool active = false;
  int cache = -1;           ///< index into World::pair_caches, -1: none
  // Geometry.
  Vec3 normal;              ///< unit, a -> b
  Vec3 point;               ///< where friction and damping act
  Real depth = 0;           ///< penetration depth, or V / |S_A| for the volume law
  Real area = 0;            ///< |S_A| (volume law)
  Real volume = 0;          ///< overlap volume (volume law)
  Real depth_integral = 0;  ///< plane walls, volume law: integral of the depth over the overlap (m^4)
  Vec3 moment;              ///< moment about the world origin of a unit normal force on b
  // Force law.
  Vec3 force;               ///< on b
  Vec3 torque;              ///< on b, about the world origin
  Vec3 spring;              ///< new tangential spring
  Real twist = 0;           ///< new twisting spring (rad, volume law)
  Vec3 roll;                ///< new rocking spring (rad, volume law between bodies)
  Real elastic = 0;         ///< energy stored in the contact (J)
};

/// Warm start of one candidate pair, kept while its boxes overlap.
struct PairCache {
  BodyPair pair;
  GjkCache gjk;
};

struct World {
  std::vector<ShapeTemplate> templates;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  std::vector<PlaneWall> planes;
  ContactModel model = ContactModel::Hertz;
  Vec3 gravity{0, 0, -9.81};
  Real time = 0;
  /// Stiffness of the linear law (N/m) and of the volume law (N/m^3); 0 takes
  /// them from the materials per pair: E* R* and E* / R* (docs/dem.md).
  Real linear_stiffness = 0;
  Real volume_stiffness = 0;
  VolumeForm volume_form = VolumeForm::Normalized;
  /// Volume law between bodies: the contact area resists relative rocking
  /// (world.cpp); without it two flat faces rock freely about the middle of
  /// their contact and stacks topple. Off, collisions under the potential
  /// form keep their energy exactly.
  bool rocking_resistance = true;
  int threads = 1;                     ///< OpenMP threads for a step (0: all cores)
  // Working state kept between steps.
  SweepWorkspace sweep;
  std::vector<Aabb> boxes;
  std::vector<BodyPair> candidates;
  std::vector<PairCache> pair_caches;  ///< sorted by pair, aligned with candidates after the broad phase
  std::vector<StepContact> contacts;   ///< of the last force evaluation (kept to reuse its memory)
  std::vector<OverlapWorkspace> overlap_work;  ///< clipping buffers, one per thread
  bool forces_current = false;         ///< body forces belong to the current state
  Real elastic_energy = 0;             ///< in the contact springs at the last force evaluation (J)
  int last_contacts = 0;               ///< contacts at the last force evaluation
  int last_wall_contacts = 0;          ///< of which with a plane wall or a fixed body
  std::map<std::pair<bool, Real>, Real> damping_cache;  ///< (Hertz?, restitution) -> calibrated damping
};

/// Makes `caches` follow the sorted `candidates`: entries of pairs that are
/// still candidates keep their warm start, new pairs start cold, the rest are
/// dropped. Needs `caches` sorted by pair; no allocation once capacity suffices.
void align_pair_caches(std::span<const BodyPair> candidates, std::vector<PairCache>& caches);

/// Pose of a body's shape: its principal frame placed in the world, composed
/// with the shape's frame relative to its principal frame.
Transform shape_pose(const World& world, const Body& body) noexcept;

Real mass_of(const World& world, const Body& body) noexcept;

/// Angular velocity (rad/s, world frame) of a body; zero for fixed bodies.
Vec3 angular_velocity_of(const World& world, const Body& body) noexcept;

/// Advances the world by dt (s).
void step(World& world, Real dt);

/// Kinetic energy (J) of all bodies.
Real kinetic_energy(const World& world) noexcept;

/// Potential energy of gravity (J), zero at the world origin.
Real potential_energy(const World& world) noexcept;

/// A critical time step estimate (s): the shortest contact duration between
/// two of the world's bodies divided by 20, or the Rayleigh time step times
/// 0.2 for the Hertz law (docs/dem.md). Needs at least one moving body.
Real critical_time_step(const World& world);

}  // namespace gjkdem::dem
