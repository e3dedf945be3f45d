#include "gjkdem/contact/manifold.hpp"

#include <array>

#include "gjkdem/collide/triangle_contact.hpp"

#include <gtest/gtest.h>

#include <random>

namespace gjkdem {
namespace {

ContactManifold manifold_of(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb) {
  return contact_manifold(a, pa, b, pb, penetration(a, pa, b, pb));
}

TEST(Manifold, BoxOnBoxGivesTheFourCornersOfTheOverlap) {
  const Shape big{Box{{2, 2, 0.5}}}, small{Box{{0.5, 0.5, 0.5}}};
  // The small box sinks 0.01 into the big one's top face, shifted and turned about z.
  const Transform pa = Transform::identity();
  const Transform pb = Transform::from({0.3, -0.2, 0.99}, quat_from_axis_angle({0, 0, 1}, 0.3));
  const ContactManifold m = manifold_of(big, pa, small, pb);
  ASSERT_EQ(m.count, 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(m.points[k].depth, 0.01, 1e-12);
    EXPECT_NEAR(m.points[k].point.z, 0.495, 1e-12);  // midway between the surfaces
    EXPECT_NEAR(m.points[k].normal.z, 1.0, 1e-12);
    // The small box's bottom corners, in the xy-plane.
    const Vec3 local = apply_inverse(pb, m.points[k].point);
    EXPECT_NEAR(std::fabs(local.x), 0.5, 1e-12);
    EXPECT_NEAR(std::fabs(local.y), 0.5, 1e-12);
  }
}

TEST(Manifold, ClipsToTheReferenceFaceAndKeepsTheLargestArea) {
  // Two equal boxes offset diagonally: the overlap of the faces is a square;
  // its corners are the four points.
  const Shape box{Box{{1, 1, 1}}};
  const ContactManifold m = manifold_of(box, Transform::identity(), box, Transform::from({1, 1, 1.98}, {}));
  ASSERT_EQ(m.count, 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_GE(m.points[k].point.x, -1e-12);
    EXPECT_LE(m.points[k].point.x, 1 + 1e-12);
    EXPECT_GE(m.points[k].point.y, -1e-12);
    EXPECT_NEAR(m.points[k].depth, 0.02, 1e-12);
  }
}

TEST(Manifold, EdgeAndVertexContacts) {
  const Shape box{Box{{0.5, 0.5, 0.5}}}, floor{Box{{5, 5, 0.5}}};
  // A box standing on an edge: two points along the edge.
  const Transform edge = Transform::from({0, 0, 0.5 + std::sqrt(0.5) - 0.01}, quat_from_axis_angle({1, 0, 0}, 0.785398163397448));
  const ContactManifold e = manifold_of(floor, Transform::identity(), box, edge);
  EXPECT_EQ(e.count, 2);
  // A box standing on a corner: one point.
  const Quat corner_up = normalized(quat_from_axis_angle(normalized(Vec3{1, -1, 0}), std::acos(1 / std::sqrt(3.0))));
  const Transform vertex = Transform::from({0, 0, 0.5 + std::sqrt(0.75) - 0.01}, corner_up);
  const ContactManifold v = manifold_of(floor, Transform::identity(), box, vertex);
  EXPECT_EQ(v.count, 1);
  EXPECT_NEAR(v.points[0].depth, 0.01, 1e-9);
  // Curved shapes: a single point from the witnesses.
  const ContactManifold s = manifold_of(floor, Transform::identity(), make_sphere(1), Transform::from({0, 0, 1.4}, {}));
  ASSERT_EQ(s.count, 1);
  EXPECT_NEAR(s.points[0].depth, 0.1, 1e-12);
}

TEST(Manifold, RandomContactsStayOnTheSurfaces) {
  std::mt19937_64 rng(91);
  std::uniform_real_distribution<double> u(-1, 1);
  int multi = 0;
  for (int c = 0; c < 200; ++c) {
    std::vector<Vec3> pts;
    for (int i = 0; i < 12; ++i) pts.push_back({u(rng), u(rng), 0.3 * u(rng)});  // flat-ish: big faces
    const Shape a{make_polytope(pts)}, b{Box{{0.6, 0.6, 0.2}}};
    const Transform pb = Transform::from({0.3 * u(rng), 0.3 * u(rng), 0.45 + 0.05 * u(rng)}, quat_from_axis_angle({0, 0, 1}, u(rng)));
    const PenetrationResult r = penetration(a, Transform::identity(), b, pb);
    if (!r.intersect) continue;
    const ContactManifold m = contact_manifold(a, Transform::identity(), b, pb, r);
    ASSERT_GE(m.count, 1);
    ASSERT_LE(m.count, 4);
    multi += m.count > 1;
    for (int k = 0; k < m.count; ++k) {
      // Depths are measured along the reference face's normal, which may differ
      // from the minimum-penetration normal by up to acos(kManifoldFaceCos): they
      // stay positive and of the order of the pair's depth. Each point lies
      // within depth/2 of both shapes (midway between the surfaces).
      EXPECT_GE(m.points[k].depth, -1e-12) << "case " << c;
      EXPECT_LE(m.points[k].depth, 2 * r.depth) << "case " << c;
      const double slack = std::fabs(m.points[k].depth) / 2 + 1e-9;
      EXPECT_LE(distance(Shape{Point{}}, Transform::from(m.points[k].point, {}), a, Transform::identity()).distance, slack);
      EXPECT_LE(distance(Shape{Point{}}, Transform::from(m.points[k].point, {}), b, pb).distance, slack);
    }
  }
  EXPECT_GT(multi, 20);
}

// A ball resting on the shared edge of two wall triangles touches both: the
// seed's triangle query finds one contact per triangle, clustering keeps one.
TEST(Cluster, WallTrianglesSharingAnEdgeGiveOneContact) {
  const Vec3 p0{-1, -1, 0}, p1{1, -1, 0}, p2{1, 1, 0}, p3{-1, 1, 0};  // two triangles, diagonal p0-p2
  const Vec3 centre{0.2, 0.2, 0.49};                                  // above the diagonal
  const double radius = 0.5;
  std::vector<ContactPoint> found;
  for (const auto& tri : {std::array<Vec3, 3>{p0, p1, p2}, std::array<Vec3, 3>{p0, p2, p3}}) {
    const TriangleContact t = triangle_contact(tri[0], tri[1], tri[2], centre, centre, centre, radius);
    ASSERT_TRUE(t.contact);
    found.push_back({(t.witness_a + t.witness_b) * 0.5, t.normal, radius - t.distance});  // normal wall -> ball: +z
  }
  ASSERT_EQ(found.size(), 2u);
  const std::vector<ContactPoint> merged = cluster_contacts(found, kContactMergeRelDist * 2);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_NEAR(merged[0].depth, 0.01, 1e-12);
  EXPECT_NEAR(merged[0].normal.z, 1.0, 1e-12);
}

TEST(Cluster, MergesRedundantContacts) {
  const std::vector<ContactPoint> in = {{{0, 0, 0}, {0, 0, 1}, 0.01},
                                        {{1e-4, 0, 0}, {0, 0, 1}, 0.03},   // same place: merged
                                        {{0, 0, 0}, {1, 0, 0}, 0.02},      // other normal: kept
                                        {{1, 0, 0}, {0, 0, 1}, 0.01}};     // far: kept
  const std::vector<ContactPoint> out = cluster_contacts(in, 1e-3);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_NEAR(out[0].depth, 0.03, 1e-15);
  EXPECT_NEAR(out[0].point.x, 0.75e-4, 1e-15);  // depth-weighted: (0*0.01 + 1e-4*0.03) / 0.04
  EXPECT_NEAR(out[1].normal.x, 1.0, 1e-15);
  EXPECT_NEAR(out[2].point.x, 1.0, 1e-15);
}

}  // namespace
}  // namespace gjkdem
