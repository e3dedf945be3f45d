// A body against a half-space, checked against independent answers: the
// overlap clipper (a polytope against a box far larger than it, whose top
// face is the plane) and the closed form of a spherical cap.
#include "gjkdem/contact/half_space.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem::dem {
namespace {

Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return normalized(Quat{g(rng), g(rng), g(rng), g(rng)});
}

TEST(HalfSpace, PolytopeVolumeAndCutFaceMatchTheClipper) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  OverlapWorkspace work;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Vec3> pts(4 + trial % 20);
    for (Vec3& p : pts) p = {u(rng), u(rng), u(rng)};
    const Shape body{make_polytope(pts)};
    const Transform pose = Transform::from({u(rng), u(rng), 0.3 * u(rng)}, random_rotation(rng));
    const Vec3 n = normalized(Vec3{0.2 * u(rng), 0.2 * u(rng), 1});
    const Vec3 point{0, 0, 0};
    const HalfSpaceContact h = half_space_contact(body, pose, point, n);
    // The wall as a box of half-size 50 whose face +z lies on the plane.
    const Quat tilt = quat_from_axis_angle(normalized(cross(Vec3{0, 0, 1}, n)), std::acos(n.z));
    const Shape wall{Box{{50, 50, 50}}};
    const Transform wall_pose = Transform::from(point - n * 50, tilt);
    const OverlapResult o = overlap(wall, wall_pose, body, pose, work);
    if (o.status != OverlapStatus::Overlapping) {
      EXPECT_NEAR(h.volume, 0, 1e-12) << trial;
      continue;
    }
    ASSERT_TRUE(h.touching && h.has_volume) << trial;
    EXPECT_NEAR(h.volume, o.volume, 1e-10) << trial;
    // The overlap's boundary on the wall is the cut face: S_wall = area * n.
    EXPECT_NEAR(h.area, length(o.area_a), 1e-9) << trial;
    // The cut face centroid is where the moment of the wall-side faces acts:
    // M = c x S for a flat face.
    EXPECT_NEAR(length(cross(h.face_centroid, o.area_a) - o.moment_a), 0, 1e-8) << trial;
    EXPECT_NEAR(dot(h.face_centroid - point, n), 0, 1e-12) << trial;
    EXPECT_NEAR(length(h.centroid - o.centroid), 0, 1e-9) << trial;
  }
}

// The integral of the depth over the part below the plane equals the integral
// over s of the volume lying deeper than s (layer-cake), here by Simpson's
// rule on the clipper's volumes of planes lowered by s.
TEST(HalfSpace, DepthIntegralIsTheLayerCakeOfVolumes) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> pts(6 + trial);
    for (Vec3& p : pts) p = {u(rng), u(rng), u(rng)};
    const Shape body{make_polytope(pts)};
    const Transform pose = Transform::from({0, 0, 0.2 * u(rng)}, random_rotation(rng));
    const Vec3 n = normalized(Vec3{0.3 * u(rng), 0.3 * u(rng), 1});
    const HalfSpaceContact h = half_space_contact(body, pose, {0, 0, 0}, n);
    ASSERT_TRUE(h.has_volume) << trial;
    const int steps = 2000;
    const Real ds = h.depth / steps;
    Real integral = 0;
    for (int k = 0; k <= steps; ++k) {
      const Real weight = k == 0 || k == steps ? 1 : (k % 2 ? 4 : 2);
      integral += weight * half_space_contact(body, pose, n * -(k * ds), n).volume;
    }
    integral *= ds / 3;
    EXPECT_NEAR(h.depth_integral, integral, 1e-6 * h.depth * h.volume + 1e-15) << trial;
  }
}

TEST(HalfSpace, BoxBelowThePlaneIsClippedExactly) {
  const Shape box{Box{{0.5, 1, 2}}};
  // Centre 1.5 above the plane z = 0, tilted 0: 0.5 of its height below.
  const HalfSpaceContact h = half_space_contact(box, Transform::from({3, 4, 1.5}, Quat{}), {0, 0, 0}, {0, 0, 1});
  ASSERT_TRUE(h.has_volume);
  EXPECT_NEAR(h.depth, 0.5, 1e-15);
  EXPECT_NEAR(h.volume, 1 * 2 * 0.5, 1e-14);
  EXPECT_NEAR(h.area, 2, 1e-14);
  EXPECT_NEAR(length(h.face_centroid - Vec3{3, 4, 0}), 0, 1e-14);
  EXPECT_NEAR(length(h.centroid - Vec3{3, 4, -0.25}), 0, 1e-14);
  EXPECT_NEAR(h.depth_integral, 2 * 0.5 * 0.5 / 2, 1e-14);
}

TEST(HalfSpace, SphereCapMatchesClosedForm) {
  const Real r = 0.3, pi = kPi;
  for (Real h : {0.01, 0.1, 0.3, 0.5}) {
    const HalfSpaceContact c = half_space_contact(make_sphere(r), Transform::from({1, 2, r - h}, Quat{}), {0, 0, 0},
                                                  {0, 0, 1});
    ASSERT_TRUE(c.has_volume);
    EXPECT_NEAR(c.depth, h, 1e-15);
    EXPECT_NEAR(c.volume, pi * h * h * (3 * r - h) / 3, 1e-15);
    EXPECT_NEAR(c.area, pi * (r * r - (r - h) * (r - h)), 1e-14);
    // Layer cake: the integral over s in [0, h] of the cap of height u = h - s,
    // pi u^2 (3r - u) / 3, is pi (r h^3 - h^4 / 4) / 3.
    EXPECT_NEAR(c.depth_integral, pi * (r * h * h * h - h * h * h * h / 4) / 3, 1e-15);
  }
  EXPECT_FALSE(half_space_contact(make_sphere(r), Transform::from({0, 0, r + 1e-9}, Quat{}), {0, 0, 0}, {0, 0, 1}).touching);
}

}  // namespace
}  // namespace gjkdem::dem
