#pragma once
// Rotation of a rigid body between contact kicks: the symplectic splitting of
// Dullweber, Leimkuhler and McLachlan ("Symplectic splitting methods for rigid
// body molecular dynamics", J. Chem. Phys. 107, 1997). The free rotation is
// split into rotations about the principal axes, each exactly solvable:
// about axis i for time t the body turns by t * pi_i / I_i (pi = body-frame
// angular momentum). The sequence 1(h/2) 2(h/2) 3(h) 2(h/2) 1(h/2) is second
// order, time-reversible and symplectic: the world angular momentum is kept
// exactly, the energy oscillates by O(h^2) without drift, and the
// intermediate-axis flip of asymmetric bodies appears as it should.
// Torques enter as half-step kicks of the world angular momentum around it.
#include "gjkdem/math/quat.hpp"

namespace gjkdem::dem {

/// Advances `orientation` (principal frame -> world) by dt with the world
/// angular momentum `angular_momentum` held fixed. `moments` are the principal
/// moments of inertia (kg m^2, > 0).
void rotate_free(Quat& orientation, const Vec3& angular_momentum, const Vec3& moments, Real dt) noexcept;

/// World angular velocity of a body with the given state.
Vec3 angular_velocity(const Quat& orientation, const Vec3& angular_momentum, const Vec3& moments) noexcept;

/// Rotational kinetic energy (J).
Real rotational_energy(const Quat& orientation, const Vec3& angular_momentum, const Vec3& moments) noexcept;

}  // namespace gjkdem::dem
