// Torque-free rotation: the splitting keeps the world angular momentum, keeps
// the energy without drift, follows a fine reference solution of Euler's
// equations, and shows the intermediate-axis (Dzhanibekov) flip.
#include "gjkdem/dem/rigid_rotation.hpp"

#include <gtest/gtest.h>

namespace gjkdem::dem {
namespace {

// Reference: Euler's equations dpi/dt = pi x (pi / I) in the body frame, RK4.
Vec3 euler_reference(Vec3 pi, const Vec3& moments, double t_end, double dt) {
  auto f = [&](const Vec3& p) { return cross(p, Vec3{p.x / moments.x, p.y / moments.y, p.z / moments.z}); };
  for (double t = 0; t < t_end - dt / 2; t += dt) {
    const Vec3 k1 = f(pi), k2 = f(pi + k1 * (dt / 2)), k3 = f(pi + k2 * (dt / 2)), k4 = f(pi + k3 * dt);
    pi += (k1 + k2 * 2 + k3 * 2 + k4) * (dt / 6);
  }
  return pi;
}

TEST(RigidRotation, IntermediateAxisFlipsAndInvariantsHold) {
  const Vec3 moments{1, 2, 3};
  const Quat q0 = normalized(Quat{0.8, 0.1, -0.3, 0.5});
  Quat q = q0;
  const Vec3 omega_body{1e-3, 1.0, 1e-3};  // spun about the intermediate axis
  const Vec3 l = rotate(q0, hadamard(moments, omega_body));
  const double e0 = rotational_energy(q, l, moments), dt = 1e-3;
  double min_omega2 = 1, worst_energy = 0;
  for (int step = 1; step <= 30000; ++step) {
    rotate_free(q, l, moments, dt);
    const Vec3 pi = transpose_mul(to_matrix(q), l);
    min_omega2 = std::fmin(min_omega2, pi.y / moments.y);
    worst_energy = std::fmax(worst_energy, std::fabs(rotational_energy(q, l, moments) - e0) / e0);
    if (step == 5000) {  // 5 s against the reference
      const Vec3 ref = euler_reference(hadamard(moments, omega_body), moments, 5.0, 1e-4);
      EXPECT_NEAR(length(pi - ref) / length(ref), 0.0, 1e-4);
    }
  }
  EXPECT_LT(min_omega2, -0.9);     // the body turned over
  EXPECT_LT(worst_energy, 1e-5);   // no drift: O(dt^2) oscillation
  // The world angular momentum is the state: the body-frame one keeps its length.
  EXPECT_NEAR(length(transpose_mul(to_matrix(q), l)), length(l), 1e-12 * length(l));
}

TEST(RigidRotation, AxisymmetricSpinIsSteady) {
  const Vec3 moments{2, 2, 1};
  Quat q{};
  const Vec3 l{0, 0, 3};  // spin about the symmetry axis
  for (int k = 0; k < 1000; ++k) rotate_free(q, l, moments, 1e-2);
  const Vec3 w = angular_velocity(q, l, moments);
  EXPECT_NEAR(w.z, 3.0, 1e-12);
  EXPECT_NEAR(rotate(q, {0, 0, 1}).z, 1.0, 1e-12);
  // The body turned by omega * t = 3 * 10 rad about z.
  EXPECT_NEAR(std::atan2(rotate(q, {1, 0, 0}).y, rotate(q, {1, 0, 0}).x), std::remainder(30.0, 2 * kPi), 1e-9);
}

}  // namespace
}  // namespace gjkdem::dem
