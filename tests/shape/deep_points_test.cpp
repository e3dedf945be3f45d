// Deep points of closed surfaces (shape/deep_points.hpp), against what the
// solids' own geometry says: a box's centre, a torus's core circle, an L's
// two arms; and the distance to a surface against a scan of its triangles.
#include "gjkdem/shape/deep_points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gjkdem/tolerances.hpp"
#include "surface_shapes.hpp"

namespace gjkdem {
namespace {

// The distance to the nearest triangle, scanning all of them.
Real scanned_distance(const Surface& s, const Vec3& p) {
  Real best = 1e300;
  for (const TriangleIndices& k : s.triangles)
    best = std::fmin(best, length(p - closest_point_on_triangle(p, s.vertices[k[0]], s.vertices[k[1]], s.vertices[k[2]])));
  return best;
}

TEST(DeepPoints, TheDistanceThroughTheTreeIsTheScansAndTheClosestPointIsOnTheTriangle) {
  const Surface torus = test::surface_of(test::torus(1.5, 0.6, 24, 12));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Real> u(-3, 3);
  for (int k = 0; k < 300; ++k) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    EXPECT_EQ(distance_to_surface(torus, p), scanned_distance(torus, p));
  }
  // The closest point of a triangle: no point of a fine grid on it is nearer.
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0.2, 1, 0};
  for (int k = 0; k < 200; ++k) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const Real d = length(p - closest_point_on_triangle(p, a, b, c));
    Real grid = 1e300;
    for (int i = 0; i <= 100; ++i)
      for (int j = 0; i + j <= 100; ++j) grid = std::fmin(grid, length(p - (a + (b - a) * (i / 100.0) + (c - a) * (j / 100.0))));
    EXPECT_LE(d, grid + 1e-12);
    EXPECT_GE(d, grid - 0.02);
  }
}

TEST(DeepPoints, ABoxHasItsCentreATorusItsCoreAnLItsArms) {
  const Surface box = test::surface_of(test::box_surface({0, 0, 0}, {4, 2, 1}));
  const std::vector<DeepPoint> in_box = deep_points(box);
  ASSERT_FALSE(in_box.empty());
  EXPECT_NEAR(in_box[0].depth, 0.5, 1e-3);  // half the thinnest side
  EXPECT_NEAR(in_box[0].point.z, 0.5, 1e-3);

  const Surface torus = test::surface_of(test::torus(1.5, 0.6, 24, 12));
  const std::vector<DeepPoint> in_torus = deep_points(torus);
  ASSERT_GE(in_torus.size(), 4u);  // around the ring, its centre outside
  for (const DeepPoint& d : in_torus) {
    const Real from_axis = std::hypot(d.point.x, d.point.y);
    EXPECT_NEAR(from_axis, 1.5, 0.1);  // on the core circle (of the faceted tube)
    EXPECT_NEAR(d.point.z, 0, 0.05);
    EXPECT_GT(d.depth, 0.5);  // the tube's radius, less its facets
    EXPECT_EQ(d.depth, distance_to_surface(torus, d.point));
  }

  const Surface l = test::surface_of(test::l_prism(1));  // arms [0,2]x[0,1] and [0,1]x[0,2]
  const std::vector<DeepPoint> in_l = deep_points(l);
  bool long_arm = false, tall_arm = false;
  for (const DeepPoint& d : in_l) {
    EXPECT_NEAR(d.depth, 0.5, 1e-3);
    long_arm = long_arm || d.point.x > 1.2;
    tall_arm = tall_arm || d.point.y > 1.2;
  }
  EXPECT_TRUE(long_arm && tall_arm);
  EXPECT_LE(in_l.size(), kDeepPointsMax);
}

}  // namespace
}  // namespace gjkdem
