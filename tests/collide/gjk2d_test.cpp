// Planar GJK: the seed text's walk-through (its Figures A.8 to A.10: first
// iteration, second iteration, a backtrack that resets simplex and direction,
// then the iteration that encloses the origin), and distance/depth against a
// brute-force reference on random polygons.
#include "gjkdem/collide/gjk2d.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace gjkdem {
namespace {

void expect_vec(const Vec2& got, const Vec2& want) {
  EXPECT_DOUBLE_EQ(got.x, want.x);
  EXPECT_DOUBLE_EQ(got.y, want.y);
}

// Every number below was derived by hand from Algorithm 14 (support(d) =
// support_A(d) - support_B(-d); perpendiculars (X x Y) x Z):
//  1. d = (1,0): A gives (6,6), B gives (-5,4): p = (11,2); simplex {(11,2)}, d = -p.
//  2. d = (-11,-2): A gives (0,-4), B gives (4,6): p = (-4,-10). The origin lies
//     beyond the segment's end (AB.AO = 180 > 0), so d = (AB x AO) x AB = (-1224,1530).
//  3. d ~ (-4,5): A gives (1,5), B gives (-2,-2): p = (3,7). The triangle misses the
//     origin: the perpendicular of edge (3,7)-(-4,-10) points at it (dot 342 > 0),
//     so the algorithm backtracks: (11,2) is dropped and d = (-2907,1197).
//  4. d ~ (-17,7): A gives (1,5), B gives (4,6): p = (-3,-1). Both edge tests are
//     negative (-828, -1196): the triangle encloses the origin, contact found.
TEST(Gjk2d, SeedWalkThroughBacktracksThenEncloses) {
  const std::vector<Vec2> a = {{0, -4}, {1, 5}, {6, 6}, {6, -5}};
  const std::vector<Vec2> b = {{-5, 4}, {4, 6}, {-2, -2}};
  std::vector<Gjk2dStep> trace;
  EXPECT_TRUE(intersect2d({a}, {b}, {1, 0}, &trace));
  ASSERT_EQ(trace.size(), 4u);
  expect_vec(trace[0].support, {11, 2});
  ASSERT_EQ(trace[0].simplex.size(), 1u);
  expect_vec(trace[1].direction, {-11, -2});
  expect_vec(trace[1].support, {-4, -10});
  ASSERT_EQ(trace[1].simplex.size(), 2u);
  expect_vec(trace[2].direction, {-1224, 1530});
  expect_vec(trace[2].support, {3, 7});
  ASSERT_EQ(trace[2].simplex.size(), 2u);  // the backtrack
  expect_vec(trace[2].simplex[0], {-4, -10});
  expect_vec(trace[2].simplex[1], {3, 7});
  expect_vec(trace[3].direction, {-2907, 1197});
  expect_vec(trace[3].support, {-3, -1});
  ASSERT_EQ(trace[3].simplex.size(), 3u);
  EXPECT_TRUE(trace[3].enclosed);
  EXPECT_FALSE(trace[2].enclosed);
}

TEST(Gjk2d, SeparatedPairStopsAtFirstSeparatingDirection) {
  const std::vector<Vec2> a = {{0, 0}, {1, 0}, {0, 1}};
  const std::vector<Vec2> b = {{3, 0}, {4, 0}, {3, 1}};
  std::vector<Gjk2dStep> trace;
  EXPECT_FALSE(intersect2d({a}, {b}, {1, 0}, &trace));
  EXPECT_LE(trace.size(), 2u);
}

struct Truth2d {
  bool intersect;
  double value;  // distance or depth
};

// Brute force over all difference points: a segment whose line supports every
// point gives the distance (origin outside) or bounds the depth (inside).
Truth2d brute_force(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  std::vector<Vec2> d;
  for (const Vec2& p : a)
    for (const Vec2& q : b) d.push_back(p - q);
  double best_out = std::numeric_limits<double>::infinity(), best_in = best_out;
  bool outside = false;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t j = 0; j < d.size(); ++j) {
      const Vec2 e = d[j] - d[i];
      const double len = length(e);
      if (!(len > 1e-12)) continue;
      const Vec2 n{e.y / len, -e.x / len};
      const double off = dot(n, d[i]);
      bool supports = true;
      for (const Vec2& p : d) supports &= dot(n, p) <= off + 1e-12;
      if (!supports) continue;
      if (off < 0) {  // origin outside this edge: distance to the segment
        outside = true;
        double u = -dot(d[i], e) / (len * len);
        u = u < 0 ? 0 : (u > 1 ? 1 : u);
        best_out = std::fmin(best_out, length(d[i] + e * u));
      } else {
        best_in = std::fmin(best_in, off);
      }
    }
  return outside ? Truth2d{false, best_out} : Truth2d{true, best_in};
}

TEST(Gjk2d, RandomPolygonsMatchBruteForce) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int c = 0; c < 300; ++c) {
    std::vector<Vec2> a, b;
    for (int i = 0; i < 3 + c % 8; ++i) a.push_back({u(rng), u(rng)});
    const Vec2 off{1.5 * u(rng), 1.5 * u(rng)};
    for (int i = 0; i < 3 + c % 5; ++i) b.push_back(Vec2{u(rng), u(rng)} + off);
    const Truth2d t = brute_force(a, b);
    const Penetration2dResult r = penetration2d({a}, {b});
    ASSERT_EQ(r.intersect, t.intersect) << "case " << c;
    EXPECT_EQ(intersect2d({a}, {b}, {1, 0}), t.intersect) << "case " << c;
    hits += t.intersect;
    if (t.intersect) {
      EXPECT_NEAR(r.depth, t.value, 1e-10) << "case " << c;
      EXPECT_NEAR(length(r.witness_a - r.witness_b), r.depth, 1e-10);
    } else {
      EXPECT_NEAR(r.distance, t.value, 1e-10) << "case " << c;
      EXPECT_NEAR(length(r.witness_b - r.witness_a), r.distance, 1e-10);
    }
  }
  EXPECT_GT(hits, 60);
  EXPECT_LT(hits, 240);
}

}  // namespace
}  // namespace gjkdem
