#include "gjkdem/shape/convex_hull.hpp"

#include <gtest/gtest.h>

#include <random>

#include "gjkdem/math/quat.hpp"
#include "shape/float_sphere.hpp"

namespace gjkdem {
namespace {

TEST(ConvexHull, RandomCloudsAreEnclosedAndClosed) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 0; c < 40; ++c) {
    std::vector<Vec3> pts;
    const int n = 4 + c * 10;
    for (int i = 0; i < n; ++i) pts.push_back({u(rng), u(rng), u(rng)});
    const ConvexHull h = convex_hull(pts);
    ASSERT_EQ(h.dimension, HullDimension::Solid);
    EXPECT_TRUE(h.manifold);
    EXPECT_EQ(h.triangles.size(), 2 * h.vertices.size() - 4);  // Euler, all faces triangles
    for (const auto& t : h.triangles) {
      const Vec3 nrm = normalized(cross(h.vertices[t[1]] - h.vertices[t[0]], h.vertices[t[2]] - h.vertices[t[0]]));
      for (const Vec3& p : pts) EXPECT_LE(dot(nrm, p - h.vertices[t[0]]), 1e-12);  // all points inside
    }
    // Random clouds have no coplanar triangles: one facet each.
    EXPECT_EQ(h.facets.size(), h.triangles.size());
    // Every hull vertex is an input point.
    for (const Vec3& v : h.vertices) EXPECT_NE(std::find(pts.begin(), pts.end(), v), pts.end());
  }
}

// Points closer than the hull's tolerance are one point: kept both, they made
// a needle face whose plane was noise (a single-precision sphere, turned, had
// every other point up to its diameter beyond one face, and overlaps read it
// as empty). Every face's plane must hold every point behind it.
TEST(ConvexHull, NearDuplicatePointsMakeNoNeedleFaces) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int steps : {8, 12, 16, 32})
    for (int c = 0; c < 6; ++c) {
      const Quat q = normalized(Quat{u(rng), u(rng), u(rng), u(rng)});
      std::vector<Vec3> pts;
      for (const Vec3& p : test::float_sphere(2, steps)) pts.push_back(rotate(q, p) + Vec3{u(rng), u(rng), u(rng)});
      const ConvexHull h = convex_hull(pts);
      ASSERT_EQ(h.dimension, HullDimension::Solid);
      EXPECT_TRUE(h.manifold);
      double worst = 0;
      for (const auto& t : h.triangles) {
        const Vec3 nrm = normalized(cross(h.vertices[t[1]] - h.vertices[t[0]], h.vertices[t[2]] - h.vertices[t[0]]));
        for (const Vec3& p : pts) worst = std::fmax(worst, dot(nrm, p - h.vertices[t[0]]));
      }
      EXPECT_LT(worst, 1e-9) << steps << " steps, case " << c;
      for (std::size_t i = 0; i < h.vertices.size(); ++i)
        for (std::size_t j = i + 1; j < h.vertices.size(); ++j) ASSERT_GT(length(h.vertices[i] - h.vertices[j]), 4e-12);
    }
}

TEST(ConvexHull, DegenerateCloudsReportTheirDimension) {
  EXPECT_EQ(convex_hull(std::vector<Vec3>{}).dimension, HullDimension::Empty);
  EXPECT_EQ(convex_hull(std::vector<Vec3>{{1, 2, 3}, {1, 2, 3}}).dimension, HullDimension::Point);
  const ConvexHull seg = convex_hull(std::vector<Vec3>{{0, 0, 0}, {1, 1, 1}, {0.5, 0.5, 0.5}, {2, 2, 2}});
  EXPECT_EQ(seg.dimension, HullDimension::Segment);
  EXPECT_EQ(seg.vertices.size(), 2u);
  const ConvexHull square = convex_hull(std::vector<Vec3>{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 1}, {0.5, 0, 1}});
  EXPECT_EQ(square.dimension, HullDimension::Polygon);
  EXPECT_EQ(square.vertices.size(), 4u);
  // A cube with points on its faces and edges keeps only the 8 corners.
  std::vector<Vec3> cube;
  for (int i = 0; i < 27; ++i) cube.push_back({double(i % 3) - 1, double(i / 3 % 3) - 1, double(i / 9) - 1});
  const ConvexHull h = convex_hull(cube);
  EXPECT_EQ(h.vertices.size(), 8u);
  EXPECT_TRUE(h.manifold);
  // Its 12 triangles merge into 6 square facets, outward, each next to 4 others
  // (never to itself or its opposite face).
  ASSERT_EQ(h.facets.size(), 6u);
  for (std::size_t f = 0; f < 6; ++f) {
    ASSERT_EQ(h.facet_neighbors[f].size(), 4u);
    for (int g : h.facet_neighbors[f]) {
      ASSERT_GE(g, 0);
      EXPECT_NEAR(dot(h.facet_normals[f], h.facet_normals[g]), 0.0, 1e-15);
    }
  }
  for (std::size_t f = 0; f < h.facets.size(); ++f) {
    EXPECT_EQ(h.facets[f].size(), 4u);
    EXPECT_NEAR(max_abs(h.facet_normals[f]), 1.0, 1e-15);
    const Vec3 c = (h.vertices[h.facets[f][0]] + h.vertices[h.facets[f][2]]) * 0.5;
    EXPECT_NEAR(dot(c, h.facet_normals[f]), 1.0, 1e-15);  // centre of the face, outward
  }
}

TEST(ConvexHull2d, RandomAndDegenerateSets) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 0; c < 50; ++c) {
    std::vector<Vec2> pts;
    for (int i = 0; i < 3 + c; ++i) pts.push_back({u(rng), u(rng)});
    pts.push_back(pts[0]);                            // a duplicate
    pts.push_back((pts[1] + pts[2]) * 0.5);            // a point between two others
    const std::vector<int> h = convex_hull_2d(pts);
    ASSERT_GE(h.size(), 3u);
    for (std::size_t e = 0; e < h.size(); ++e) {
      const Vec2 a = pts[h[e]], b = pts[h[(e + 1) % h.size()]];
      for (const Vec2& p : pts) EXPECT_GE(cross(b - a, p - a), -1e-15);  // everything on the left: CCW, enclosed
    }
  }
  // Collinear points: the two ends; a square with edge midpoints: its corners.
  EXPECT_EQ(convex_hull_2d(std::vector<Vec2>{{0, 0}, {1, 1}, {2, 2}, {3, 3}}).size(), 2u);
  EXPECT_EQ(convex_hull_2d(std::vector<Vec2>{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}).size(), 4u);
  EXPECT_EQ(convex_hull_2d(std::vector<Vec2>{{5, 5}}).size(), 1u);
}

}  // namespace
}  // namespace gjkdem
