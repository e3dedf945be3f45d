#include "gjkdem/dem/contact_law.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "gjkdem/tolerances.hpp"

namespace gjkdem::dem {
namespace {

// Restitution of a dimensionless impact x'' = -max(0, F(x, x')) entered at
// x = 0 with unit speed; the contact ends when x returns to 0. The force is
// clamped because contacts push and never pull: near the end of a damped
// impact the unclamped law would hold the bodies together. Both laws here
// give a restitution independent of mass, stiffness and speed, so one
// dimensionless calibration serves every pair.
template <class Force>
Real dimensionless_restitution(Force force) {
  Real x = 0, v = 1, t = 0;
  const Real dt = kCalibrationTimeStep;
  auto accel = [&](Real xx, Real vv) { return -std::fmax(force(std::fmax(xx, Real(0)), vv), Real(0)); };
  do {  // RK4 until the overlap closes again
    const Real k1x = v, k1v = accel(x, v);
    const Real k2x = v + k1v * dt / 2, k2v = accel(x + k1x * dt / 2, v + k1v * dt / 2);
    const Real k3x = v + k2v * dt / 2, k3v = accel(x + k2x * dt / 2, v + k2v * dt / 2);
    const Real k4x = v + k3v * dt, k4v = accel(x + k3x * dt, v + k3v * dt);
    const Real x_new = x + (k1x + 2 * k2x + 2 * k3x + k4x) * dt / 6;
    const Real v_new = v + (k1v + 2 * k2v + 2 * k3v + k4v) * dt / 6;
    if (x_new <= 0 && t > 0) return -(v + (v_new - v) * (x / (x - x_new)));  // speed where x crosses 0
    x = x_new;
    v = v_new;
    t += dt;
  } while (t < 100);
  return 0;  // overdamped: never separates
}

Real hertz_restitution(Real beta) {
  // m = 1, k = 1: F = x^1.5 + 2 beta sqrt(S_n) v with S_n = 1.5 sqrt(x).
  return dimensionless_restitution([beta](Real x, Real v) { return x * std::sqrt(x) + 2 * beta * std::sqrt(1.5 * std::sqrt(x)) * v; });
}

Real linear_restitution(Real zeta) {
  return dimensionless_restitution([zeta](Real x, Real v) { return x + 2 * zeta * v; });
}

// The damping parameter in [0, inf) giving restitution e (restitution falls as it grows).
template <class Restitution>
Real calibrate(Real e, Restitution restitution_of) {
  if (!(e > 0 && e <= 1)) throw std::invalid_argument("restitution must lie in (0, 1]");
  if (e == 1) return 0;
  Real lo = 0, hi = 2;
  while (restitution_of(hi) > e) hi *= 2;
  for (int it = 0; it < 60 && hi - lo > kDampingCalibrationTol; ++it) {
    const Real mid = 0.5 * (lo + hi);
    (restitution_of(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

Real effective_mass(Real m1, Real m2) noexcept {
  if (std::isinf(m1)) return m2;
  if (std::isinf(m2)) return m1;
  return m1 * m2 / (m1 + m2);
}

Real effective_radius(Real r1, Real r2) noexcept { return 1 / (1 / r1 + 1 / r2); }

Real effective_modulus(Real e1, Real nu1, Real e2, Real nu2) noexcept {
  return 1 / ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2);
}

Real effective_shear_modulus(Real e1, Real nu1, Real e2, Real nu2) noexcept {
  return 1 / (2 * (2 - nu1) * (1 + nu1) / e1 + 2 * (2 - nu2) * (1 + nu2) / e2);
}

Real linear_damping_ratio_for_restitution(Real e) { return calibrate(e, linear_restitution); }

Real linear_damping(Real zeta, Real k, Real m) noexcept { return 2 * zeta * std::sqrt(k * m); }

Real linear_normal_force(Real k, Real c, Real overlap, Real speed) noexcept {
  return overlap > 0 ? std::fmax(k * overlap + c * speed, Real(0)) : 0;
}

Real hertz_damping_for_restitution(Real e) { return calibrate(e, hertz_restitution); }

Real hertz_normal_force(const HertzParameters& p, Real overlap, Real speed) noexcept {
  if (!(overlap > 0)) return 0;
  const Real root = std::sqrt(p.effective_radius * overlap);
  const Real k_n = 4.0 / 3 * p.effective_modulus * root;
  const Real s_n = 2 * p.effective_modulus * root;
  return std::fmax(k_n * overlap + 2 * p.damping * std::sqrt(s_n * p.effective_mass) * speed, Real(0));
}

}  // namespace gjkdem::dem
