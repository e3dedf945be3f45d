#pragma once
// The force of one contact: a pure function of its geometry, its pair of
// materials, the two bodies' motion and the springs it remembers.
//
// Normal force: the world's law (contact_law.hpp) with the damping
// calibrated for the pair's restitution; on a patch of surface grains
// (ContactGeometry::patch) the Hertz and linear laws take an energy of the
// overlap alone, whose gradient the force is (docs/contact.md). Friction: an incremental tangential
// spring per persistent contact (Mindlin's stiffness 8 G* sqrt(R* delta) for
// Hertz, 2/7 of the normal stiffness for the linear and volume laws), carried
// into the current tangent plane each step and capped by Coulomb's mu F_n
// (sliding). Under the volume law the contact area also resists relative
// spin about the normal (a twisting spring capped by 2/3 mu F_n r, r the
// radius of a disc of the contact's area) and, between bodies, relative
// rocking (k r^2 / 4, capped at F_n r). Under every law a material's rolling
// friction mu_r resists relative rolling (Ai et al. 2011, type C: capped at
// mu_r R* F_n); it shares the rocking spring.
#include "gjkdem/dem/contact_geometry.hpp"
#include "gjkdem/dem/material.hpp"
#include "gjkdem/dem/pair_state.hpp"
#include "gjkdem/dem/world_settings.hpp"

namespace gjkdem::dem {

/// One side of a contact. A fixed body or a plane wall has infinite mass,
/// curvature radius and volume, and no motion.
struct ContactSide {
  bool moving = false;
  Vec3 position;         ///< centre of mass, world (m)
  Vec3 velocity;         ///< m/s
  Vec3 spin;             ///< angular velocity, world (rad/s)
  Real mass = 0;         ///< kg
  Real curvature_radius = 0;  ///< m
  Real volume = 0;       ///< m^3
};

struct ContactForce {
  Vec3 force;            ///< on b (N); a gets the opposite
  Vec3 torque;           ///< on b about the world origin (N m)
  PairHistory history;   ///< the springs after this step
  Real elastic = 0;      ///< energy stored in the contact (J)
};

/// `a_is_plane`: side a is a plane wall (no rocking spring: the wall's force
/// through the centroid of the part below it already rocks back). `dt` is the
/// time since the springs were last advanced (0 at the start of a run).
ContactForce contact_force(const ContactGeometry& geometry, bool a_is_plane, const MaterialPair& materials,
                           const ContactSide& a, const ContactSide& b, const PairHistory& before,
                           const WorldSettings& settings, Real dt) noexcept;

}  // namespace gjkdem::dem
