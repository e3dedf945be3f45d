// Normal contact laws in a head-on impact (the law alone, integrated here):
// the Hertz values of Chung and Ooi (2011) test 1 (peak overlap, peak force,
// duration from Hertz theory) and restitution out = in (their test 2) for
// the linear and the calibrated Hertz laws.
#include "gjkdem/dem/contact_law.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace gjkdem::dem {
namespace {

struct Impact {
  double peak_overlap = 0, peak_force = 0, duration = 0, restitution = 0;
};

// m x'' = -F(x, x'), entering contact at x = 0 with speed v0; RK4 with step
// dt (about 1e-5 of the contact time); gives up after 1e7 steps.
Impact integrate(double m, double v0, double dt, const std::function<double(double, double)>& force) {
  Impact r;
  double x = 0, v = v0, t = 0;
  auto a = [&](double xx, double vv) { return -force(xx, vv) / m; };
  for (int step = 0; step < 10000000; ++step) {
    const double k1x = v, k1v = a(x, v);
    const double k2x = v + k1v * dt / 2, k2v = a(x + k1x * dt / 2, v + k1v * dt / 2);
    const double k3x = v + k2v * dt / 2, k3v = a(x + k2x * dt / 2, v + k2v * dt / 2);
    const double k4x = v + k3v * dt, k4v = a(x + k3x * dt, v + k3v * dt);
    const double xn = x + (k1x + 2 * k2x + 2 * k3x + k4x) * dt / 6, vn = v + (k1v + 2 * k2v + 2 * k3v + k4v) * dt / 6;
    if (xn <= 0 && t > 0) {
      const double f = x / (x - xn);
      r.duration = t + f * dt;
      r.restitution = -(v + (vn - v) * f) / v0;
      return r;
    }
    x = xn;
    v = vn;
    t += dt;
    r.peak_overlap = std::fmax(r.peak_overlap, x);
    r.peak_force = std::fmax(r.peak_force, force(x, v));
  }
  return r;
}

// Chung and Ooi test 1: a glass sphere (R = 0.01 m, rho = 2500 kg/m^3,
// E = 4.8e10 Pa, nu = 0.2) onto a rigid wall of the same material at 0.2 m/s.
TEST(ContactLaw, HertzImpactMatchesHertzTheory) {
  const double radius = 0.01, rho = 2500, e_mod = 4.8e10, nu = 0.2, v0 = 0.2;
  const double mass = rho * 4.0 / 3 * kPi * radius * radius * radius;
  HertzParameters p{effective_mass(mass, INFINITY), effective_radius(radius, INFINITY),
                    effective_modulus(e_mod, nu, e_mod, nu), 0};
  const Impact r = integrate(p.effective_mass, v0, 1e-9, [&](double x, double v) { return hertz_normal_force(p, x, v); });
  // Hertz: delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), F_max = 4/3 E* sqrt(R*) delta_max^1.5,
  // t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5).
  const double d_max = std::pow(15 * p.effective_mass * v0 * v0 / (16 * p.effective_modulus * std::sqrt(p.effective_radius)), 0.4);
  const double f_max = 4.0 / 3 * p.effective_modulus * std::sqrt(p.effective_radius) * std::pow(d_max, 1.5);
  const double t_c = 2.868265 * std::pow(p.effective_mass * p.effective_mass / (p.effective_radius * p.effective_modulus * p.effective_modulus * v0), 0.2);
  EXPECT_NEAR(r.peak_overlap / d_max, 1.0, 1e-4);
  EXPECT_NEAR(r.peak_force / f_max, 1.0, 1e-4);
  EXPECT_NEAR(r.duration / t_c, 1.0, 1e-4);
  EXPECT_NEAR(r.restitution, 1.0, 1e-6);
}

TEST(ContactLaw, RestitutionOutEqualsIn) {
  const double m = 0.01, k = 1e5, v0 = 0.5;
  for (double e : {0.2, 0.4, 0.6, 0.8, 1.0}) {
    const double c = linear_damping(linear_damping_ratio_for_restitution(e), k, m);
    const Impact lin = integrate(m, v0, 1e-8, [&](double x, double v) { return linear_normal_force(k, c, x, v); });
    EXPECT_NEAR(lin.restitution, e, 1e-4) << "linear, e = " << e;
    HertzParameters p{m, 0.005, 1e8, hertz_damping_for_restitution(e)};
    for (double speed : {0.05, 0.5, 5.0}) {  // independent of the impact speed
      const Impact h = integrate(m, speed, 1e-8 / std::pow(speed, 0.2), [&](double x, double v) { return hertz_normal_force(p, x, v); });
      EXPECT_NEAR(h.restitution, e, 1e-4) << "Hertz, e = " << e << ", v = " << speed;
    }
  }
  // Without the clamp acting (light damping) the calibration is the textbook ratio.
  const double ln_e = std::log(0.95);
  EXPECT_NEAR(linear_damping_ratio_for_restitution(0.95), -ln_e / std::sqrt(kPi * kPi + ln_e * ln_e), 2e-3);
  EXPECT_THROW(hertz_damping_for_restitution(0), std::invalid_argument);
  EXPECT_THROW(hertz_damping_for_restitution(1.5), std::invalid_argument);
}

}  // namespace
}  // namespace gjkdem::dem
