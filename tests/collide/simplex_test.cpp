// The signed-volume sub-algorithm against the independent Voronoi-region
// closest point of tests/oracle.
#include "gjkdem/collide/simplex.hpp"

#include <gtest/gtest.h>

#include <random>

#include "oracle/distance_oracle.hpp"

namespace gjkdem {
namespace {

Simplex make_simplex(std::initializer_list<Vec3> pts) {
  Simplex s;
  for (const Vec3& p : pts) s.p[s.size++] = {p, p, {}, {}};
  return s;
}

TEST(Simplex, TrianglesMatchOracle) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 0; c < 2000; ++c) {
    const Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)};
    // Every tenth triangle is degenerate (collinear).
    const Vec3 cc = c % 10 == 0 ? a + (b - a) * u(rng) : Vec3{u(rng), u(rng), u(rng)};
    Simplex s = make_simplex({a, b, cc});
    const Vec3 v = reduce_to_closest(s);
    const Vec3 ref = oracle::closest_on_triangle(a, b, cc);
    EXPECT_NEAR(length(v), length(ref), 1e-12) << "case " << c;
    Vec3 wa, wb;
    simplex_witnesses(s, wa, wb);
    EXPECT_NEAR(length(wa - v), 0.0, 1e-12);
  }
}

TEST(Simplex, TetrahedraMatchOracle) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int inside = 0;
  for (int c = 0; c < 2000; ++c) {
    const Vec3 p[4] = {{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    Simplex s = make_simplex({p[0], p[1], p[2], p[3]});
    const Vec3 v = reduce_to_closest(s);
    double ref = 1e300;
    for (int m = 0; m < 4; ++m)
      ref = std::fmin(ref, length(oracle::closest_on_triangle(p[(m + 1) % 4], p[(m + 2) % 4], p[(m + 3) % 4])));
    if (s.size == 4) {
      ++inside;
      // Origin inside: barycentric weights positive and summing to one.
      double sum = 0;
      for (int m = 0; m < 4; ++m) { EXPECT_GT(s.lambda[m], 0); sum += s.lambda[m]; }
      EXPECT_NEAR(sum, 1.0, 1e-12);
    } else {
      EXPECT_NEAR(length(v), ref, 1e-12) << "case " << c;
    }
  }
  EXPECT_GT(inside, 50);
  EXPECT_LT(inside, 1000);
}

}  // namespace
}  // namespace gjkdem
