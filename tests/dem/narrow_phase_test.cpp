// The narrow phase of a step (narrow_phase.hpp) on its own, against closed
// forms computed here:
// - two spheres under the penetration laws: depth r1 + r2 - d along the line
//   of centres, the point halfway between the surfaces, apart when d > r1 + r2;
//   under the volume law the lens of two spherical caps;
// - two axis-aligned cubes overlapping in a box (volume law): its volume, the
//   vector area S_A of the faces on A's boundary, its normal and depth, and
//   the moment sum (face centroid x area) / |S_A|, the point on that line;
// - a box pressed into a tilted plane wall by h: volume area h, depth h,
//   depth integral area h^2 / 2 under the volume law, depth h under Hertz;
// - A and B swapped: the same contact seen from the other side (normal and
//   moment negated, depth, volume, area and point the same);
// - shapes a law has no computation for are Unsupported, not Apart;
// - merge_wall_contacts: a sphere over the shared edge of two coplanar
//   triangles of one mesh gets one contact (the deeper triangle's, at the
//   depth-weighted mean point), while contacts with triangles of two meshes,
//   or with two faces of one mesh folded by more than the merge's angle,
//   are left as they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "gjkdem/dem/narrow_phase.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

void expect_vec_near(const Vec3& got, const Vec3& want, Real tol, const char* what) {
  EXPECT_NEAR(got.x, want.x, tol) << what;
  EXPECT_NEAR(got.y, want.y, tol) << what;
  EXPECT_NEAR(got.z, want.z, tol) << what;
}

ContactGeometry contact(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb, ContactModel model) {
  GjkCache cache;
  OverlapWorkspace work;
  return body_contact(a, pa, b, pb, model, &cache, work);
}

// Two spheres (points with margins) along a slanted axis, their centres d
// apart.
TEST(NarrowPhaseTest, SpheresUnderThePenetrationLawsGiveTheAnalyticOverlap) {
  const Real r1 = 0.01, r2 = 0.015;
  const Vec3 c1{0.1, -0.2, 0.3}, u = normalized(Vec3{1, 2, -0.5});
  for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear}) {
    for (const Real overlap : {1e-6, 1e-4, 2e-3}) {
      const Real d = r1 + r2 - overlap;
      const Vec3 c2 = c1 + u * d;
      const ContactGeometry g =
          contact(make_sphere(r1), Transform::from(c1, {}), make_sphere(r2), Transform::from(c2, {}), model);
      ASSERT_EQ(g.status, GeometryStatus::Touching) << "overlap " << overlap;
      EXPECT_NEAR(g.depth, overlap, 1e-12) << "overlap " << overlap;
      expect_vec_near(g.normal, u, 1e-12, "normal a -> b");
      // Halfway between A's deepest point c1 + u r1 and B's c2 - u r2.
      const Vec3 point = ((c1 + u * r1) + (c2 - u * r2)) * 0.5;
      expect_vec_near(g.point, point, 1e-12, "point");
      expect_vec_near(g.moment, cross(point, u), 1e-12, "moment of a unit normal force");
    }
    // A gap of 1e-6 m: not touching.
    const ContactGeometry apart = contact(make_sphere(r1), Transform::from(c1, {}), make_sphere(r2),
                                          Transform::from(c1 + u * (r1 + r2 + 1e-6), {}), model);
    EXPECT_EQ(apart.status, GeometryStatus::Apart);
  }
}

// Under the volume law, two spheres overlap in a lens: two caps of heights
// h1, h2 cut by the plane of the circle where the spheres meet.
TEST(NarrowPhaseTest, SpheresUnderTheVolumeLawOverlapInALens) {
  const Real r1 = 0.01, r2 = 0.006;
  const Vec3 c1{-0.02, 0.05, 0.01}, u = normalized(Vec3{-1, 0.3, 2});
  for (const Real d : {0.0155, 0.012, 0.0075}) {
    const ContactGeometry g = contact(make_sphere(r1), Transform::from(c1, {}), make_sphere(r2),
                                      Transform::from(c1 + u * d, {}), ContactModel::Volume);
    ASSERT_EQ(g.status, GeometryStatus::Touching) << "d = " << d;
    const Real x = (d * d + r1 * r1 - r2 * r2) / (2 * d);  // from c1 to the circle's plane
    const Real h1 = r1 - x, h2 = r2 - (d - x);
    const Real volume = kPi * h1 * h1 * (3 * r1 - h1) / 3 + kPi * h2 * h2 * (3 * r2 - h2) / 3;
    const Real area = kPi * (r1 * r1 - x * x);  // the circle's disc: S_A
    EXPECT_NEAR(g.volume, volume, 1e-12 * volume) << "d = " << d;
    EXPECT_NEAR(g.area, area, 1e-12 * area) << "d = " << d;
    EXPECT_NEAR(g.depth, volume / area, 1e-12 * volume / area) << "d = " << d;
    expect_vec_near(g.normal, u, 1e-12, "normal a -> b");
  }
  const ContactGeometry apart = contact(make_sphere(r1), Transform::from(c1, {}), make_sphere(r2),
                                        Transform::from(c1 + u * (r1 + r2 + 1e-7), {}), ContactModel::Volume);
  EXPECT_EQ(apart.status, GeometryStatus::Apart);
}

// Cubes of half-size h: A at the origin, B at (2h - s, dy, dz). They overlap
// in the box [h - s, h] x [dy - h, h] x [-h, dz + h] (dy > 0 > dz); of its six
// faces, x = h, y = h and z = -h lie on A's boundary.
TEST(NarrowPhaseTest, OverlappingCubesUnderTheVolumeLawGiveTheOverlapBox) {
  const Real h = 0.01;
  const Shape cube{Box{{h, h, h}}};
  const Vec3 origin{0.3, -0.1, 0.2};  // A's centre: the world origin is elsewhere, the moment sees it
  for (const Real s : {1e-4, 1e-3, 4e-3}) {
    const Real dy = 0.003, dz = -0.002;
    const ContactGeometry g = contact(cube, Transform::from(origin, {}), cube,
                                      Transform::from(origin + Vec3{2 * h - s, dy, dz}, {}), ContactModel::Volume);
    ASSERT_EQ(g.status, GeometryStatus::Touching) << "s = " << s;
    const Vec3 lo = origin + Vec3{h - s, dy - h, -h}, hi = origin + Vec3{h, h, dz + h};
    const Vec3 size = hi - lo;
    const Real volume = size.x * size.y * size.z;
    EXPECT_NEAR(g.volume, volume, 1e-12 * volume) << "s = " << s;
    // The faces on A's boundary: outward area vectors and centroids.
    const Vec3 mid = (lo + hi) * 0.5;
    const Vec3 area_x{size.y * size.z, 0, 0}, area_y{0, size.x * size.z, 0}, area_z{0, 0, -size.x * size.y};
    const Vec3 at_x{hi.x, mid.y, mid.z}, at_y{mid.x, hi.y, mid.z}, at_z{mid.x, mid.y, lo.z};
    const Vec3 s_a = area_x + area_y + area_z;
    const Real area = length(s_a);
    EXPECT_NEAR(g.area, area, 1e-12 * area) << "s = " << s;
    EXPECT_NEAR(g.depth, volume / area, 1e-12 * volume / area) << "s = " << s;
    expect_vec_near(g.normal, s_a / area, 1e-12, "normal: S_A / |S_A|");
    EXPECT_GT(g.normal.x, 0.9) << "mostly along +x, the axis of the slab";
    const Vec3 moment = (cross(at_x, area_x) + cross(at_y, area_y) + cross(at_z, area_z)) / area;
    expect_vec_near(g.moment, moment, 1e-12, "moment (face centroid x area) / |S_A|");
    // The point lies on the line of action (the moment less its twisting
    // part about the normal), level with the overlap's centroid.
    expect_vec_near(cross(g.point, g.normal), moment - g.normal * dot(moment, g.normal), 1e-12, "line of action");
    EXPECT_NEAR(dot(g.point - mid, g.normal), 0, 1e-12) << "s = " << s;
  }
  const ContactGeometry apart = contact(cube, Transform::from(origin, {}), cube,
                                        Transform::from(origin + Vec3{2 * h + 1e-6, 0.003, -0.002}, {}),
                                        ContactModel::Volume);
  EXPECT_EQ(apart.status, GeometryStatus::Apart);
}

// A box of half extents (a, b, c) with its bottom face parallel to a tilted
// plane wall and sunk into it by h (the box also turned about the normal).
TEST(NarrowPhaseTest, ABoxSunkIntoAPlaneByHGivesAreaTimesH) {
  const Real a = 0.02, b = 0.01, c = 0.005;
  const Shape box{Box{{a, b, c}}};
  PlaneWall wall;
  wall.point = {0.1, 0.2, -0.3};
  wall.normal = normalized(Vec3{1, 1, 2});
  // The box's +z axis along the normal, then turned about it by 0.4 rad.
  const Vec3 z{0, 0, 1};
  const Quat tilt = quat_from_axis_angle(normalized(cross(z, wall.normal)), std::acos(dot(z, wall.normal)));
  const Quat q = quat_from_axis_angle(wall.normal, 0.4) * tilt;
  ASSERT_NEAR(length(rotate(q, z) - wall.normal), 0, 1e-14);
  const Vec3 along = normalized(cross(wall.normal, Vec3{1, 0, 0}));  // some direction in the plane
  for (const Real h : {1e-5, 1e-3, 4e-3}) {
    const Vec3 centre = wall.point + along * 0.07 + wall.normal * (c - h);
    const Transform pose = Transform::from(centre, q);
    const Vec3 below = centre - wall.normal * (c - h);  // the bottom face's centre projected on the plane
    const ContactGeometry v = plane_contact(wall, box, pose, ContactModel::Volume);
    ASSERT_EQ(v.status, GeometryStatus::Touching) << "h = " << h;
    const Real area = 4 * a * b;
    EXPECT_NEAR(v.volume, area * h, 1e-9 * area * h) << "h = " << h;
    EXPECT_NEAR(v.area, area, 1e-9 * area) << "h = " << h;
    EXPECT_NEAR(v.depth, h, 1e-9 * h) << "h = " << h;
    EXPECT_NEAR(v.depth_integral, area * h * h / 2, 1e-9 * area * h * h) << "h = " << h;
    expect_vec_near(v.normal, wall.normal, 1e-15, "normal: the wall's");
    expect_vec_near(v.point, below, 1e-12, "point: on the wall below the centroid");
    expect_vec_near(v.moment, cross(below, wall.normal), 1e-12, "moment");
    for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear}) {
      const ContactGeometry p = plane_contact(wall, box, pose, model);
      ASSERT_EQ(p.status, GeometryStatus::Touching) << "h = " << h;
      EXPECT_NEAR(p.depth, h, 1e-12) << "h = " << h;
      expect_vec_near(p.normal, wall.normal, 1e-15, "normal: the wall's");
      expect_vec_near(p.point, below, 1e-12, "point: the middle of the face on the wall");
    }
  }
  const Transform lifted = Transform::from(wall.point + wall.normal * (c + 1e-6), q);
  for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear, ContactModel::Volume})
    EXPECT_EQ(plane_contact(wall, box, lifted, model).status, GeometryStatus::Apart);
  // A sphere under Hertz: depth r - distance, pushed at the middle of the
  // disc the wall cuts from it, the centre's foot on the wall.
  const Real r = 0.01, depth = 2e-4;
  const Vec3 centre = wall.point + along * 0.03 + wall.normal * (r - depth);
  const ContactGeometry s = plane_contact(wall, make_sphere(r), Transform::from(centre, {}), ContactModel::Hertz);
  ASSERT_EQ(s.status, GeometryStatus::Touching);
  EXPECT_NEAR(s.depth, depth, 1e-14);
  expect_vec_near(s.point, centre - wall.normal * (r - depth), 1e-14, "sphere: the centre's foot on the wall");
}

// Swapping A and B describes the same contact from B's side.
TEST(NarrowPhaseTest, SwappingTheBodiesNegatesTheNormalAndMoment) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> unit(-1, 1);
  for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear, ContactModel::Volume}) {
    int touching = 0;
    for (int trial = 0; trial < 30; ++trial) {
      const Shape a = random_polyhedron(12, 0.02, rng), b = random_polyhedron(9, 0.015, rng);
      const Vec3 ca{unit(rng), unit(rng), unit(rng)};
      const Vec3 dir = normalized(Vec3{unit(rng), unit(rng), unit(rng)});
      const Transform pa = Transform::from(ca, random_rotation(rng));
      const Transform pb = Transform::from(ca + dir * 0.008, random_rotation(rng));
      const ContactGeometry ab = contact(a, pa, b, pb, model), ba = contact(b, pb, a, pa, model);
      ASSERT_EQ(ab.status, ba.status) << "trial " << trial;
      if (ab.status != GeometryStatus::Touching) continue;
      ++touching;
      const Real scale = std::max(ab.depth, 1e-6);
      EXPECT_NEAR(ba.depth, ab.depth, 1e-9 * scale) << "trial " << trial;
      expect_vec_near(ba.normal, -ab.normal, 1e-7, "normal negated");
      expect_vec_near(ba.point, ab.point, 1e-9, "same point");
      expect_vec_near(ba.moment, -ab.moment, 1e-9, "moment negated");
      if (model == ContactModel::Volume) {
        EXPECT_NEAR(ba.volume, ab.volume, 1e-12 * ab.volume) << "trial " << trial;
        EXPECT_NEAR(ba.area, ab.area, 1e-12 * ab.area) << "trial " << trial;
      }
    }
    EXPECT_GE(touching, 20) << "most trials overlap";
  }
}

TEST(NarrowPhaseTest, ShapesTheVolumeLawCannotClipAreUnsupported) {
  const Shape ellipsoid{Ellipsoid{{0.01, 0.008, 0.006}}}, cylinder{Cylinder{0.01, 0.01}};
  const ContactGeometry g = contact(ellipsoid, Transform::from({0, 0, 0}, {}), cylinder,
                                    Transform::from({0.015, 0, 0}, {}), ContactModel::Volume);
  EXPECT_EQ(g.status, GeometryStatus::Unsupported);
  // The same pair under Hertz is a touching contact: GJK/EPA takes any convex shape.
  EXPECT_EQ(contact(ellipsoid, Transform::from({0, 0, 0}, {}), cylinder, Transform::from({0.015, 0, 0}, {}),
                    ContactModel::Hertz)
                .status,
            GeometryStatus::Touching);
  PlaneWall floor;
  floor.normal = {0, 0, 1};
  EXPECT_EQ(plane_contact(floor, ellipsoid, Transform::from({0, 0, 0.005}, {}), ContactModel::Volume).status,
            GeometryStatus::Unsupported);
  EXPECT_EQ(plane_contact(floor, ellipsoid, Transform::from({0, 0, 0.005}, {}), ContactModel::Hertz).status,
            GeometryStatus::Touching);
}

// Walls for the merge tests: a sphere of radius kR (body 0) and the mesh
// pieces `add` makes, under Hertz, the pieces' thickness 2 kM.
constexpr Real kR = 0.01, kM = 0.001;

template <class Add>
World sphere_and_mesh(const Vec3& sphere_at, Add add) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder builder(settings);
  builder.accept_initial_overlaps();
  const std::uint32_t m = builder.add_material({"m", 1000, 1e7, 0.3, 0.5, 0.5});
  builder.add_body({.shape = {make_sphere(kR), {}}, .material = m, .position = sphere_at, .label = "sphere"});
  add(builder, m);
  return builder.build();
}

// The sphere against every wall piece, as the step lists them (a: the
// sphere, the smaller index; b: the piece).
std::vector<StepContact> piece_contacts(const World& w) {
  std::vector<StepContact> out;
  const Body& s = w.bodies[0];
  for (std::uint32_t i = 1; i < w.bodies.size(); ++i) {
    StepContact c;
    c.a = 0;
    c.b = i;
    c.geometry = contact(w.templates[s.shape].shape, shape_pose(w, s), w.templates[w.bodies[i].shape].shape,
                         shape_pose(w, w.bodies[i]), ContactModel::Hertz);
    c.active = c.geometry.status == GeometryStatus::Touching;
    out.push_back(c);
  }
  return out;
}

// The square [-0.05, 0.05]^2 at z = 0 split along its diagonal y = x.
const Vec3 kSquare[4] = {{-0.05, -0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0}, {-0.05, 0.05, 0}};
const std::array<std::uint32_t, 3> kHalves[2] = {{0, 1, 2}, {0, 2, 3}};

// The sphere just off the shared edge, on the side of triangle 0 (y < x).
const Vec3 kOverEdge{0.0007, -0.0007, kR + kM - 2e-4};

TEST(NarrowPhaseTest, MergeMakesOneContactOfTwoCoplanarTrianglesOfOneMesh) {
  const World w = sphere_and_mesh(kOverEdge, [](WorldBuilder& b, std::uint32_t m) {
    b.add_mesh_walls(kSquare, kHalves, 2 * kM, m, "square");
  });
  ASSERT_EQ(w.bodies.size(), 3u);
  ASSERT_EQ(w.bodies[1].group, w.bodies[2].group);
  ASSERT_GT(w.bodies[1].group, 0u);
  std::vector<StepContact> contacts = piece_contacts(w);
  const std::vector<StepContact> before = contacts;
  ASSERT_TRUE(before[0].active && before[1].active) << "the sphere touches both triangles";
  // Triangle 0 holds the point below the sphere: 2e-4 deep; the other only
  // its edge, less deep.
  const std::size_t deep = before[0].geometry.depth > before[1].geometry.depth ? 0 : 1;
  EXPECT_NEAR(before[deep].geometry.depth, 2e-4, 1e-12);
  EXPECT_LT(before[1 - deep].geometry.depth, before[deep].geometry.depth);

  // The edge's contact is the face's seen over the seam (its normal tilted
  // off the triangle's): dropped, the face's kept as it was, under the
  // sphere's centre.
  merge_wall_contacts(w.bodies, w.templates, contacts);
  EXPECT_TRUE(contacts[deep].active) << "the deeper triangle carries the contact";
  EXPECT_FALSE(contacts[1 - deep].active);
  const ContactGeometry& g = contacts[deep].geometry;
  EXPECT_EQ(g.depth, before[deep].geometry.depth) << "the deepest depth";
  EXPECT_EQ(g.normal, before[deep].geometry.normal) << "the deepest normal";
  expect_vec_near(g.point, before[deep].geometry.point, 1e-15, "the face's point");
  expect_vec_near({g.point.x, g.point.y, 0}, {w.bodies[0].position.x, w.bodies[0].position.y, 0}, 1e-15,
                  "under the sphere's centre");
  expect_vec_near(g.moment, cross(g.point, g.normal), 1e-15, "moment at the point");
}

TEST(NarrowPhaseTest, MergeLeavesTrianglesOfTwoMeshesAndPlaneContactsAlone) {
  const World w = sphere_and_mesh(kOverEdge, [](WorldBuilder& b, std::uint32_t m) {
    b.add_mesh_walls(kSquare, std::span(kHalves, 1), 2 * kM, m, "first half");
    b.add_mesh_walls(kSquare, std::span(kHalves + 1, 1), 2 * kM, m, "second half");
  });
  ASSERT_EQ(w.bodies.size(), 3u);
  ASSERT_NE(w.bodies[1].group, w.bodies[2].group);
  std::vector<StepContact> contacts = piece_contacts(w);
  // A plane wall's contact with the same sphere: merging never looks at it.
  StepContact plane;
  plane.a = 0;
  plane.b = 0;
  plane.a_is_plane = true;
  plane.active = true;
  plane.geometry.status = GeometryStatus::Touching;
  plane.geometry.normal = {0, 0, 1};
  plane.geometry.point = {0, 0, kM};
  plane.geometry.depth = 2e-4;
  contacts.push_back(plane);
  const std::vector<StepContact> before = contacts;
  ASSERT_TRUE(before[0].active && before[1].active);
  merge_wall_contacts(w.bodies, w.templates, contacts);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    EXPECT_TRUE(contacts[k].active) << "contact " << k;
    EXPECT_EQ(contacts[k].geometry.depth, before[k].geometry.depth) << "contact " << k;
    expect_vec_near(contacts[k].geometry.point, before[k].geometry.point, 1e-15, "point (a cluster of one: its own)");
    EXPECT_EQ(contacts[k].geometry.normal, before[k].geometry.normal) << "contact " << k;
  }
}

TEST(NarrowPhaseTest, MergeKeepsContactsWithFacesFoldedBeyondItsAngleApart) {
  // One mesh: a valley of two triangles meeting along the y axis, each
  // rising at 15 degrees, so their normals are 30 degrees apart (cos 0.87,
  // below the merge's 0.9) while the sphere's two contact points lie closer
  // than its radius: only the normals keep the contacts apart. The sphere is
  // 1e-4 deep in the face rising to +x, 3e-4 in the other.
  const Real theta = kPi / 12, c = std::cos(theta), s = std::sin(theta);
  const Vec3 valley[4] = {{0, -0.05, 0}, {0, 0.05, 0}, {0.05 * c, 0, 0.05 * s}, {-0.05 * c, 0, 0.05 * s}};
  const std::array<std::uint32_t, 3> faces[2] = {{0, 1, 2}, {0, 3, 1}};
  const Real dist_up = kR + kM - 1e-4, dist_down = kR + kM - 3e-4;  // centre to each face's plane
  // n = (-s, 0, c) for the face rising to +x, (s, 0, c) for the other.
  const Vec3 centre{(dist_down - dist_up) / (2 * s), 0.002, (dist_up + dist_down) / (2 * c)};
  const World w = sphere_and_mesh(centre, [&](WorldBuilder& b, std::uint32_t m) {
    b.add_mesh_walls(valley, faces, 2 * kM, m, "valley");
  });
  ASSERT_EQ(w.bodies.size(), 3u);
  ASSERT_EQ(w.bodies[1].group, w.bodies[2].group);
  std::vector<StepContact> contacts = piece_contacts(w);
  const std::vector<StepContact> before = contacts;
  ASSERT_TRUE(before[0].active && before[1].active);
  EXPECT_NEAR(before[0].geometry.depth, 1e-4, 1e-12) << "the face rising to +x";
  EXPECT_NEAR(before[1].geometry.depth, 3e-4, 1e-12) << "the other";
  EXPECT_NEAR(dot(before[0].geometry.normal, before[1].geometry.normal), std::cos(2 * theta), 1e-12);
  EXPECT_LT(length(before[0].geometry.point - before[1].geometry.point), kR) << "within the merge distance";
  merge_wall_contacts(w.bodies, w.templates, contacts);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    EXPECT_TRUE(contacts[k].active) << "contact " << k;
    EXPECT_EQ(contacts[k].geometry.depth, before[k].geometry.depth) << "contact " << k;
    EXPECT_EQ(contacts[k].geometry.normal, before[k].geometry.normal) << "contact " << k;
    expect_vec_near(contacts[k].geometry.point, before[k].geometry.point, 1e-15, "point (a cluster of one: its own)");
  }
}

}  // namespace
}  // namespace gjkdem::dem
