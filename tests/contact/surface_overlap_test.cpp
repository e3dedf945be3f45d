// The overlap of closed surfaces against independent answers: the convex
// clipping of contact/overlap.hpp on random hulls, closed forms on boxes and
// an L-shaped prism, and the properties every answer must have (swap,
// translate, scale, touching, coplanar faces).
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <random>
#include <vector>

#include "gjkdem/collide/surface_distance.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "shape/surface_shapes.hpp"

namespace gjkdem {
namespace {

using test::box_surface;
using test::Mesh;
using test::surface_of;

// The hull of points as a closed surface, the points moved by `shift`.
Surface hull_surface(const Polytope& p, const Vec3& shift) {
  Mesh m;
  for (const Vec3& v : p.data->vertices) m.vertices.push_back(v + shift);
  m.triangles.assign(p.data->triangles.begin(), p.data->triangles.end());
  return surface_of(m);
}

Mesh moved(Mesh m, const Vec3& by, Real scale = 1) {
  for (Vec3& v : m.vertices) v = scale * v + by;
  return m;
}

TEST(SurfaceOverlap, MatchesConvexClippingOnRandomHulls) {
  std::mt19937_64 rng(7);
  std::normal_distribution<Real> gauss;
  std::uniform_real_distribution<Real> offset(-0.8, 0.8);
  OverlapWorkspace work;
  int overlapping = 0;
  for (int n = 0; n < 200; ++n) {
    std::vector<Vec3> pa(12), pb(12);
    for (Vec3& p : pa) p = {gauss(rng), gauss(rng), gauss(rng)};
    for (Vec3& p : pb) p = {gauss(rng), gauss(rng), gauss(rng)};
    const Polytope a = make_polytope(pa), b = make_polytope(pb);
    const Vec3 shift{offset(rng) * 3, offset(rng) * 3, offset(rng) * 3};
    const OverlapResult expected = overlap(Shape{a}, Transform{}, Shape{b}, Transform::from(shift, Quat{}), work);
    const SurfaceOverlap got = surface_overlap(hull_surface(a, {}), hull_surface(b, shift));
    const Real scale = std::fmax(mass_properties(Shape{a}).volume, Real(1));
    ASSERT_NEAR(got.volume, expected.volume, 1e-10 * scale) << n;
    if (expected.volume > 1e-6) {
      ++overlapping;
      ASSERT_EQ(got.patches.size(), 1u) << n;  // convex: one piece
      EXPECT_NEAR(got.patches[0].volume, got.volume, 1e-12 * scale) << n;
      EXPECT_NEAR(length(got.centroid - expected.centroid), 0, 1e-9) << n;
      EXPECT_NEAR(length(got.area_a - expected.area_a), 0, 1e-9 * length(expected.area_a) + 1e-12) << n;
      EXPECT_NEAR(length(got.area_a + got.area_b), 0, 1e-9 * length(expected.area_a) + 1e-12) << n;
      // The first moment of S_A (Feng's line of action and couple).
      EXPECT_NEAR(length(got.area_moment_a - expected.moment_a), 0, 1e-9 * (length(expected.moment_a) + length(expected.area_a)) + 1e-12) << n;
      EXPECT_NEAR(length(got.patches[0].area_moment_a - got.area_moment_a), 0, 1e-12 * length(expected.area_a) + 1e-15) << n;
    }
  }
  EXPECT_GT(overlapping, 50);
}

TEST(SurfaceOverlap, BoxesOnAnIntegerGridMatchTheirClosedForms) {
  // Small integer corners: faces on one plane, edges on edges, corners on
  // corners everywhere. A ∩ B is the box of the overlaps; its faces on one
  // body only count in that body's area, faces on both facing the same way
  // in neither.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> corner(0, 4), size(1, 3);
  for (int n = 0; n < 2000; ++n) {
    Vec3 la, ha, lb, hb;
    for (int k = 0; k < 3; ++k) la[k] = corner(rng), ha[k] = la[k] + size(rng), lb[k] = corner(rng), hb[k] = lb[k] + size(rng);
    const SurfaceOverlap o = surface_overlap(surface_of(box_surface(la, ha)), surface_of(box_surface(lb, hb)));
    Vec3 lo, hi, area_a, area_b;
    bool apart = false, touching = true;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::fmax(la[k], lb[k]), hi[k] = std::fmin(ha[k], hb[k]);
      apart |= hi[k] <= lo[k];
      touching &= hi[k] >= lo[k];
    }
    ASSERT_EQ(o.intersect, touching) << n;
    if (apart) {
      EXPECT_EQ(o.volume, 0) << n;
      EXPECT_TRUE(o.patches.empty()) << n;
      continue;
    }
    const Vec3 w = hi - lo;
    EXPECT_NEAR(o.volume, w.x * w.y * w.z, 1e-12) << n;
    EXPECT_NEAR(length(o.centroid - 0.5 * (lo + hi)), 0, 1e-12) << n;
    ASSERT_EQ(o.patches.size(), 1u) << n;
    for (int k = 0; k < 3; ++k) {
      const Real face = w.x * w.y * w.z / w[k];
      Vec3 e;
      e[k] = 1;
      if (ha[k] == hi[k] && hb[k] != hi[k]) area_a += face * e;
      if (hb[k] == hi[k] && ha[k] != hi[k]) area_b += face * e;
      if (la[k] == lo[k] && lb[k] != lo[k]) area_a -= face * e;
      if (lb[k] == lo[k] && la[k] != lo[k]) area_b -= face * e;
    }
    EXPECT_NEAR(length(o.area_a - area_a), 0, 1e-12) << n;
    EXPECT_NEAR(length(o.area_b - area_b), 0, 1e-12) << n;
  }
}

TEST(SurfaceOverlap, LPrismAgainstABoxInItsCorner) {
  // The box [0.5,1.5]^2 x [0.25,0.75] less the L's notch [1,1.5]^2.
  const Surface l = surface_of(test::l_prism(1));
  const Surface box = surface_of(box_surface({0.5, 0.5, 0.25}, {1.5, 1.5, 0.75}));
  const SurfaceOverlap o = surface_overlap(l, box);
  EXPECT_TRUE(o.intersect);
  EXPECT_NEAR(o.volume, 0.375, 1e-14);
  const Real c = (1 * 1 - 0.25 * 1.25) / 0.75;
  EXPECT_NEAR(o.centroid.x, c, 1e-14);
  EXPECT_NEAR(o.centroid.y, c, 1e-14);
  EXPECT_NEAR(o.centroid.z, 0.5, 1e-14);
  // The box lies wholly within the L's height: the contact surface is the
  // L's two inner walls of the notch, facing +x and +y ... inside the box.
  EXPECT_NEAR(o.area_a.x, 0.25, 1e-14);  // the L's wall x = 1 across y in [1, 1.5], z in [0.25, 0.75]
  EXPECT_NEAR(o.area_a.y, 0.25, 1e-14);
  EXPECT_NEAR(o.area_a.z, 0, 1e-14);
}

TEST(SurfaceOverlap, PropertiesHoldOnAnLPrismAndARotatedBox) {
  Mesh bar = box_surface({-0.3, -0.2, -0.4}, {0.3, 0.2, 0.4});
  // Turned about z and x so that no face is parallel to the L's.
  const Quat q = normalized(Quat{0.9, 0.2, 0.1, 0.3});
  for (Vec3& v : bar.vertices) v = rotate(q, v) + Vec3{1.1, 0.9, 0.5};
  const Mesh l = test::l_prism(1);
  const SurfaceOverlap o = surface_overlap(surface_of(l), surface_of(bar));
  ASSERT_GT(o.volume, 0.01);
  // Swap: the same solid, the areas exchanged.
  const SurfaceOverlap s = surface_overlap(surface_of(bar), surface_of(l));
  EXPECT_NEAR(s.volume, o.volume, 1e-14);
  EXPECT_NEAR(length(s.centroid - o.centroid), 0, 1e-14);
  EXPECT_NEAR(length(s.area_a - o.area_b), 0, 1e-14);
  // Never more than either body's volume; the patches add up to the whole;
  // the areas opposite (no shared faces).
  EXPECT_LE(o.volume, 0.6 * 0.4 * 0.8);
  Real patches = 0;
  for (const SurfacePatch& p : o.patches) patches += p.volume;
  EXPECT_NEAR(patches, o.volume, 1e-14);
  EXPECT_NEAR(length(o.area_a + o.area_b), 0, 1e-13);
  // Translated by 1e5 and scaled by 1e-3 and 1e3.
  const Vec3 far{1e5, -1e5, 1e5};
  const SurfaceOverlap t = surface_overlap(surface_of(moved(l, far)), surface_of(moved(bar, far)));
  EXPECT_NEAR(t.volume, o.volume, 1e-9 * o.volume);
  EXPECT_NEAR(length(t.centroid - far - o.centroid), 0, 1e-9);
  for (const Real k : {1e-3, 1e3}) {
    const SurfaceOverlap m = surface_overlap(surface_of(moved(l, {}, k)), surface_of(moved(bar, {}, k)));
    EXPECT_NEAR(m.volume, k * k * k * o.volume, 1e-12 * k * k * k * o.volume);
    EXPECT_NEAR(length(m.centroid - k * o.centroid), 0, 1e-12 * k);
    EXPECT_NEAR(length(m.area_a - k * k * o.area_a), 0, 1e-12 * k * k);
  }
}

TEST(SurfaceOverlap, BothMovedAlikeGiveTheSameOverlapMoved) {
  Mesh bar = box_surface({-0.3, -0.2, -0.4}, {0.3, 0.2, 0.4});
  for (Vec3& v : bar.vertices) v = rotate(normalized(Quat{0.9, 0.2, 0.1, 0.3}), v) + Vec3{1.1, 0.9, 0.5};
  const Surface l = surface_of(test::l_prism(1)), b = surface_of(bar);
  const SurfaceOverlap o = surface_overlap(l, b);
  const Transform pose = Transform::from({3, -2, 7}, normalized(Quat{0.3, -0.5, 0.7, 0.2}));
  const Surface lm = moved(l, pose), bm = moved(b, pose);
  EXPECT_NEAR(mass_properties(lm).volume, mass_properties(l).volume, 1e-14);
  const SurfaceOverlap m = surface_overlap(lm, bm);
  EXPECT_NEAR(m.volume, o.volume, 1e-12 * o.volume);
  EXPECT_NEAR(length(m.centroid - apply(pose, o.centroid)), 0, 1e-12);
  EXPECT_NEAR(length(m.area_a - apply_rotation(pose, o.area_a)), 0, 1e-12);
  EXPECT_EQ(m.patches.size(), o.patches.size());
  // Moved by nothing: the same bits.
  const SurfaceOverlap same = surface_overlap(moved(l, Transform{}), moved(b, Transform{}));
  EXPECT_EQ(same.volume, o.volume);
  EXPECT_EQ(same.centroid, o.centroid);
}

TEST(SurfaceOverlap, TouchingAndSharedFaces) {
  const Surface unit = surface_of(box_surface({0, 0, 0}, {1, 1, 1}));
  // Face to face: touching, no volume.
  const SurfaceOverlap touch = surface_overlap(unit, surface_of(box_surface({0.5, 0.5, 1}, {1.5, 1.5, 2})));
  EXPECT_TRUE(touch.intersect);
  EXPECT_EQ(touch.volume, 0);
  // Apart by the least step: neither.
  const SurfaceOverlap apart = surface_overlap(unit, surface_of(box_surface({0.5, 0.5, 1 + 0x1p-52}, {1.5, 1.5, 2})));
  EXPECT_FALSE(apart.intersect);
  EXPECT_EQ(apart.volume, 0);
  // Identical: the whole box, no contact surface.
  const SurfaceOverlap same = surface_overlap(unit, unit);
  EXPECT_NEAR(same.volume, 1, 1e-15);
  EXPECT_NEAR(length(same.area_a - same.area_b), 0, 1e-15);
  // Sharing the planes y = 0, y = 1 and z = 0 (facing the same way: in
  // neither area): A ∩ B = [0.5,1] x [0,1] x [0,0.5], bounded by A's face
  // x = 1 and B's faces x = 0.5 and z = 0.5.
  const SurfaceOverlap shared = surface_overlap(unit, surface_of(box_surface({0.5, 0, 0}, {1.5, 1, 0.5})));
  EXPECT_NEAR(shared.volume, 0.25, 1e-15);
  const Vec3 n = shared.area_a - shared.area_b;
  EXPECT_NEAR(n.x, 0.5 + 0.5, 1e-15);  // +x 0.5 from A's wall x = 1 (its lower half), minus -x 0.5 from B's wall x = 0.5
  EXPECT_NEAR(n.y, 0, 1e-15);
  EXPECT_NEAR(n.z, -0.5, 1e-15);  // minus B's top, 0.5 facing +z
}

TEST(SurfaceOverlap, ABarAcrossAUsArmsGivesTwoPatches) {
  const Surface u = surface_of(test::u_prism(1));
  EXPECT_NEAR(mass_properties(u).volume, 5, 1e-14);
  const SurfaceOverlap o = surface_overlap(u, surface_of(box_surface({-0.5, 1.25, 0.25}, {3.5, 1.75, 0.75})));
  EXPECT_NEAR(o.volume, 0.5, 1e-14);
  ASSERT_EQ(o.patches.size(), 2u);
  std::vector<Real> xs;
  for (const SurfacePatch& p : o.patches) {
    EXPECT_NEAR(p.volume, 0.25, 1e-14);
    EXPECT_NEAR(p.centroid.y, 1.5, 1e-14);
    EXPECT_NEAR(p.centroid.z, 0.5, 1e-14);
    xs.push_back(p.centroid.x);
  }
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], 0.5, 1e-14);
  EXPECT_NEAR(xs[1], 2.5, 1e-14);
  // Pushed down onto the base: one piece (the base joins the arms), whose
  // contact surface faces up from the U into the bar (the bar's bottom face).
  const SurfaceOverlap low = surface_overlap(u, surface_of(box_surface({-0.5, 0.5, 0.25}, {3.5, 1.75, 0.75})));
  ASSERT_EQ(low.patches.size(), 1u);
  EXPECT_NEAR(low.patches[0].volume, 0.5 * (3 * 0.5 + 2 * 0.75), 1e-14);
  // Apart: no patch.
  EXPECT_TRUE(surface_overlap(u, surface_of(box_surface({1.25, 1.25, 0.25}, {1.75, 1.75, 0.75}))).patches.empty());
}

TEST(SurfaceOverlap, PiecesTouchingAlongAnEdgeAreTwoPatches) {
  // The L and the L turned half way about (1, 1): two unit squares of
  // overlap meeting along the line x = y = 1 only.
  const Surface l = surface_of(test::l_prism(1));
  const Surface turned = surface_of(test::prism({{2, 2}, {0, 2}, {0, 1}, {1, 1}, {1, 0}, {2, 0}},
                                                {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}, 0.25, 0.75));
  const SurfaceOverlap o = surface_overlap(l, turned);
  EXPECT_NEAR(o.volume, 1, 1e-14);
  ASSERT_EQ(o.patches.size(), 2u);
  std::vector<Real> xs;
  for (const SurfacePatch& p : o.patches) {
    EXPECT_NEAR(p.volume, 0.5, 1e-14);
    EXPECT_NEAR(p.centroid.x + p.centroid.y, 2, 1e-14);
    xs.push_back(p.centroid.x);
  }
  std::sort(xs.begin(), xs.end());
  EXPECT_NEAR(xs[0], 0.5, 1e-14);
  EXPECT_NEAR(xs[1], 1.5, 1e-14);
}

// Issue 54, point 7: a piece below kPatchMinRelVolume was left out of the
// patches but kept in the totals (overlap_volume > 0 with patches: []). The
// totals are the patches' sums, on random poses of an L-prism and a box, and
// on a sliver of overlap 1e-13 thick, which is no patch and no volume.
TEST(SurfaceOverlap, TheTotalsAreThePatchesSums) {
  std::mt19937_64 rng(54);
  std::uniform_real_distribution<Real> u(-1, 1);
  const Surface l = surface_of(test::l_prism(1));
  for (int k = 0; k < 200; ++k) {
    const Surface b = surface_of(moved(box_surface({0, 0, 0}, {0.6, 0.5, 0.7}), {1 + u(rng), 1 + u(rng), 0.5 + u(rng)}));
    const SurfaceOverlap o = surface_overlap(l, b);
    Real volume = 0;
    Vec3 area_a, area_b;
    for (const SurfacePatch& p : o.patches) volume += p.volume, area_a += p.area_a, area_b += p.area_b;
    EXPECT_NEAR(o.volume, volume, 1e-15) << k;
    EXPECT_LT(length(o.area_a - area_a) + length(o.area_b - area_b), 1e-14) << k;
    EXPECT_EQ(o.volume > 0, !o.patches.empty()) << k;
  }
  const Surface a = surface_of(box_surface({0, 0, 0}, {1, 1, 1}));
  const Surface sliver = surface_of(box_surface({1 - 1e-13, 0.2, 0.2}, {2, 0.8, 0.8}));
  const SurfaceOverlap o = surface_overlap(a, sliver);
  EXPECT_TRUE(o.intersect);
  EXPECT_TRUE(o.patches.empty());
  EXPECT_EQ(o.volume, 0);
}

// Issue 54, point 8: a curved mesh against itself got a unit normal made of
// round-off (its contact area 7e-16), where identical cubes got none. One
// rule (piece_meeting) decides for the surface grains and the query: a
// torus, a bowl and a box against themselves meet wholly inside, with no
// normal in the query's line; the same moved a little meet by their area.
TEST(SurfaceOverlap, AMeshAgainstItselfHasNoContactNormal) {
  for (const Mesh& m : {test::torus(1, 0.3, 24, 12), test::bowl(0.8, 1, 24, 8), box_surface({0, 0, 0}, {1, 2, 3})}) {
    const Surface s = surface_of(m);
    const SurfaceOverlap same = surface_overlap(s, s);
    EXPECT_NEAR(same.volume, s.volume, 1e-12 * s.volume);
    EXPECT_FALSE(has_contact_area(0.5 * length(same.area_a - same.area_b), same.volume));
    for (const SurfacePatch& p : same.patches)
      EXPECT_EQ(piece_meeting(0.5 * length(p.area_a - p.area_b), p.volume, s.volume), PieceMeeting::WhollyInside);
    const std::string line = io::format_surface_result("1", same, nullptr, s.volume);
    EXPECT_NE(line.find("\"contact_normal\":null"), std::string::npos) << line;
    EXPECT_EQ(line.find("\"normal\":["), std::string::npos) << line;  // nor any patch's
    const SurfaceOverlap near = surface_overlap(s, surface_of(moved(m, {0.01, 0.02, 0})));
    EXPECT_TRUE(has_contact_area(0.5 * length(near.area_a - near.area_b), near.volume));
    EXPECT_NE(io::format_surface_result("1", near, nullptr, s.volume).find("\"contact_normal\":["), std::string::npos);
  }
}

TEST(SurfaceDistance, SeparatedBoxesGiveTheirGapAndWitnesses) {
  const Surface a = surface_of(box_surface({0, 0, 0}, {1, 1, 1}));
  const Surface b = surface_of(box_surface({1.5, 0.25, 0.25}, {2, 0.75, 0.75}));
  const SurfaceDistance d = surface_distance(a, b);
  EXPECT_NEAR(d.distance, 0.5, 1e-14);
  EXPECT_NEAR(d.witness_a.x, 1, 1e-14);
  EXPECT_NEAR(d.witness_b.x, 1.5, 1e-14);
}

}  // namespace
}  // namespace gjkdem
