// Narrow-phase queries against brute-force references (tests/oracle), closed
// forms and metamorphic relations.
#include "gjkdem/collide/query.hpp"

#include <gtest/gtest.h>

#include <random>

#include "oracle/distance_oracle.hpp"

namespace gjkdem {
namespace {

struct RandomPolytope {
  std::vector<Vec3> world;  // vertices in world coordinates
  Shape shape;
  Transform pose;
};

RandomPolytope random_polytope(std::mt19937_64& rng, int n, const Vec3& centre, double size) {
  std::uniform_real_distribution<double> u(-1, 1);
  RandomPolytope p;
  std::vector<Vec3> local;
  for (int i = 0; i < n; ++i) local.push_back(Vec3{u(rng), u(rng), u(rng)} * (size / 2));
  p.pose = Transform::from(centre, normalized(Quat{u(rng), u(rng), u(rng), u(rng)}));
  for (const Vec3& v : local) p.world.push_back(apply(p.pose, v));
  p.shape.core = make_polytope(local);
  return p;
}

// The support value of A - B along unit n, from the world vertex lists.
double support_of_difference(const RandomPolytope& a, const RandomPolytope& b, const Vec3& n) {
  double ha = -1e300, hb = -1e300;
  for (const Vec3& v : a.world) ha = std::fmax(ha, dot(v, n));
  for (const Vec3& v : b.world) hb = std::fmax(hb, dot(v, -n));
  return ha + hb;
}

TEST(Query, RandomPolytopePairsMatchBruteForce) {
  const std::uint64_t seed = 20261122;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, cases = 0;
  for (int c = 0; c < 300; ++c) {
    SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(c));
    const double size = std::pow(10.0, 2 * u(rng));  // 0.01 .. 100
    const Vec3 base = Vec3{u(rng), u(rng), u(rng)} * (50 * size);
    const RandomPolytope a = random_polytope(rng, 4 + c % 6, base, size);
    const RandomPolytope b = random_polytope(rng, 4 + (c / 6) % 6, base + Vec3{u(rng), u(rng), u(rng)} * (0.45 * size), size);
    const auto truth = oracle::brute_force_pair(oracle::minkowski_difference(a.world, b.world));
    const PenetrationResult r = penetration(a.shape, a.pose, b.shape, b.pose);
    const double tol = 1e-9 * size + 1e-14 * 50 * size;
    const double truth_gap = truth.intersect ? truth.depth : truth.distance;
    ++cases;
    hits += truth.intersect;
    if (truth_gap > tol) { ASSERT_EQ(r.intersect, truth.intersect); }
    EXPECT_NEAR(r.distance, truth.intersect ? 0.0 : truth.distance, tol);
    EXPECT_NEAR(r.depth, truth.intersect ? truth.depth : 0.0, tol);
    EXPECT_NEAR(length(r.normal), 1.0, 1e-12);
    if (r.intersect) {
      // Certificate: translating B by depth * normal must be a shortest separating move.
      EXPECT_NEAR(support_of_difference(a, b, r.normal), r.depth, tol);
      EXPECT_NEAR(length(r.witness_a - r.witness_b), r.depth, tol);
    } else {
      EXPECT_NEAR(length(r.witness_b - r.witness_a), r.distance, tol);
      // Witnesses are the extreme points of A and B along the normal.
      EXPECT_NEAR(support_of_difference(a, b, r.normal), -r.distance, tol);
    }
    // The boolean test and the distance query agree with the full query.
    if (truth_gap > tol) {
      EXPECT_EQ(intersect(a.shape, a.pose, b.shape, b.pose), truth.intersect);
      const DistanceResult d = distance(a.shape, a.pose, b.shape, b.pose);
      EXPECT_EQ(d.intersect, truth.intersect);
      if (!d.intersect) { EXPECT_NEAR(d.distance, truth.distance, tol); }
    }
  }
  // The generator must exercise both outcomes, or the test passes vacuously.
  EXPECT_GT(hits, cases * 3 / 10);
  EXPECT_LT(hits, cases * 7 / 10);
}

TEST(Query, SpheresHaveClosedForm) {
  const Shape a = make_sphere(1.5), b = make_sphere(0.5);
  const Transform pa = Transform::from({1, 2, 3}, {}), pb = Transform::from({1, 2, 3 + 3.0}, {});
  const PenetrationResult sep = penetration(a, pa, b, pb);
  EXPECT_FALSE(sep.intersect);
  EXPECT_NEAR(sep.distance, 1.0, 1e-12);
  EXPECT_NEAR(sep.normal.z, 1.0, 1e-12);
  EXPECT_NEAR(sep.witness_a.z, 4.5, 1e-12);
  EXPECT_NEAR(sep.witness_b.z, 5.5, 1e-12);
  const Transform pc = Transform::from({1, 2 + 1.2, 3}, {});
  const PenetrationResult pen = penetration(a, pa, b, pc);
  EXPECT_TRUE(pen.intersect);
  EXPECT_NEAR(pen.depth, 0.8, 1e-12);
  EXPECT_NEAR(pen.normal.y, 1.0, 1e-12);
  // Concentric spheres: depth is the sum of radii whatever the normal.
  const PenetrationResult same = penetration(a, pa, b, pa);
  EXPECT_TRUE(same.intersect);
  EXPECT_NEAR(same.depth, 2.0, 1e-12);
}

TEST(Query, BoxesFaceToFace) {
  const Shape box{Box{{0.5, 0.5, 0.5}}};
  const Transform pa = Transform::identity();
  for (double gap : {0.25, 1e-6, 0.0, -1e-6, -0.3}) {
    SCOPED_TRACE(gap);
    const Transform pb = Transform::from({1.0 + gap, 0.2, -0.1}, {});
    const PenetrationResult r = penetration(box, pa, box, pb);
    if (gap > 0) {
      EXPECT_FALSE(r.intersect);
      EXPECT_NEAR(r.distance, gap, 1e-12);
    } else {
      EXPECT_TRUE(r.intersect);
      EXPECT_NEAR(r.depth, -gap, 1e-12);
    }
    if (gap != 0) { EXPECT_NEAR(r.normal.x, 1.0, 1e-9); }
    EXPECT_EQ(intersect(box, pa, box, pb), gap <= 0);
  }
  // Coincident boxes: depth is the full width, along one of the axes.
  const PenetrationResult same = penetration(box, pa, box, pa);
  EXPECT_TRUE(same.intersect);
  EXPECT_NEAR(same.depth, 1.0, 1e-12);
  EXPECT_NEAR(max_abs(same.normal), 1.0, 1e-12);
}

TEST(Query, CapsulesAndMarginsAreExact) {
  // Parallel capsules along x, 2 apart in y, radii 0.3 and 0.4: distance 1.3.
  const Shape a = make_capsule({-1, 0, 0}, {1, 0, 0}, 0.3), b = make_capsule({-1, 0, 0}, {1, 0, 0}, 0.4);
  const PenetrationResult r = penetration(a, Transform::identity(), b, Transform::from({0.5, 2, 0}, {}));
  EXPECT_NEAR(r.distance, 1.3, 1e-12);
  EXPECT_NEAR(r.normal.y, 1.0, 1e-12);
  // Rounded box against a plain box, overlapping only through the margin.
  const Shape rounded{Box{{1, 1, 1}}, 0.2}, plain{Box{{1, 1, 1}}};
  const PenetrationResult m = penetration(rounded, Transform::identity(), plain, Transform::from({0, 0, 2.15}, {}));
  EXPECT_TRUE(m.intersect);
  EXPECT_NEAR(m.depth, 0.05, 1e-12);
  EXPECT_NEAR(m.normal.z, 1.0, 1e-12);
}

TEST(Query, SwapNegatesNormalAndSwapsWitnesses) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 0; c < 50; ++c) {
    const RandomPolytope a = random_polytope(rng, 8, {0, 0, 0}, 1);
    const RandomPolytope b = random_polytope(rng, 8, Vec3{u(rng), u(rng), u(rng)}, 1);
    const PenetrationResult ab = penetration(a.shape, a.pose, b.shape, b.pose);
    const PenetrationResult ba = penetration(b.shape, b.pose, a.shape, a.pose);
    ASSERT_EQ(ab.intersect, ba.intersect);
    EXPECT_NEAR(ab.distance, ba.distance, 1e-12);
    EXPECT_NEAR(ab.depth, ba.depth, 1e-12);
    EXPECT_NEAR(dot(ab.normal, ba.normal), -1.0, 1e-9);
  }
}

TEST(Query, RigidMotionAndScaleInvariance) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 0; c < 50; ++c) {
    std::vector<Vec3> pa, pb;
    for (int i = 0; i < 10; ++i) pa.push_back({u(rng), u(rng), u(rng)});
    for (int i = 0; i < 10; ++i) pb.push_back({u(rng), u(rng), u(rng)});
    const Shape a{make_polytope(pa)}, b{make_polytope(pb)};
    const Transform ta = Transform::identity(), tb = Transform::from({u(rng) * 2, u(rng) * 2, u(rng) * 2}, {});
    const PenetrationResult base = penetration(a, ta, b, tb);
    // A common rigid motion (large offset included) changes nothing but frames.
    const Transform motion = Transform::from({1e6, -2e5, 3e5}, normalized(Quat{u(rng), u(rng), u(rng), u(rng)}));
    const Transform ma{motion.rotation * ta.rotation, apply(motion, ta.translation)};
    const Transform mb{motion.rotation * tb.rotation, apply(motion, tb.translation)};
    const PenetrationResult moved = penetration(a, ma, b, mb);
    ASSERT_EQ(base.intersect, moved.intersect);
    EXPECT_NEAR(base.distance, moved.distance, 1e-9);
    EXPECT_NEAR(base.depth, moved.depth, 1e-9);
    // A uniform scale scales distance and depth.
    std::vector<Vec3> sa, sb;
    for (const Vec3& p : pa) sa.push_back(p * 1e-3);
    for (const Vec3& p : pb) sb.push_back(p * 1e-3);
    const Transform tbs = Transform::from(tb.translation * 1e-3, {});
    const PenetrationResult scaled = penetration(Shape{make_polytope(sa)}, ta, Shape{make_polytope(sb)}, tbs);
    ASSERT_EQ(base.intersect, scaled.intersect);
    EXPECT_NEAR(base.distance * 1e-3, scaled.distance, 1e-14);
    EXPECT_NEAR(base.depth * 1e-3, scaled.depth, 1e-14);
  }
}

TEST(Query, TranslatingAlongNormalFlipsIntersect) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 0; c < 50; ++c) {
    const RandomPolytope a = random_polytope(rng, 8, {0, 0, 0}, 1);
    const RandomPolytope b = random_polytope(rng, 8, Vec3{u(rng), u(rng), u(rng)} * 0.7, 1);
    const PenetrationResult r = penetration(a.shape, a.pose, b.shape, b.pose);
    const double gap = r.intersect ? r.depth : -r.distance;  // move B by gap along the normal to touch
    for (double eps : {1e-6, -1e-6}) {
      const Transform moved{b.pose.rotation, b.pose.translation + r.normal * (gap + eps)};
      EXPECT_EQ(intersect(a.shape, a.pose, b.shape, moved), eps < 0) << "case " << c << " eps " << eps;
    }
  }
}

TEST(Query, DegenerateInputs) {
  const Transform id = Transform::identity();
  // Duplicate and interior points do not change the answer.
  const Shape cube{make_polytope(std::vector<Vec3>{{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, 1},
                                                   {1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {0, 0, 0}, {0.5, 0, 0}})};
  EXPECT_EQ(std::get<Polytope>(cube.core).data->vertices.size(), 8u);
  // Point, segment and flat polygon polytopes.
  const Shape point{make_polytope(std::vector<Vec3>{{0, 0, 3}})};
  EXPECT_NEAR(penetration(cube, id, point, id).distance, 2.0, 1e-12);
  const Shape needle{make_polytope(std::vector<Vec3>{{-5, 0, 0}, {5, 0, 0}, {0, 0, 0}})};
  const PenetrationResult rn = penetration(cube, id, needle, Transform::from({0, 0, 1.5}, {}));
  EXPECT_NEAR(rn.distance, 0.5, 1e-12);
  const PenetrationResult rn_in = penetration(cube, id, needle, Transform::from({0, 0, 0.75}, {}));
  EXPECT_TRUE(rn_in.intersect);
  EXPECT_NEAR(rn_in.depth, 0.25, 1e-12);
  // Two coplanar flat squares overlapping: intersecting with zero depth.
  const Shape square{make_polytope(std::vector<Vec3>{{-1, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {1, 1, 0}})};
  const PenetrationResult flat = penetration(square, id, square, Transform::from({0.5, 0.5, 0}, {}));
  EXPECT_TRUE(flat.intersect);
  EXPECT_NEAR(flat.depth, 0.0, 1e-12);
  EXPECT_EQ(flat.epa_status, EpaStatus::Degenerate);
  // Vertex touching a face exactly.
  const PenetrationResult touch = penetration(cube, id, point, Transform::from({0, 0, -2}, {}));
  EXPECT_TRUE(touch.intersect);
  EXPECT_NEAR(touch.depth, 0.0, 1e-12);
}

TEST(Query, WarmStartGivesSameAnswerInFewerIterations) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 400; ++i) pts.push_back(normalized(Vec3{u(rng), u(rng), u(rng)}));
  const Shape ball{make_polytope(pts)};
  GjkCache cache;
  int cold_total = 0, warm_total = 0;
  for (int step = 0; step < 100; ++step) {
    // B drifts slowly past A, as between two DEM time steps.
    const Transform pa = Transform::identity();
    const Transform pb = Transform::from({2.1, -1 + 0.02 * step, 0.3}, quat_from_axis_angle({0, 0, 1}, 0.01 * step));
    const DistanceResult cold = distance(ball, pa, ball, pb);
    const DistanceResult warm = distance(ball, pa, ball, pb, &cache);
    EXPECT_EQ(cold.intersect, warm.intersect);
    EXPECT_NEAR(cold.distance, warm.distance, 1e-12);
    cold_total += cold.iterations;
    warm_total += warm.iterations;
  }
  EXPECT_LT(warm_total, cold_total);
}

}  // namespace
}  // namespace gjkdem
