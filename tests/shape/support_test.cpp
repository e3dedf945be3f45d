// Support functions against dense sampling of each shape's surface: the support
// point must lie on the shape and reach at least as far as every sample.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "gjkdem/shape/shape.hpp"

namespace gjkdem {
namespace {


// Signed power: sign(x) |x|^p, the superquadric parametrisation.
double spow(double x, double p) { return std::copysign(std::pow(std::fabs(x), p), x); }

std::vector<Vec3> sample_surface(const ShapeCore& core, int n) {
  std::vector<Vec3> s;
  for (int i = 0; i <= n; ++i) {
    const double eta = -kPi / 2 + kPi * i / n;  // latitude
    for (int j = 0; j < 2 * n; ++j) {
      const double om = -kPi + kPi * j / n;  // longitude
      if (const auto* e = std::get_if<Ellipsoid>(&core)) {
        s.push_back({e->radii.x * std::cos(eta) * std::cos(om), e->radii.y * std::cos(eta) * std::sin(om),
                     e->radii.z * std::sin(eta)});
      } else if (const auto* q = std::get_if<Superellipsoid>(&core)) {
        s.push_back({q->radii.x * spow(std::cos(eta), q->e1) * spow(std::cos(om), q->e2),
                     q->radii.y * spow(std::cos(eta), q->e1) * spow(std::sin(om), q->e2),
                     q->radii.z * spow(std::sin(eta), q->e1)});
      } else if (const auto* c = std::get_if<Cylinder>(&core)) {
        const double z = -c->half_height + 2 * c->half_height * i / n;
        s.push_back({c->radius * std::cos(om), c->radius * std::sin(om), z});
      } else if (const auto* k = std::get_if<Cone>(&core)) {
        const double t = double(i) / n;  // 0 at apex, 1 at base
        s.push_back({k->radius * t * std::cos(om), k->radius * t * std::sin(om), k->half_height * (1 - 2 * t)});
      }
    }
  }
  return s;
}

// Implicit "inside" measure: <= 1 inside, 1 on the surface.
double implicit(const ShapeCore& core, const Vec3& p) {
  if (const auto* e = std::get_if<Ellipsoid>(&core))
    return std::sqrt(std::pow(p.x / e->radii.x, 2) + std::pow(p.y / e->radii.y, 2) + std::pow(p.z / e->radii.z, 2));
  if (const auto* q = std::get_if<Superellipsoid>(&core)) {
    const double xy = std::pow(std::fabs(p.x / q->radii.x), 2 / q->e2) + std::pow(std::fabs(p.y / q->radii.y), 2 / q->e2);
    return std::pow(std::pow(xy, q->e2 / q->e1) + std::pow(std::fabs(p.z / q->radii.z), 2 / q->e1), q->e1 / 2);
  }
  if (const auto* c = std::get_if<Cylinder>(&core))
    return std::fmax(std::hypot(p.x, p.y) / c->radius, std::fabs(p.z) / c->half_height);
  if (const auto* k = std::get_if<Cone>(&core)) {
    const double t = (k->half_height - p.z) / (2 * k->half_height);  // 0 at the apex, 1 on the base
    const double radial = std::hypot(p.x, p.y);
    if (radial == 0 && t == 0) return 1;  // the apex itself
    return std::fmax(t > 0 ? radial / (k->radius * t) : 2.0, t);
  }
  return 0;
}

class SupportTest : public ::testing::TestWithParam<ShapeCore> {};

std::string core_test_name(const ::testing::TestParamInfo<ShapeCore>& param_info) {
  static const char* const kNames[] = {"Point", "Segment", "Triangle", "Box", "Ellipsoid",
                                       "Cylinder", "Cone", "Superellipsoid", "Polytope"};
  return std::string(kNames[param_info.param.index()]) + std::to_string(param_info.index);
}

TEST_P(SupportTest, ReachesFarthestSampleAndLiesOnShape) {
  const ShapeCore core = GetParam();
  const std::vector<Vec3> samples = sample_surface(core, 120);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  double scale = 0;
  for (const Vec3& p : samples) scale = std::fmax(scale, length(p));
  for (int k = 0; k < 300; ++k) {
    Vec3 d{g(rng), g(rng), g(rng)};
    if (k < 6) {  // the axes first, where ties are likely
      d = Vec3{};
      d[k / 2] = k % 2 ? -1 : 1;
    }
    int hint = 0;
    const Vec3 s = std::visit([&](const auto& c) { return support(c, d, hint); }, core);
    double best = -1e300;
    for (const Vec3& p : samples) best = std::fmax(best, dot(p, d));
    EXPECT_GE(dot(s, d), best - 1e-12 * scale * length(d)) << "direction " << k;
    // The sampling is dense, so it misses the maximum by little.
    EXPECT_LE(dot(s, d), best + 2e-3 * scale * length(d)) << "direction " << k;
    EXPECT_NEAR(implicit(core, s), 1.0, 1e-9) << "direction " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Curved, SupportTest,
    ::testing::Values(ShapeCore{Ellipsoid{{1.0, 0.3, 2.0}}}, ShapeCore{Superellipsoid{{1.0, 0.5, 0.8}, 1.0, 1.0}},
                      ShapeCore{Superellipsoid{{1.0, 0.5, 0.8}, 0.3, 0.5}},
                      ShapeCore{Superellipsoid{{0.7, 1.2, 0.4}, 1.7, 1.2}},
                      ShapeCore{Superellipsoid{{1.0, 1.0, 1.0}, 2.0, 2.0}}, ShapeCore{Cylinder{0.5, 2.0}},
                      ShapeCore{Cone{1.0, 0.7}}),
    core_test_name);

TEST(Support, BoxSegmentTriangleAndMargin) {
  int hint = 0;
  EXPECT_EQ(support(Box{{1, 2, 3}}, {1, -1, 1}, hint), (Vec3{1, -2, 3}));
  EXPECT_EQ(support(Segment{{0, 0, 0}, {1, 0, 0}}, {1, 0.5, 0}, hint), (Vec3{1, 0, 0}));
  EXPECT_EQ(support(Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {-1, 2, 0}, hint), (Vec3{0, 1, 0}));
  const Shape rounded{Box{{1, 1, 1}}, 0.5};
  const Vec3 s = support(rounded, {0, 0, 2});
  EXPECT_NEAR(s.z, 1.5, 1e-15);
  EXPECT_NEAR(bounding_radius(make_sphere(2)), 2.0, 1e-15);
}

TEST(Support, PolytopeHillClimbMatchesScan) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  std::vector<Vec3> pts;
  for (int i = 0; i < 3000; ++i) pts.push_back(normalized(Vec3{g(rng), g(rng), g(rng)}) * (1 + 0.01 * g(rng)));
  const Polytope p = make_polytope(pts);
  ASSERT_FALSE(p.data->adj.empty()) << "a large hull must hill-climb";
  int hint = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 d{g(rng), g(rng), g(rng)};
    const Vec3 s = support(p, d, hint);  // warm from the previous hint
    double best = -1e300;
    for (const Vec3& v : pts) best = std::fmax(best, dot(v, d));
    EXPECT_NEAR(dot(s, d), best, 1e-12 * length(d));
  }
}

// The 4-wide scan (AVX2 where the processor has it) and the 2-wide one
// return the same vertex, the first with the largest product, also on ties:
// grids of points whose hulls have many vertices in a plane, probed along
// the axes and diagonals, and random hulls of every size the scans serve.
TEST(Support, WideAndNarrowScansPickTheSameVertex) {
  std::mt19937_64 rng(6);
  std::normal_distribution<double> g;
  std::vector<Polytope> hulls;
  for (int n = 4; n <= kHillClimbMinVertices; ++n) {
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) pts.push_back(Vec3{g(rng), g(rng), g(rng)});
    hulls.push_back(make_polytope(pts));
  }
  for (int side = 2; side <= 4; ++side) {  // a cube's grid: hull vertices tie along the axes
    std::vector<Vec3> pts;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) pts.push_back(Vec3{Real(i), Real(j), 0}), pts.push_back(Vec3{Real(i), Real(j), 1});
    hulls.push_back(make_polytope(pts));
  }
  std::vector<Vec3> dirs = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 0}, {1, 1, 1}};
  for (int k = 0; k < 200; ++k) dirs.push_back(Vec3{g(rng), g(rng), g(rng)});
  int wide = 0;
  for (const Polytope& p : hulls) {
    const PolytopeData& s = *p.data;
    ASSERT_EQ(s.soa_stride % 4, 0);
    wide += s.soa_stride >= kWideScanMinVertices;
    for (const Vec3& d : dirs) {
      const int a = detail::scan_support_index_wide(s, d), b = detail::scan_support_index_narrow(s, d);
      ASSERT_EQ(a, b) << "hull of " << s.vertices.size() << " vertices, direction " << d.x << " " << d.y << " " << d.z;
      ASSERT_LT(a, static_cast<int>(s.vertices.size()));
    }
  }
  EXPECT_GT(wide, 10);
}

}  // namespace
}  // namespace gjkdem
