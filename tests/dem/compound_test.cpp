// Compounds (non-convex grains as rigid unions of convex parts): their mass
// properties equal the exact integration of their parts (checked against
// closed forms and against one polytope of the same solid); overlapping
// parts are refused; contacts are found part against part, so an L standing
// on its two tips rests on both, where its convex hull (one Hertz contact
// on its flat face) rocks; frames draw every part.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/run_output.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem::dem {
namespace {

// An L of two boxes in the xz-plane, touching along z = 0.01: a foot
// x in [0, 0.04], z in [0, 0.01], and a leg x in [0, 0.01], z in [0.01, 0.04].
std::vector<PlacedShape> l_parts() {
  return {{Shape{Box{{0.02, 0.005, 0.005}}}, Transform::from({0.02, 0, 0.005}, Quat{})},
          {Shape{Box{{0.005, 0.005, 0.015}}}, Transform::from({0.005, 0, 0.025}, Quat{})}};
}

// A box's inertia about its centre per unit density: V (h_j^2 + h_k^2) / 3.
Vec3 box_moments(const Vec3& h) {
  const Real v = 8 * h.x * h.y * h.z;
  return Vec3{h.y * h.y + h.z * h.z, h.x * h.x + h.z * h.z, h.x * h.x + h.y * h.y} * (v / 3);
}

TEST(Compound, MassPropertiesAreThoseOfTheParts) {
  const ShapeTemplate t = make_compound_template(l_parts(), false);
  const Real v1 = 0.04 * 0.01 * 0.01, v2 = 0.01 * 0.01 * 0.03;
  EXPECT_NEAR(t.unit_mass.volume, v1 + v2, 1e-18);
  const Vec3 c1{0.02, 0, 0.005}, c2{0.005, 0, 0.025};
  const Vec3 c = (c1 * v1 + c2 * v2) / (v1 + v2);
  EXPECT_LT(length(t.unit_mass.centroid - c), 1e-15);
  // Parallel axes, by hand.
  const Vec3 m1 = box_moments({0.02, 0.005, 0.005}), m2 = box_moments({0.005, 0.005, 0.015});
  const Vec3 d1 = c1 - c, d2 = c2 - c;
  const Real ixx = m1.x + v1 * (d1.y * d1.y + d1.z * d1.z) + m2.x + v2 * (d2.y * d2.y + d2.z * d2.z);
  const Real iyy = m1.y + v1 * (d1.x * d1.x + d1.z * d1.z) + m2.y + v2 * (d2.x * d2.x + d2.z * d2.z);
  const Real izz = m1.z + v1 * (d1.x * d1.x + d1.y * d1.y) + m2.z + v2 * (d2.x * d2.x + d2.y * d2.y);
  const Real ixz = -(v1 * d1.x * d1.z + v2 * d2.x * d2.z);
  const Mat3& i = t.unit_mass.inertia;
  EXPECT_NEAR(i.row[0][0], ixx, 1e-12 * ixx);
  EXPECT_NEAR(i.row[1][1], iyy, 1e-12 * iyy);
  EXPECT_NEAR(i.row[2][2], izz, 1e-12 * izz);
  EXPECT_NEAR(i.row[0][2], ixz, 1e-12 * ixx);
  EXPECT_NEAR(i.row[2][0], ixz, 1e-12 * ixx);
  EXPECT_NEAR(i.row[0][1], 0, 1e-12 * ixx);
  // Reach: the farthest corner from the centre of mass.
  Real reach = 0;
  for (const Vec3 corner : {Vec3{0.04, 0.005, 0}, Vec3{0.04, -0.005, 0.01}, Vec3{0, 0.005, 0.04}, Vec3{0.01, 0.005, 0.04}})
    reach = std::fmax(reach, length(corner - c));
  EXPECT_GE(t.reach, reach);
}

TEST(Compound, TwoHalvesOfATurnedBoxWeighAsTheBox) {
  // A box cut in two along its long axis, turned: the compound's mass
  // properties equal those of the whole box as a polytope.
  const Quat q = normalized(Quat{0.9, 0.2, -0.3, 0.25});
  const Transform turn = Transform::from({0.1, -0.2, 0.05}, q);
  std::vector<PlacedShape> halves;
  for (const Real side : {-1.0, 1.0})
    halves.push_back({Shape{Box{{0.01, 0.02, 0.03}}}, compose(turn, Transform::from({side * 0.01, 0, 0}, Quat{}))});
  std::vector<Vec3> corners;
  for (int k = 0; k < 8; ++k)
    corners.push_back(apply(turn, {(k & 1) ? 0.02 : -0.02, (k & 2) ? 0.02 : -0.02, (k & 4) ? 0.03 : -0.03}));
  const ShapeTemplate compound = make_compound_template(halves, false);
  const ShapeTemplate whole = make_template(Shape{make_polytope(corners)});
  EXPECT_NEAR(compound.unit_mass.volume, whole.unit_mass.volume, 1e-14 * whole.unit_mass.volume);
  EXPECT_LT(length(compound.unit_mass.centroid - whole.unit_mass.centroid), 1e-14);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(compound.unit_mass.inertia.row[r][k], whole.unit_mass.inertia.row[r][k], 1e-12 * 1e-9);
  EXPECT_LT(length(compound.principal.moments - whole.principal.moments), 1e-12 * length(whole.principal.moments));
}

TEST(Compound, OverlappingPartsAreRefused) {
  WorldBuilder b;
  const std::uint32_t m = b.add_material({"rock", 2500, 1e7});
  std::vector<PlacedShape> parts = l_parts();
  parts[1].pose.translation.z -= 0.001;  // the leg sinks 1 mm into the foot
  try {
    b.add_body({.shape = {.parts = parts}, .material = m, .label = "ell"});
    ADD_FAILURE() << "overlapping parts accepted";
  } catch (const BuildError& e) {
    EXPECT_NE(std::string(e.what()).find("ell: parts 0 and 1 overlap by 0.001"), std::string::npos) << e.what();
  }
  b.add_body({.shape = {.parts = l_parts()}, .material = m, .label = "touching"});  // touching is fine
}

// The L turned so that its corner is on top and its two tips stand on a
// plane (the bisector of its legs points down), set rocking, under the
// Hertz law, for 1 s.
// Returns the world; `hull`: the L's convex hull instead.
World standing_ell(bool hull) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder b(settings);
  const std::uint32_t m = b.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  b.add_plane({}, {0, 0, 1}, m, "floor");
  BodyShape shape{.parts = l_parts()};
  if (hull) shape = {make_compound_template(l_parts(), false).shape, {}};
  // 135 degrees about y: the legs' bisector (1, 0, 1) points down; the tips
  // are then 0.03536 m below the corner, at z = 0 when the corner is there.
  const Quat turn = quat_from_axis_angle({0, 1, 0}, 0.75 * kPi);
  // Set rocking in its plane (2 rad/s about y).
  b.add_body({.shape = shape, .material = m, .position = {0, 0, 0.0354 + 1e-4}, .rotation = turn,
              .angular_velocity = {0, 2, 0}, .label = "ell"});
  World w = b.build();
  RunState run = plan_run(1.0, critical_time_step(w), 1.0);
  const RunOutcome outcome = dem::run(w, run, {});
  EXPECT_EQ(outcome.status, RunStatus::Completed) << outcome.error;
  return w;
}

TEST(Compound, AnLStandsOnBothFeetWhereItsHullRocks) {
  const World ell = standing_ell(false);
  std::set<int> parts;
  for (const StepContact& c : ell.results.contacts)
    if (c.active) parts.insert(c.part_b);
  EXPECT_EQ(parts, (std::set<int>{0, 1})) << "both feet carry the L";
  const Real spin = length(angular_velocity_of(ell, ell.bodies[0]));
  EXPECT_LT(spin, 0.01) << "the L rests";
  EXPECT_LT(length(ell.bodies[0].velocity), 1e-3);

  const World hull = standing_ell(true);
  EXPECT_EQ(hull.stats.contacts, 1) << "the hull's flat face is one Hertz contact";
  EXPECT_GT(length(angular_velocity_of(hull, hull.bodies[0])), 10 * spin) << "the hull should rock";
}

TEST(Compound, FramesDrawEveryPart) {
  const ShapeTemplate t = make_compound_template(l_parts(), false);
  const io::DisplayMesh m = io::display_mesh(t);
  EXPECT_EQ(m.polygon_begin.size(), 1u + 12u) << "six faces a box";
  for (const Vec3& v : m.vertices)
    EXPECT_TRUE(v.x >= -1e-12 && v.x <= 0.04 + 1e-12 && v.z >= -1e-12 && v.z <= 0.04 + 1e-12);
}

}  // namespace
}  // namespace gjkdem::dem
