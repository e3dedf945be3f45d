// The batched triangle-pair kernel: against the brute-force oracle on random
// pairs, against constructed gaps (vertex over face, edge against edge, nearly
// parallel faces) down to 1e-12, on degenerate triangles, and the same bits on
// every instruction set and in the one-pair query.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "gjkdem/collide/triangle_contact.hpp"
#include "oracle/distance_oracle.hpp"

namespace gjkdem {
namespace {

struct Tri {
  Vec3 p[3];
};
struct Pair {
  Tri a, b;
};

std::vector<TriangleDistanceBlock> run(const std::vector<Pair>& pairs, TriangleSimd simd = TriangleSimd::Best) {
  TrianglePairs in;
  for (const Pair& q : pairs) in.push_back(q.a.p[0], q.a.p[1], q.a.p[2], q.b.p[0], q.b.p[1], q.b.p[2]);
  std::vector<TriangleDistanceBlock> out;
  triangle_distances(in, out, simd);
  return out;
}

Real distance_of(const std::vector<TriangleDistanceBlock>& out, std::size_t i) {
  return out[i / kTriangleLanes].distance[i % kTriangleLanes];
}
Vec3 witness(const Real (&w)[3][kTriangleLanes], std::size_t lane) { return {w[0][lane], w[1][lane], w[2][lane]}; }

// Distance from p to triangle t (the oracle's closest point, its own code).
Real point_triangle(const Vec3& p, const Tri& t) {
  return length(oracle::closest_on_triangle(t.p[0] - p, t.p[1] - p, t.p[2] - p));
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return normalized(Vec3{g(rng), g(rng), g(rng)});
}

TEST(TrianglePairs, RandomPairsMatchTheBruteForceOracleWithWitnessesOnTheTriangles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Pair> pairs;
  std::vector<double> sizes;
  for (int k = 0; k < 600; ++k) {
    const double scale = std::pow(10.0, (k % 7) - 3);  // 1e-3 .. 1e3
    const Vec3 base = Vec3{u(rng), u(rng), u(rng)} * 1e5 * (k % 2);  // half of them far from the origin
    const Vec3 off = Vec3{u(rng), u(rng), u(rng)} * 0.9 * scale;
    Pair q;
    for (Vec3& p : q.a.p) p = base + Vec3{u(rng), u(rng), u(rng)} * scale;
    for (Vec3& p : q.b.p) p = base + off + Vec3{u(rng), u(rng), u(rng)} * scale;
    pairs.push_back(q);
    sizes.push_back(scale);
  }
  const auto out = run(pairs);
  int crossing = 0, apart = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& q = pairs[i];
    const Vec3 base = q.a.p[0];  // the oracle works on differences: take them near the origin
    std::vector<Vec3> la, lb;
    for (const Vec3& p : q.a.p) la.push_back(p - base);
    for (const Vec3& p : q.b.p) lb.push_back(p - base);
    const auto truth = oracle::brute_force_pair(oracle::minkowski_difference(la, lb));
    const double d = truth.intersect ? 0.0 : truth.distance;
    // Coordinates 1e5 carry round-off of 1e5 * 2^-53 ~ 1e-11 before any query.
    const double tol = 1e-12 * sizes[i] + (length(base) > 1 ? 1e-10 : 0);
    const double got = distance_of(out, i);
    ASSERT_NEAR(got, d, tol) << "pair " << i;
    const std::size_t lane = i % kTriangleLanes;
    const Vec3 wa = witness(out[i / kTriangleLanes].witness_a, lane), wb = witness(out[i / kTriangleLanes].witness_b, lane);
    EXPECT_NEAR(length(wb - wa), got, tol) << "pair " << i;
    EXPECT_LT(point_triangle(wa, q.a), tol) << "pair " << i;
    EXPECT_LT(point_triangle(wb, q.b), tol) << "pair " << i;
    crossing += truth.intersect;
    apart += !truth.intersect;
  }
  EXPECT_GT(crossing, 60);
  EXPECT_GT(apart, 300);
}

// Pairs whose distance is known by construction: a corner of B above a point
// inside A, the rest of B farther; two skew edges with their closest points
// inside both, the triangles opening away from each other; nearly parallel
// faces tilted by up to 1e-2 with the nearest corner given.
TEST(TrianglePairs, ConstructedGapsDownTo1e12AreFound) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Pair> pairs;
  std::vector<double> gaps;
  for (int k = 0; k < 900; ++k) {
    const double gap = std::pow(10.0, -12 + 11 * u(rng));
    const Vec3 n = random_unit(rng);
    Vec3 t1, t2;
    orthonormal_basis(n, t1, t2);
    const Vec3 base = Vec3{u(rng), u(rng), u(rng)} * 10;
    Pair q;
    if (k % 3 == 0) {  // corner over face
      q.a.p[0] = base + t1 * -1 + t2 * -1;
      q.a.p[1] = base + t1 * 1.5 + t2 * -0.5;
      q.a.p[2] = base + t1 * -0.5 + t2 * 1.5;
      const Vec3 apex = base + t1 * (0.3 * u(rng) - 0.15) + t2 * (0.3 * u(rng) - 0.15) + n * gap;
      q.b.p[0] = apex;
      q.b.p[1] = apex + n * (0.2 + u(rng)) + t1 * (u(rng) - 0.5);
      q.b.p[2] = apex + n * (0.2 + u(rng)) + t2 * (u(rng) - 0.5);
    } else if (k % 3 == 1) {  // edge against edge: A's edge along t1 at 0, B's along t2 at gap n
      const double s = u(rng) - 0.5, t = u(rng) - 0.5;
      q.a.p[0] = base + t1 * (s - 0.7);
      q.a.p[1] = base + t1 * (s + 0.6);
      q.a.p[2] = base + t2 * (u(rng) - 0.5) - n * (0.3 + u(rng));  // opens below
      q.b.p[0] = base + n * gap + t2 * (t - 0.8);
      q.b.p[1] = base + n * gap + t2 * (t + 0.5);
      q.b.p[2] = base + n * (gap + 0.3 + u(rng)) + t1 * (u(rng) - 0.5);  // opens above
    } else {  // nearly parallel faces: B tilted by up to 1e-2 about t2, nearest corner over A
      const double tilt = (k % 2) ? 0.0 : std::pow(10.0, -9 + 7 * u(rng));
      const Vec3 m1 = normalized(t1 + n * tilt);  // in B's plane, rising away from A
      q.a.p[0] = base + t1 * -2 + t2 * -2;
      q.a.p[1] = base + t1 * 3 + t2 * -1;
      q.a.p[2] = base + t1 * -1 + t2 * 3;
      // B's corner nearest A is `low`: the others lie along +m1 and t2, higher.
      const Vec3 low = base + n * gap;
      q.b.p[0] = low;
      q.b.p[1] = low + m1 * 0.8 + t2 * 0.2;
      q.b.p[2] = low + m1 * 0.3 + t2 * 0.7;
    }
    pairs.push_back(q);
    gaps.push_back(gap);
  }
  const auto out = run(pairs);
  for (std::size_t i = 0; i < pairs.size(); ++i)
    ASSERT_NEAR(distance_of(out, i), gaps[i], 2e-15 * 16) << "pair " << i << " (kind " << i % 3 << ")";
}

TEST(TrianglePairs, DegenerateTrianglesTouchingAndCoplanarPairs) {
  const Vec3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  struct Case {
    Vec3 a0, a1, a2, b0, b1, b2;
    double d;
  };
  const std::vector<Case> cases = {
      {o, x, y, o, x, y, 0},                                  // the same triangle
      {o, x, y, x, {1, 1, 0}, y, 0},                          // sharing an edge, coplanar
      {o, x, y, x, {2, 0, 0}, {1, 0, 1}, 0},                  // sharing a corner only
      {o, x, y, {0.2, 0.2, 0}, {0.5, 0.2, 0}, {0.2, 0.5, 0}, 0},  // coplanar, one inside the other
      {o, x, y, {2, 0, 0}, {3, 0, 0}, {2, 1, 0}, 1},          // coplanar, apart
      {o, x, y, {0.2, 0.2, 0.5}, {0.2, 0.2, 0.5}, {0.2, 0.2, 0.5}, 0.5},  // a point over the face
      {o, x, y, {2, 0, 0}, {2, 0, 0}, {2, 0, 0}, 1},          // a point off a corner
      {o, x, x, {0.5, -1, 1}, {0.5, 1, 1}, {0.5, 1, 1}, 1},   // two segments, skew
      {o, x, x, {0, 1, 0}, {1, 1, 0}, {1, 1, 0}, 1},          // two parallel segments
      {o, o, o, o, o, o, 0},                                  // two equal points
      {o, x, y, {0.25, 0.25, -1}, {0.25, 0.25, 1}, {3, 3, 3}, 0},  // an edge through the face
      {o, x, y, {-1, 0.25, 0.5}, {2, 0.25, 0.5}, {0.25, 0.25, -0.5}, 0},  // A's edge crosses B
      {o, x, z, {0.5, -1, 0.25}, {0.5, 1, 0.25}, {0.5, 0, -2}, 0},  // pierce each other
  };
  std::vector<Pair> pairs;
  for (const Case& c : cases) pairs.push_back({{c.a0, c.a1, c.a2}, {c.b0, c.b1, c.b2}});
  const auto out = run(pairs);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_NEAR(distance_of(out, i), cases[i].d, 1e-15) << "case " << i;
    const Case& c = cases[i];
    const TriangleContact one = triangle_contact(c.a0, c.a1, c.a2, c.b0, c.b1, c.b2, 0);
    EXPECT_EQ(one.status, cases[i].d == 0 ? GjkStatus::Intersecting : GjkStatus::Separated) << "case " << i;
    EXPECT_TRUE(std::isfinite(witness(out[i / kTriangleLanes].witness_a, i % kTriangleLanes).x)) << "case " << i;
  }
}

TEST(TrianglePairs, SwappedAndMovedPairsAgree) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Pair> pairs, swapped, moved;
  const Vec3 shift{1e5, -3e4, 7e4};
  for (int k = 0; k < 400; ++k) {
    Pair q;
    const Vec3 off = Vec3{u(rng), u(rng), u(rng)} * 1.5;
    for (Vec3& p : q.a.p) p = Vec3{u(rng), u(rng), u(rng)};
    for (Vec3& p : q.b.p) p = off + Vec3{u(rng), u(rng), u(rng)};
    pairs.push_back(q);
    swapped.push_back({q.b, q.a});
    Pair m = q;
    for (Vec3& p : m.a.p) p = p + shift;
    for (Vec3& p : m.b.p) p = p + shift;
    moved.push_back(m);
  }
  const auto out = run(pairs), out_swapped = run(swapped), out_moved = run(moved);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_NEAR(distance_of(out_swapped, i), distance_of(out, i), 1e-14) << "pair " << i;
    EXPECT_NEAR(distance_of(out_moved, i), distance_of(out, i), 1e-10) << "pair " << i;  // 1e5 * 2^-53 per coordinate
  }
}

// Candidates multiply up to four lengths: in metres, 1e-80 m triangles would
// underflow and 1e80 m ones overflow. The kernel works in units of each
// pair's extent, so the answers scale with the pairs from 1e-150 to 1e150.
TEST(TrianglePairs, AnswersScaleWithThePairsAtAnySize) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Pair> pairs;
  for (int k = 0; k < 200; ++k) {
    Pair q;
    const Vec3 off = Vec3{u(rng), u(rng), u(rng)} * 1.2;
    for (Vec3& p : q.a.p) p = Vec3{u(rng), u(rng), u(rng)};
    for (Vec3& p : q.b.p) p = off + Vec3{u(rng), u(rng), u(rng)};
    pairs.push_back(q);
  }
  const auto unit = run(pairs);
  for (const double scale : {1e-150, 1e-80, 1e-20, 1e20, 1e80, 1e150}) {
    std::vector<Pair> scaled = pairs;
    for (Pair& q : scaled)
      for (Tri* t : {&q.a, &q.b})
        for (Vec3& p : t->p) p = p * scale;
    const auto out = run(scaled);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const double want = distance_of(unit, i) * scale, got = distance_of(out, i);
      ASSERT_TRUE(std::isfinite(got)) << "scale " << scale << " pair " << i;
      ASSERT_NEAR(got, want, 1e-13 * scale) << "scale " << scale << " pair " << i;
      const Vec3 wa = witness(out[i / kTriangleLanes].witness_a, i % kTriangleLanes);
      EXPECT_LT(length(wa - witness(unit[i / kTriangleLanes].witness_a, i % kTriangleLanes) * scale), 1e-12 * scale)
          << "scale " << scale << " pair " << i;
    }
  }
}

TEST(TrianglePairs, EveryInstructionSetAndTheOnePairQueryGiveTheSameBits) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Pair> pairs;
  for (int k = 0; k < 203; ++k) {  // not a multiple of the block: padding lanes too
    Pair q;
    const Vec3 off = Vec3{u(rng), u(rng), u(rng)} * (k % 4 == 0 ? 0.0 : 1.5);
    for (Vec3& p : q.a.p) p = Vec3{u(rng), u(rng), u(rng)};
    for (Vec3& p : q.b.p) p = off + Vec3{u(rng), u(rng), u(rng)};
    if (k % 10 == 0) q.b.p[2] = q.b.p[1];  // some segments
    pairs.push_back(q);
  }
  const auto sse2 = run(pairs, TriangleSimd::Sse2);
  ASSERT_EQ(sse2.size(), (pairs.size() + kTriangleLanes - 1) / kTriangleLanes);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& q = pairs[i];
    const TriangleContact one = triangle_contact(q.a.p[0], q.a.p[1], q.a.p[2], q.b.p[0], q.b.p[1], q.b.p[2], 0);
    const std::size_t lane = i % kTriangleLanes;
    const TriangleDistanceBlock& b = sse2[i / kTriangleLanes];
    EXPECT_EQ(one.distance, b.distance[lane]) << "pair " << i;
    EXPECT_TRUE(one.witness_a == witness(b.witness_a, lane)) << "pair " << i;
    EXPECT_TRUE(one.witness_b == witness(b.witness_b, lane)) << "pair " << i;
  }
  int wide = 0;
  for (TriangleSimd simd : {TriangleSimd::Avx2, TriangleSimd::Avx512, TriangleSimd::Best}) {
    if (!triangle_simd_available(simd)) continue;
    const auto other = run(pairs, simd);
    ASSERT_EQ(other.size(), sse2.size());
    EXPECT_EQ(std::memcmp(other.data(), sse2.data(), sse2.size() * sizeof(TriangleDistanceBlock)), 0)
        << "instruction set " << static_cast<int>(simd);
    wide += simd != TriangleSimd::Best;
  }
  if (wide == 0) GTEST_SKIP() << "no AVX2 or AVX-512 on this processor: SSE2 only";
}

}  // namespace
}  // namespace gjkdem
