#pragma once
// Prescribed motion: walls and fixed bodies that move as told, not as forces
// push them (a rotating drum, a vibrating sieve, a shear plate, a conveyor).
// A motion is a rigid movement of the frame its pieces were given in:
//
//   x(t) = c + D(t) + R(t) (x_given - c)
//
// with c the centre of rotation (as given), R(t) the turn by |w| t about the
// angular velocity w, and D(t) the displacement: constant velocity v t, plus
// a sinusoidal vibration a sin(2 pi f t + phase), plus a piecewise-linear
// table of displacements over time (held at its ends). t is the world's time.
// Velocities follow exactly: the piece's point x moves at D'(t) + w x (x - c -
// D(t)). Driven pieces have infinite mass; the work they do on the bodies is
// counted in the energy balance (World::wall_work).
#include <cstdint>
#include <string>
#include <vector>

#include "gjkdem/math/quat.hpp"
#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

struct PrescribedMotion {
  Vec3 center{};            ///< point the rotation turns about, as given (m)
  Vec3 velocity{};          ///< constant translation (m/s)
  Vec3 angular_velocity{};  ///< constant, about `center` (rad/s, world)
  Vec3 amplitude{};         ///< vibration: displacement amplitude and direction (m)
  Real frequency = 0;       ///< vibration frequency (Hz)
  Real phase = 0;           ///< vibration phase (rad)
  std::vector<Real> table_times{};        ///< increasing (s); empty: no table
  std::vector<Vec3> table_displacements{};  ///< one per time (m)
};

/// The movement at one time: the rigid map x -> origin_shift + R x, and the
/// velocity field v(x) = velocity_at_origin + spin x x.
struct MotionFrame {
  Vec3 displacement;        ///< D(t)
  Quat rotation;            ///< R(t)
  Vec3 spin;                ///< w (rad/s)
  Vec3 velocity;            ///< D'(t): the velocity of the moving centre c + D(t)
  Vec3 center;              ///< c + D(t)
  Vec3 velocity_at_origin;  ///< D'(t) - w x (c + D(t))
};

/// Power (W) of a driven piece moving with frame f on a body it pushes with
/// force F and torque T about the world origin (both acting on the body).
inline Real driven_power(const MotionFrame& f, const Vec3& force, const Vec3& torque) noexcept {
  return dot(force, f.velocity_at_origin) + dot(torque, f.spin);
}

/// Throws std::invalid_argument for non-finite values, a negative frequency,
/// a table whose times do not increase or whose sizes differ.
void check_motion(const PrescribedMotion& motion);

MotionFrame motion_frame(const PrescribedMotion& motion, Real time) noexcept;

/// Where a point given at `x` is at the frame's time, and its velocity there.
inline Vec3 moved_point(const MotionFrame& f, const PrescribedMotion& m, const Vec3& x) noexcept {
  return f.center + rotate(f.rotation, x - m.center);
}
inline Vec3 point_velocity(const MotionFrame& f, const Vec3& x) noexcept {
  return f.velocity_at_origin + cross(f.spin, x);
}

}  // namespace gjkdem::dem
