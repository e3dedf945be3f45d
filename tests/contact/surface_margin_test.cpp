// A closed surface against a triangle with a margin (contact/surface_margin.hpp):
// - the deepest contact is rho minus the least distance of any of the
//   surface's triangles to the triangle, found by the one-pair query over
//   every triangle (no tree), on tori and U prisms placed at random;
// - nothing within the margin gives no contact; a flat face pushes at its
//   middle;
// - moved and turned together, or scaled, the contacts follow;
// - a box pushed past the triangle's plane pushes back along its normal by
//   the margin plus how far its top lies beyond the plane.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gjkdem/contact/surface_margin.hpp"
#include "gjkdem/math/quat.hpp"
#include "gjkdem/math/transform.hpp"
#include "shape/surface_shapes.hpp"

namespace gjkdem {
namespace {

using test::Mesh;

// The contacts of a surface whose solid holds `centre` with the triangles.
void surface_margin_contacts(const Surface& surface, std::span<const MarginTriangle> triangles, const Vec3& centre,
                             SurfaceMarginScratch& scratch, std::vector<MarginContact>& out) {
  TriangleSet set = triangles_of(surface);
  set.inside = centre;
  gjkdem::surface_margin_contacts(set, triangles, scratch, out);
}

// The least distance of any triangle of the surface to the triangle.
Real brute_distance(const Surface& s, const std::array<Vec3, 3>& t) {
  Real least = INFINITY;
  for (const TriangleIndices& v : s.triangles)
    least = std::fmin(least, triangle_contact(t[0], t[1], t[2], s.vertices[v[0]], s.vertices[v[1]],
                                              s.vertices[v[2]], 0).distance);
  return least;
}

// One triangle's contacts.
void surface_triangle_margin(const Surface& s, const std::array<Vec3, 3>& t, Real rho, const Vec3& centre,
                             SurfaceMarginScratch& scratch, std::vector<ContactPoint>& out) {
  std::vector<MarginContact> found;
  const MarginTriangle one{t, rho};
  surface_margin_contacts(s, {&one, 1}, centre, scratch, found);
  out.clear();
  for (const MarginContact& c : found) {
    EXPECT_EQ(c.triangle, 0u);
    out.push_back(c.contact);
  }
}

Real deepest(const std::vector<ContactPoint>& contacts) {
  Real d = -INFINITY;
  for (const ContactPoint& c : contacts) d = std::fmax(d, c.depth);
  return d;
}

TEST(SurfaceMargin, DeepestContactIsTheMarginLessTheLeastDistance) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  const Surface shapes[2] = {test::surface_of(test::torus(1, 0.35, 24, 12)), test::surface_of(test::u_prism(1))};
  SurfaceMarginScratch scratch;
  std::vector<ContactPoint> out;
  int touching = 0, apart = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Surface& s = shapes[trial % 2];
    const Vec3 middle = 0.5 * (s.box.lo + s.box.hi);
    // A triangle of size about 1 near the surface's box.
    const Vec3 at = middle + Vec3{u(rng), u(rng), u(rng)} * 1.6;
    const std::array<Vec3, 3> t{at + Vec3{u(rng), u(rng), u(rng)} * 0.6, at + Vec3{u(rng), u(rng), u(rng)} * 0.6,
                                at + Vec3{u(rng), u(rng), u(rng)} * 0.6};
    const Real rho = 0.02 + 0.2 * (u(rng) + 1);
    surface_triangle_margin(s, t, rho, middle, scratch, out);
    const Real d = brute_distance(s, t);
    if (d >= rho) {
      EXPECT_TRUE(out.empty()) << trial;
      ++apart;
      continue;
    }
    if (d == 0) continue;  // crossing: checked below
    ASSERT_FALSE(out.empty()) << trial;
    EXPECT_NEAR(deepest(out), rho - d, 1e-12) << trial;
    for (const ContactPoint& c : out) {
      EXPECT_NEAR(length(c.normal), 1, 1e-12);
      EXPECT_GT(c.depth, 0);
      EXPECT_LE(c.depth, rho);
    }
    ++touching;
  }
  EXPECT_GT(touching, 40);
  EXPECT_GT(apart, 40);
}

TEST(SurfaceMargin, ContactsFollowTheSurfaceAndTriangleMovedOrScaledTogether) {
  const Mesh torus = test::torus(1, 0.35, 24, 12);
  const std::array<Vec3, 3> t{Vec3{0.2, -0.3, 0.4}, Vec3{1.6, 0.1, 0.38}, Vec3{0.9, 1.2, 0.45}};
  const Real rho = 0.1;
  SurfaceMarginScratch scratch;
  std::vector<ContactPoint> base, moved;
  surface_triangle_margin(test::surface_of(torus), t, rho, {}, scratch, base);
  ASSERT_FALSE(base.empty());
  const Transform pose{to_matrix(normalized(Quat{0.9, 0.2, -0.3, 0.1})), {1e5, -3e4, 2e5}};
  for (const Real scale : {1e-3, 1.0, 1e3}) {
    Mesh m = torus;
    for (Vec3& v : m.vertices) v = apply(pose, v * scale);
    const std::array<Vec3, 3> tm{apply(pose, t[0] * scale), apply(pose, t[1] * scale), apply(pose, t[2] * scale)};
    surface_triangle_margin(test::surface_of(m), tm, rho * scale, pose.translation, scratch, moved);
    ASSERT_EQ(moved.size(), base.size()) << scale;
    const Real tol = 1e-9 * scale + 1e-10 * length(pose.translation);
    for (std::size_t k = 0; k < base.size(); ++k) {
      EXPECT_NEAR(moved[k].depth, base[k].depth * scale, tol) << scale;
      EXPECT_LT(length(moved[k].point - apply(pose, base[k].point * scale)), tol) << scale;
      // A normal is the witnesses' difference over their distance: round-off
      // at the translation's magnitude, over distances that shrink with scale.
      EXPECT_LT(length(moved[k].normal - apply_rotation(pose, base[k].normal)),
                1e-9 + 1e-14 * length(pose.translation) / scale)
          << scale;
    }
  }
}

TEST(SurfaceMargin, ABoxPastThePlanePushesBackAlongTheNormal) {
  const Surface box = test::surface_of(test::box_surface({-1, -1, -1}, {1, 1, 1}));
  // A big triangle through the box's top, 0.3 below its top face.
  const std::array<Vec3, 3> t{Vec3{-5, -5, 0.7}, Vec3{5, -5, 0.7}, Vec3{0, 8, 0.7}};
  SurfaceMarginScratch scratch;
  std::vector<ContactPoint> out;
  surface_triangle_margin(box, t, 0.1, {0, 0, 0}, scratch, out);
  ASSERT_FALSE(out.empty());
  EXPECT_NEAR(deepest(out), 0.4, 1e-12);  // the top face at 1 against the margin's side at 0.6
  for (const ContactPoint& c : out) {
    if (c.depth == deepest(out)) {
      EXPECT_LT(length(c.normal - Vec3{0, 0, -1}), 1e-12);
    }
  }
  // Resting on top of it instead, 0.05 above: one contact, depth 0.05, upwards.
  const std::array<Vec3, 3> under{Vec3{-5, -5, -1.05}, Vec3{5, -5, -1.05}, Vec3{0, 8, -1.05}};
  surface_triangle_margin(box, under, 0.1, {0, 0, 0}, scratch, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].depth, 0.05, 1e-12);
  EXPECT_LT(length(out[0].normal - Vec3{0, 0, 1}), 1e-12);
  EXPECT_NEAR(out[0].point.z, -0.975, 1e-12);  // midway across the overlap: from -1 up to the margin's -0.95
  EXPECT_LT(std::hypot(out[0].point.x, out[0].point.y), 1e-12);  // under the bottom face's middle
}

// A seam under a face: two triangles sharing an edge under a box's bottom
// give the one contact one big triangle gives, whichever side the seam is on.
TEST(SurfaceMargin, ASeamUnderAFaceAddsNoContact) {
  const Surface box = test::surface_of(test::box_surface({-1, -1, 0.04}, {1, 1, 2.04}));
  SurfaceMarginScratch scratch;
  std::vector<MarginContact> one, two;
  const MarginTriangle big{{Vec3{-9, -9, 0}, Vec3{9, -9, 0}, Vec3{0, 9, 0}}, 0.1};
  surface_margin_contacts(box, {&big, 1}, {0, 0, 1}, scratch, one);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0].contact.depth, 0.06, 1e-12);
  EXPECT_LT(length(one[0].contact.point - Vec3{0, 0, 0.07}), 1e-12);
  for (const Real seam : {0.0, 0.3, -0.999, 1.0}) {  // the seam x = seam
    const MarginTriangle halves[2] = {{{Vec3{-9, -9, 0}, Vec3{seam, -9, 0}, Vec3{seam, 9, 0}}, 0.1},
                                      {{Vec3{seam, -9, 0}, Vec3{9, 0, 0}, Vec3{seam, 9, 0}}, 0.1}};
    surface_margin_contacts(box, halves, {0, 0, 1}, scratch, two);
    ASSERT_EQ(two.size(), 1u) << seam;
    EXPECT_NEAR(two[0].contact.depth, 0.06, 1e-12) << seam;
    EXPECT_LT(length(two[0].contact.point - one[0].contact.point), 1e-12) << seam;
    EXPECT_LT(length(two[0].contact.normal - Vec3{0, 0, 1}), 1e-12) << seam;
  }
}

}  // namespace
}  // namespace gjkdem
