// A torque-free asymmetric body through the engine's step (box 1 x 2 x 3,
// spun about its intermediate axis with a small perturbation, no gravity, no
// contact): the intermediate-axis flip appears (the spin about that axis
// changes sign and comes back), and the world angular momentum and the
// kinetic energy are conserved to 1e-6 relative.
#include <gtest/gtest.h>

#include <cmath>

#include "gjkdem/dem/rigid_rotation.hpp"
#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {
namespace {

TEST(FreeBody, IntermediateAxisFlipsWithMomentumKept) {
  WorldSettings settings;
  settings.gravity = {};
  WorldBuilder builder(settings);
  const std::uint32_t steel = builder.add_material({"steel", 7800, 2e11, 0.3, 1, 0});
  builder.add_body({.shape = {Shape{Box{{0.05, 0.1, 0.15}}}, {}}, .material = steel, .label = "box"});
  World w = builder.build();
  Body& b = w.bodies[0];
  const Vec3 moments = principal_moments(w, b);
  // The principal axes sorted by moment: the middle one is the intermediate axis.
  int mid = 0;
  for (int k = 0; k < 3; ++k)
    if (moments[k] > std::fmin(moments.x, std::fmin(moments.y, moments.z)) &&
        moments[k] < std::fmax(moments.x, std::fmax(moments.y, moments.z)))
      mid = k;
  Vec3 spin_body{0.01, 0.01, 0.01};
  spin_body[mid] = 10;  // rad/s about the intermediate axis, perturbed
  b.angular_momentum = rotate(b.orientation, hadamard(moments, spin_body));
  const Vec3 l0 = w.bodies[0].angular_momentum;
  const Real e0 = kinetic_energy(w);
  int sign_changes = 0;
  Real previous = spin_body[mid];
  for (int i = 0; i < 20000; ++i) {  // 20 s at 1 ms
    step(w, 1e-3);
    const Body& s = w.bodies[0];
    const Vec3 body_spin = rotate(conjugate(s.orientation), angular_velocity(s.orientation, s.angular_momentum, moments));
    if ((body_spin[mid] > 0) != (previous > 0)) ++sign_changes;
    previous = body_spin[mid];
  }
  EXPECT_GE(sign_changes, 2);  // flipped over and back at least once
  EXPECT_LT(length(w.bodies[0].angular_momentum - l0) / length(l0), 1e-6);
  EXPECT_LT(std::fabs(kinetic_energy(w) - e0) / e0, 1e-6);
  EXPECT_LT(length(w.bodies[0].position), 1e-12);  // no force: the centre stays
}

}  // namespace
}  // namespace gjkdem::dem
