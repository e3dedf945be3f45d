#pragma once
// The DEM world: shape templates shared by many bodies, materials, bodies with
// global ids, the contact history that travels with the pair of ids, and one
// explicit time step. Plain data, free functions, no global state: a domain of
// an MPI decomposition is a World holding its own bodies.
//
// Friction: an incremental tangential spring per persistent contact (Mindlin's
// stiffness 8 G* sqrt(R* delta) for Hertz, 2/7 of the normal stiffness for the
// linear law), turned into the current tangent plane each step and capped by
// Coulomb's mu F_n (sliding). The volume law has no friction yet.
//
// One step (dt): broad phase on boxes from support functions, narrow phase per
// candidate pair (penetration by GJK/EPA for the Hertz and linear laws; the
// overlap region for the volume law), forces and moments, then a
// kick-drift-kick update: velocities and world angular momenta get half a
// step of force and torque, positions drift a full step and orientations
// rotate by the symplectic free-rotation splitting (rigid_rotation.hpp),
// forces are recomputed and the second half kick applied.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

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

/// Tangential spring of a persistent contact, kept by the body with the
/// smaller id of the pair, so it travels with that particle between domains.
struct ContactHistory {
  std::uint64_t other = 0;  ///< id of the other body
  Vec3 spring;              ///< accumulated tangential displacement (m), world frame
  bool touched = false;     ///< seen in the current evaluation (stale entries are dropped)
};

struct Body {
  std::uint64_t id = 0;          ///< global id, stable across domains and restarts
  std::uint32_t shape = 0;       ///< index into World::templates
  std::uint32_t material = 0;    ///< index into World::materials
  bool fixed = false;            ///< never moves (walls, obstacles)
  Vec3 position;                 ///< centre of mass, world (m)
  Quat orientation;              ///< principal frame -> world
  Vec3 velocity;                 ///< m/s
  Vec3 angular_momentum;         ///< world frame, about the centre of mass (kg m^2/s)
  Vec3 force, torque;            ///< accumulated in the current evaluation
  std::vector<ContactHistory> history;  ///< tangential springs of this body's contacts with larger ids
};

struct World {
  std::vector<ShapeTemplate> templates;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  ContactModel model = ContactModel::Hertz;
  Vec3 gravity{0, 0, -9.81};
  Real time = 0;
  /// Stiffness of the linear law (N/m) and of the volume law (N/m^3).
  Real linear_stiffness = 1e5;
  Real volume_stiffness = 1e9;
  // Working state kept between steps.
  std::vector<std::uint32_t> sweep_order;
  std::vector<Aabb> boxes;
  std::vector<BodyPair> candidates;
  OverlapWorkspace overlap_work;       ///< clipping buffers, reused every step
  bool forces_current = false;         ///< body forces belong to the current state
  std::map<std::pair<bool, Real>, Real> damping_cache;  ///< (Hertz?, restitution) -> calibrated damping
};

/// Pose of a body's shape: its principal frame placed in the world, composed
/// with the shape's frame relative to its principal frame.
Transform shape_pose(const World& world, const Body& body) noexcept;

Real mass_of(const World& world, const Body& body) noexcept;

/// Advances the world by dt (s).
void step(World& world, Real dt);

/// Kinetic energy (J) of all bodies.
Real kinetic_energy(const World& world) noexcept;

}  // namespace gjkdem::dem
