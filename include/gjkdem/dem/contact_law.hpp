#pragma once
// Normal contact force laws and their damping, as plain functions of the
// overlap and its rate, so that they can be tested (and bound to Python)
// without the engine. The sign convention: overlap delta > 0 when the bodies
// interpenetrate, approach speed v = d(delta)/dt (> 0 while approaching); the
// returned force is the repulsive magnitude along the contact normal.
//
// Laws:
// - linear spring-dashpot: F = k delta + c v, c = 2 zeta sqrt(k m*);
// - Hertz (Mindlin for the tangential part, contact_force.cpp): F = k_n delta + gamma v with
//   k_n = 4/3 E* sqrt(R* delta), gamma = 2 beta sqrt(S_n m*), S_n = 2 E*
//   sqrt(R* delta) (the damped Hertz model of Tsuji et al. 1992 as written by
//   Antypov and Elliott 2011).
// Forces never pull (clamped at 0): at the end of a damped impact the raw laws
// would. Clamped, neither law's restitution depends on the impact speed, so
// zeta and beta are calibrated once per requested e by integrating the
// dimensionless impact (the textbook zeta = -ln e / sqrt(pi^2 + ln^2 e) holds
// only for the unclamped oscillator, which the calibration reproduces when
// the clamp never acts).
#include "gjkdem/math/real.hpp"

namespace gjkdem::dem {

/// Effective values of a pair (m* = m1 m2 / (m1 + m2), 1/R* = 1/R1 + 1/R2,
/// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2). A fixed body has infinite mass or
/// radius: pass infinity, the formulas take the limit.
Real effective_mass(Real m1, Real m2) noexcept;
Real effective_radius(Real r1, Real r2) noexcept;
Real effective_modulus(Real e1, Real nu1, Real e2, Real nu2) noexcept;
/// Mindlin's 1/G* = 2 (2 - nu1)(1 + nu1)/E1 + 2 (2 - nu2)(1 + nu2)/E2.
Real effective_shear_modulus(Real e1, Real nu1, Real e2, Real nu2) noexcept;

/// Damping ratio zeta giving restitution e in (0, 1] with the clamped linear
/// law (bisection on the integrated impact, e to about 1e-6).
Real linear_damping_ratio_for_restitution(Real restitution);

/// Dashpot coefficient c = 2 zeta sqrt(k m*) (N s/m).
Real linear_damping(Real damping_ratio, Real stiffness, Real effective_mass) noexcept;

Real linear_normal_force(Real stiffness, Real damping, Real overlap, Real approach_speed) noexcept;

struct HertzParameters {
  Real effective_mass;    ///< m* (kg)
  Real effective_radius;  ///< R* (m)
  Real effective_modulus; ///< E* (Pa)
  Real damping = 0;       ///< beta of the damped Hertz law, from hertz_damping_for_restitution
};

/// Damping parameter beta >= 0 for which a normal impact rebounds with
/// restitution e in (0, 1] (1 gives 0). Bisection on the integrated
/// dimensionless impact; accurate to 1e-6 in e.
Real hertz_damping_for_restitution(Real restitution);

Real hertz_normal_force(const HertzParameters& p, Real overlap, Real approach_speed) noexcept;

}  // namespace gjkdem::dem
