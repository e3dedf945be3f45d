// The seed's triangle-pair query against the brute-force oracle, with margins.
#include "gjkdem/collide/triangle_contact.hpp"

#include <gtest/gtest.h>

#include <random>

#include "oracle/distance_oracle.hpp"

namespace gjkdem {
namespace {

TEST(TriangleContact, RandomPairsMatchBruteForce) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, in_margin = 0;
  for (int k = 0; k < 400; ++k) {
    const Vec3 base = Vec3{u(rng), u(rng), u(rng)} * 1e5;  // far from the origin
    const Vec3 off = Vec3{u(rng), u(rng), u(rng)} * 1.2;
    const std::vector<Vec3> t1 = {base + Vec3{u(rng), u(rng), u(rng)}, base + Vec3{u(rng), u(rng), u(rng)},
                                  base + Vec3{u(rng), u(rng), u(rng)}};
    const std::vector<Vec3> t2 = {base + off + Vec3{u(rng), u(rng), u(rng)}, base + off + Vec3{u(rng), u(rng), u(rng)},
                                  base + off + Vec3{u(rng), u(rng), u(rng)}};
    // The oracle works on differences, which do not depend on the offset.
    std::vector<Vec3> l1, l2;
    for (const Vec3& p : t1) l1.push_back(p - base);
    for (const Vec3& p : t2) l2.push_back(p - base);
    const auto truth = oracle::brute_force_pair(oracle::minkowski_difference(l1, l2));
    const double rho = 0.1;
    const TriangleContact r = triangle_contact(t1[0], t1[1], t1[2], t2[0], t2[1], t2[2], rho);
    const double d = truth.intersect ? 0.0 : truth.distance;
    EXPECT_NEAR(r.distance, d, 1e-9) << "case " << k;
    if (std::fabs(d - rho) > 1e-9 && d > 1e-9) {
      EXPECT_EQ(r.contact, d <= rho) << "case " << k;
    }
    hits += truth.intersect;
    in_margin += !truth.intersect && d <= rho;
    if (!r.contact || r.distance == 0) continue;
    EXPECT_NEAR(length(r.witness_b - r.witness_a), r.distance, 1e-9);
  }
  EXPECT_GT(hits, 20);       // crossing triangles,
  EXPECT_GT(in_margin, 10);  // triangles within the margin only,
  EXPECT_LT(hits + in_margin, 380);  // and triangles apart all occur
}

TEST(TriangleContact, ParallelTrianglesUseTheMargin) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const Vec3 lift{0.2, 0.2, 0.05};
  EXPECT_TRUE(triangle_contact(a, b, c, a + lift, b + lift, c + lift, 0.06).contact);
  EXPECT_FALSE(triangle_contact(a, b, c, a + lift, b + lift, c + lift, 0.04).contact);
  EXPECT_NEAR(triangle_contact(a, b, c, a + lift, b + lift, c + lift, 0).distance, 0.05, 1e-12);
  // Coplanar overlapping triangles touch (distance 0) whatever the margin.
  const Vec3 slide{0.2, 0.2, 0};
  EXPECT_TRUE(triangle_contact(a, b, c, a + slide, b + slide, c + slide, 0).contact);
}

}  // namespace
}  // namespace gjkdem
