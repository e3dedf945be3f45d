// Robustness contracts of the queries: no heap allocation inside a query, and
// finite answers with a status on degenerate inputs (flat, needle, duplicate,
// coincident and touching shapes, huge offsets).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <random>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/collide/triangle_contact.hpp"

// Counting global allocator: the test reads the count around the queries.
namespace {
std::atomic<long> g_allocations{0};
}
void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace gjkdem {
namespace {

std::vector<Shape> sample_shapes(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> cloud, big;
  for (int i = 0; i < 40; ++i) cloud.push_back({u(rng), u(rng), u(rng)});
  for (int i = 0; i < 500; ++i) big.push_back(normalized(Vec3{u(rng), u(rng), u(rng)}));
  return {Shape{make_polytope(cloud)},
          Shape{make_polytope(big), 0.05},
          make_sphere(0.7),
          make_capsule({-1, 0, 0}, {1, 0, 0}, 0.2),
          Shape{Box{{0.5, 0.3, 0.8}}},
          Shape{Ellipsoid{{0.9, 0.4, 0.6}}},
          Shape{Cylinder{0.5, 0.7}, 0.01},
          Shape{Cone{0.6, 0.5}},
          Shape{Superellipsoid{{0.8, 0.6, 0.5}, 0.4, 1.6}},
          Shape{Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}}};
}

TEST(Robustness, QueriesDoNotAllocate) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<Shape> shapes = sample_shapes(rng);
  std::vector<Transform> poses;
  for (int i = 0; i < 50; ++i)
    poses.push_back(Transform::from(Vec3{u(rng), u(rng), u(rng)} * 1.5, normalized(Quat{u(rng), u(rng), u(rng), u(rng)})));
  GjkCache cache;
  {  // the counter works: a vector allocates
    const long start = g_allocations.load();
    std::vector<int> probe(3);
    EXPECT_GT(g_allocations.load(), start);
  }
  const long before = g_allocations.load();
  double sink = 0;
  for (const Shape& a : shapes)
    for (const Shape& b : shapes)
      for (int k = 0; k + 1 < static_cast<int>(poses.size()); k += 7) {
        sink += intersect(a, poses[k], b, poses[k + 1]);
        sink += distance(a, poses[k], b, poses[k + 1], &cache).distance;
        sink += penetration(a, poses[k], b, poses[k + 1]).depth;
      }
  sink += triangle_contact({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0.1}, {1, 0, 0.1}, {0, 1, 0.2}, 0.05).distance;
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

bool finite(const PenetrationResult& r) {
  return std::isfinite(r.distance) && std::isfinite(r.depth) && is_finite(r.witness_a) && is_finite(r.witness_b) &&
         is_finite(r.normal);
}

TEST(Robustness, DegenerateInputsGiveFiniteAnswers) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(-1, 1);
  int checked = 0;
  for (int c = 0; c < 400; ++c) {
    // Families: flat, needle, duplicated, tiny, and coincident shapes.
    std::vector<Vec3> pts;
    const int family = c % 5;
    for (int i = 0; i < 12; ++i) {
      Vec3 p{u(rng), u(rng), u(rng)};
      if (family == 0) p.z = 0;                       // flat
      if (family == 1) p = Vec3{1, 2, 3} * u(rng);    // needle (a segment)
      if (family == 2) p = Vec3{u(rng) > 0 ? 1.0 : -1.0, 0.5, 0.25};  // two points, many copies
      if (family == 3) p = p * 1e-9;                   // tiny
      pts.push_back(p);
    }
    const Shape a{make_polytope(pts)};
    const Shape b = family == 4 ? a : Shape{Box{{0.5, 0.5, 0.5}}, c % 2 ? 0.0 : 0.1};
    const Vec3 offset = family == 4 ? Vec3{} : Vec3{u(rng), u(rng), u(rng)};
    const Vec3 far{1e6, -1e6, 5e5};
    const PenetrationResult r = penetration(a, Transform::from(far, {}), b, Transform::from(far + offset, {}));
    ASSERT_TRUE(finite(r)) << "case " << c;
    EXPECT_GE(r.distance, 0);
    EXPECT_GE(r.depth, 0);
    EXPECT_NEAR(length(r.normal), 1.0, 1e-9) << "case " << c;
    EXPECT_EQ(r.intersect, intersect(a, Transform::from(far, {}), b, Transform::from(far + offset, {})) ||
                               (r.intersect ? r.depth : r.distance) < 1e-9)
        << "case " << c;
    ++checked;
  }
  EXPECT_EQ(checked, 400);
}

TEST(Robustness, EpaReportsTouchingAndFlatContacts) {
  const Shape box{Box{{1, 1, 1}}};
  // Face on face, exactly touching.
  const PenetrationResult touch = penetration(box, Transform::identity(), box, Transform::from({2, 0.3, 0.1}, {}));
  EXPECT_TRUE(touch.intersect);
  EXPECT_EQ(touch.depth, 0.0);
  EXPECT_TRUE(touch.epa_status == EpaStatus::Touching || touch.gjk_status != GjkStatus::Intersecting);
  // Two coplanar triangles: A - B is flat, depth 0, status Degenerate.
  const Shape tri{Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}};
  const PenetrationResult flat = penetration(tri, Transform::identity(), tri, Transform::from({0.1, 0.1, 0}, {}));
  EXPECT_TRUE(flat.intersect);
  EXPECT_EQ(flat.epa_status, EpaStatus::Degenerate);
  EXPECT_EQ(flat.depth, 0.0);
  EXPECT_NEAR(std::fabs(flat.normal.z), 1.0, 1e-12);
}

}  // namespace
}  // namespace gjkdem
