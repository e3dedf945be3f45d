// A surface's solid beyond a plane (contact/surface_half_space.hpp) against
// independent answers: the convex clipping of half_space.hpp on random hulls
// and random planes, closed forms for a U's two feet (two pieces), and the
// limits (wholly above: nothing; wholly below: submerged).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gjkdem/contact/half_space.hpp"
#include "gjkdem/contact/surface_half_space.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "shape/surface_shapes.hpp"

namespace gjkdem {
namespace {

TEST(SurfaceHalfSpace, MatchesConvexClippingOnRandomHulls) {
  std::mt19937_64 rng(3);
  std::normal_distribution<Real> gauss;
  HalfSpaceScratch scratch;
  int cut = 0;
  for (int n = 0; n < 300; ++n) {
    std::vector<Vec3> points(14);
    for (Vec3& p : points) p = {gauss(rng), gauss(rng), gauss(rng)};
    const Polytope hull = make_polytope(points);
    const Surface s = polytope_surface(hull);
    const Vec3 normal = normalized(Vec3{gauss(rng), gauss(rng), gauss(rng)});
    const Vec3 point = normal * (0.8 * gauss(rng));
    const HalfSpaceContact expected = half_space_contact(Shape{hull}, Transform{}, point, normal);
    const SurfaceHalfSpace got = surface_half_space(s, point, normal, scratch);
    if (!expected.touching) {
      EXPECT_TRUE(got.pieces.empty()) << n;
      continue;
    }
    ASSERT_TRUE(expected.has_volume);
    if (!(expected.volume > 1e-9) || !(expected.area > 0)) continue;
    ++cut;
    ASSERT_EQ(got.pieces.size(), 1u) << n;  // convex: one piece
    const HalfSpacePiece& p = got.pieces[0];
    EXPECT_NEAR(p.volume, expected.volume, 1e-12 * s.volume) << n;
    EXPECT_LT(length(p.centroid - expected.centroid), 1e-10) << n;
    EXPECT_NEAR(p.cut_area, expected.area, 1e-11 * (1 + expected.area)) << n;
    EXPECT_NEAR(p.depth_integral, expected.depth_integral, 1e-11 * (1 + expected.depth_integral)) << n;
  }
  EXPECT_GT(cut, 100);
}

TEST(SurfaceHalfSpace, AUsFeetAreTwoPieces) {
  // The U of [0,3]x[0,1] and the arms [0,1]x[1,2], [2,3]x[1,2] (thickness 1
  // in z); the plane y = 1.5 facing -y leaves the arms' tips beyond it.
  const Surface u = test::surface_of(test::u_prism(1));
  HalfSpaceScratch scratch;
  const SurfaceHalfSpace h = surface_half_space(u, {0, 1.5, 0}, {0, -1, 0}, scratch);
  ASSERT_EQ(h.pieces.size(), 2u);
  EXPECT_FALSE(h.submerged);
  for (const HalfSpacePiece& p : h.pieces) {
    EXPECT_NEAR(p.volume, 0.5, 1e-14);
    EXPECT_NEAR(p.cut_area, 1, 1e-14);
    EXPECT_NEAR(p.depth_integral, 0.125, 1e-14);  // integral of (y - 1.5) over a 1 x 0.5 x 1 slab
    EXPECT_NEAR(p.centroid.y, 1.75, 1e-14);
    EXPECT_NEAR(p.centroid.z, 0.5, 1e-14);
  }
  EXPECT_NEAR(h.pieces[0].centroid.x + h.pieces[1].centroid.x, 3, 1e-14);  // at x = 0.5 and 2.5
  EXPECT_TRUE(surface_half_space(u, {0, 5, 0}, {0, -1, 0}, scratch).pieces.empty());
  EXPECT_TRUE(surface_half_space(u, {0, 5, 0}, {0, 1, 0}, scratch).submerged);
}

}  // namespace
}  // namespace gjkdem
