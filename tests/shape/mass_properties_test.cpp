// Mass properties against independent computations: closed forms checked on
// their polytope approximations (tessellations), and the polytope integration
// against a box and a tetrahedron known by hand.
#include "gjkdem/shape/mass_properties.hpp"

#include <gtest/gtest.h>

#include "gjkdem/shape/tessellate.hpp"

namespace gjkdem {
namespace {


void expect_mat_near(const Mat3& a, const Mat3& b, double tol) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(a.row[i][j], b.row[i][j], tol) << i << "," << j;
}

TEST(MassProperties, PolytopeIntegrationIsExact) {
  // A 2 x 4 x 6 box as a point cloud, shifted: I_xx = V (4^2 + 6^2) / 12 with V = 48.
  std::vector<Vec3> pts;
  for (int k = 0; k < 8; ++k) pts.push_back(Vec3{k & 1 ? 2.0 : 0.0, k & 2 ? 4.0 : 0.0, k & 4 ? 6.0 : 0.0} + Vec3{5, -1, 2});
  const MassProperties m = mass_properties(Shape{make_polytope(pts)});
  EXPECT_NEAR(m.volume, 48, 1e-12);
  EXPECT_NEAR(length(m.centroid - Vec3{6, 1, 5}), 0, 1e-12);  // the points are the local frame
  Mat3 want;
  want.row[0] = {48 * (16 + 36) / 12.0, 0, 0};
  want.row[1] = {0, 48 * (4 + 36) / 12.0, 0};
  want.row[2] = {0, 0, 48 * (4 + 16) / 12.0};
  expect_mat_near(m.inertia, want, 1e-10);
}

TEST(MassProperties, ClosedFormsMatchFineTessellations) {
  const Shape shapes[] = {make_sphere(0.7), Shape{Box{{0.3, 0.5, 0.9}}}, Shape{Ellipsoid{{1.0, 0.6, 0.3}}},
                          Shape{Cylinder{0.4, 0.8}}, Shape{Cone{0.5, 0.6}}, make_capsule({-0.5, 0.2, 0}, {0.5, -0.2, 0.3}, 0.25),
                          Shape{Superellipsoid{{1.0, 0.7, 0.5}, 0.5, 1.5}}, Shape{Superellipsoid{{0.8, 0.8, 1.0}, 1.7, 0.4}}};
  for (const Shape& s : shapes) {
    const MassProperties exact = mass_properties(s);
    const Tessellation t = tessellate(s, 20000);
    const MassProperties approx = mass_properties(Shape{t.polytope});
    // The inscribed polytope differs by about area * bound: a relative 1e-3 here.
    EXPECT_NEAR(approx.volume / exact.volume, 1.0, 2e-3) << s.core.index();
    EXPECT_NEAR(length(approx.centroid - exact.centroid), 0.0, 2e-3) << s.core.index();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(approx.inertia.row[i][j], exact.inertia.row[i][j], 4e-3 * exact.inertia.row[i][i]) << s.core.index();
  }
  // Superellipsoid with exponents 1 is the ellipsoid.
  const MassProperties se = mass_properties(Shape{Superellipsoid{{1.0, 0.6, 0.3}, 1, 1}});
  const MassProperties el = mass_properties(Shape{Ellipsoid{{1.0, 0.6, 0.3}}});
  EXPECT_NEAR(se.volume, el.volume, 1e-12);
  expect_mat_near(se.inertia, el.inertia, 1e-12);
  EXPECT_NEAR(el.volume, 4 * kPi / 3 * 0.18, 1e-14);
}

TEST(MassProperties, PrincipalAxesDiagonalise) {
  const Quat turn = normalized(Quat{0.9, 0.2, -0.3, 0.1});
  std::vector<Vec3> pts;
  for (int k = 0; k < 8; ++k) pts.push_back(rotate(turn, Vec3{k & 1 ? 1.0 : -1.0, k & 2 ? 2.0 : -2.0, k & 4 ? 3.0 : -3.0}));
  const MassProperties m = mass_properties(Shape{make_polytope(pts)});
  const PrincipalAxes p = principal_axes(m.inertia);
  // A 2 x 4 x 6 box (V = 48): V (l2^2 + l3^2) / 12 = 80, 160, 208, ascending.
  EXPECT_NEAR(p.moments.x, 80, 1e-9);
  EXPECT_NEAR(p.moments.y, 160, 1e-9);
  EXPECT_NEAR(p.moments.z, 208, 1e-9);
  // R diag(moments) R^T reproduces the tensor.
  const Mat3 r = to_matrix(p.rotation);
  Mat3 d;
  d.row[0] = {p.moments.x, 0, 0};
  d.row[1] = {0, p.moments.y, 0};
  d.row[2] = {0, 0, p.moments.z};
  expect_mat_near(r * d * transpose(r), m.inertia, 1e-9);
}

TEST(MassProperties, RefusesShapesWithoutVolume) {
  EXPECT_THROW(mass_properties(Shape{Point{}}), std::invalid_argument);
  EXPECT_THROW(mass_properties(Shape{Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}}), std::invalid_argument);
  EXPECT_THROW(mass_properties(Shape{make_polytope(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}), std::invalid_argument);
  EXPECT_THROW(mass_properties(Shape{Box{{1, 1, 1}}, 0.1}), std::invalid_argument);
}

}  // namespace
}  // namespace gjkdem
