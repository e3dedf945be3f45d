// A stack of three cubes on a plane floor under the volume law with friction
// and damping stays at rest for 2 s: no cube moves by more than 1e-4 of its
// size (issue 4). Each cube starts at its static overlap (a flat face under
// load W sinks by W / (k a^2)), slightly tilted and shifted, so that any
// unstable mode has something to grow from.
//
// Without the rocking resistance of the contact area (world.cpp), the two
// upper cubes rock about the middle of their faces as inverted pendulums: the
// lateral motion grows from round-off at about 45 /s and settles near 2e-4 of
// the size (measured; docs/dem.md).
#include <gtest/gtest.h>

#include <cmath>

#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {
namespace {

TEST(Stack, ThreeCubesStayAtRestForTwoSeconds) {
  constexpr Real a = 0.02, k = 1e9, density = 2500, g = 9.81;
  WorldSettings settings;
  settings.model = ContactModel::Volume;
  settings.volume_stiffness = k;
  WorldBuilder builder(settings);
  const std::uint32_t rock = builder.add_material({"rock", density, 1e7, 0.25, 0.5, 0.5});
  builder.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor");
  for (int n = 0; n < 3; ++n)  // apart; their starting state is set below
    builder.add_body({.shape = {Shape{Box{{a / 2, a / 2, a / 2}}}, {}}, .material = rock, .position = {0, 0, 1.0 + n}});
  World w = builder.build();
  const Real weight = density * a * a * a * g;
  const Real sink = weight / (k * a * a);  // of one cube under one cube's weight
  Real z = a / 2 - 3 * sink;               // the floor carries three cubes
  for (int n = 0; n < 3; ++n) {
    Body& b = w.bodies[n];
    b.position = {1e-7 * (n - 1), 2e-7 * n, z};
    b.orientation = quat_from_axis_angle(normalized(Vec3{1, Real(2 - n), 0.5}), 1e-6 * (n + 1));
    z += a - (2 - n) * sink;  // the contact above carries the cubes above it
  }
  std::vector<Vec3> start;
  for (const Body& b : w.bodies) start.push_back(b.position);
  Real largest_move = 0, largest_tilt = 0;
  const Real dt = 2e-5;
  for (int i = 0; i < static_cast<int>(2.0 / dt); ++i) {
    step(w, dt);
    for (std::size_t n = 0; n < 3; ++n) {
      largest_move = std::fmax(largest_move, length(w.bodies[n].position - start[n]));
      const Quat& q = w.bodies[n].orientation;
      largest_tilt = std::fmax(largest_tilt, 2 * std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z));
    }
  }
  EXPECT_EQ(w.stats.contacts, 3);
  EXPECT_LT(largest_move, 1e-4 * a);
  EXPECT_LT(largest_tilt, 1e-4);  // radians: an edge moves by less than 1e-4 of the size
  for (const Body& b : w.bodies) EXPECT_LT(length(b.velocity), 1e-5);
}

}  // namespace
}  // namespace gjkdem::dem
