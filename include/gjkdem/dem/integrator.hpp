#pragma once
// Time integration of the bodies between force evaluations (kick-drift-kick,
// velocity Verlet for the translation): a kick adds h of force and torque to
// velocities and world angular momenta; a drift moves positions by dt and
// turns orientations by the symplectic free rotation (rigid_rotation.hpp).
// Fixed bodies never move.
#include <span>

#include "gjkdem/dem/body.hpp"

namespace gjkdem::dem {

/// `applied`: the bodies' applied loads (Body::applied_force) are counted
/// into their applied_work, as the kinetic energy this kick gave by them.
void kick(std::span<Body> bodies, const Makeup& makeup, Real h, int threads, bool applied = false) noexcept;

void drift(std::span<Body> bodies, const Makeup& makeup, Real dt, int threads) noexcept;

}  // namespace gjkdem::dem
