// Compounds with surface parts (BodyShape::surface_parts): a closed surface,
// convex or not, as a part of a compound, met by its patches.
// - A compound of one surface part pushes as the surface grain does, on a
//   plane, a block and a surface grain (volume law) and on a mesh floor
//   (Hertz, margin model).
// - A U of one surface with a box filling its hollow is the solid box it
//   makes: the same mass properties, the same push on a plane (three
//   contacts, one per foot and one for the box), and it stands on them.
// - Parts that overlap are refused, naming them; a part in the hollow of a
//   surface is not an overlap; a surface part is one shell; a surface grain
//   given parts too is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/surface_contact.hpp"
#include "gjkdem/dem/world.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/run_output.hpp"
#include "shape/surface_shapes.hpp"

namespace gjkdem::dem {
namespace {

std::shared_ptr<const Surface> shared(const test::Mesh& m) {
  return std::make_shared<const Surface>(test::surface_of(m));
}

// A U 3 cm wide, its arms pointing down (-z), its prism axis along y: x in
// [0, 3] cm, y in [0, 1], z in [-2, 0]; the hollow x in [1, 2], z in [-2, -1].
std::shared_ptr<const Surface> u_arms_down() {
  test::Mesh u = test::u_prism(1);
  for (Vec3& v : u.vertices) v = Vec3{v.x, v.z, -v.y} * 0.01;
  return shared(u);
}

// The box that fills the U's hollow, in the U's frame.
const PlacedShape kHollowBox{Shape{Box{{0.005, 0.005, 0.005}}}, Transform::from({0.015, 0.005, -0.015}, Quat{})};

WorldSettings volume_settings() {
  WorldSettings s;
  s.model = ContactModel::Volume;
  s.volume_stiffness = 1e9;
  return s;
}

// The force and torque on a body of `shape` placed by `place` (after the
// build), the world built by `partners`; and how many contacts it has.
struct Push {
  Vec3 force, torque;
  int contacts = 0;
};
Push push_of(const WorldSettings& settings, const BodyShape& shape, const std::function<void(WorldBuilder&, std::uint32_t)>& partners,
             const std::function<void(Body&, const ShapeTemplate&)>& place) {
  WorldBuilder builder(settings);
  const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  partners(builder, rock);
  builder.add_body({.shape = shape, .material = rock, .position = {0, 0, 0.5}});
  World w = builder.build();
  Body& b = w.bodies.back();
  place(b, w.templates[b.shape]);
  const StepReport report = compute_forces_now(w);
  EXPECT_EQ(report.status, StepStatus::Ok);
  return {b.force, b.torque, w.stats.contacts};
}

// Places a body turned by `tilt` (its shape frame), its lowest point
// `depth` below z = 0, its centre of mass above (0.001, 0.002).
std::function<void(Body&, const ShapeTemplate&)> placed(const Quat& tilt, Real depth) {
  return [=](Body& b, const ShapeTemplate& t) {
    b.orientation = normalized(tilt * t.principal.rotation);
    const Vec3 low = rotate(tilt, support(t.shape, rotate(conjugate(tilt), Vec3{0, 0, -1})) - t.unit_mass.centroid);
    b.position = {0.001, 0.002, -depth - low.z};
  };
}

TEST(SurfaceCompound, OneSurfacePartPushesAsTheSurfaceGrain) {
  const std::shared_ptr<const Surface> u = u_arms_down();
  const Quat tilt = normalized(Quat{1, 0.003, -0.004, 0.01});  // both feet dip in
  const Real depth = 5e-4;
  const std::function<void(WorldBuilder&, std::uint32_t)> partners[] = {
      [](WorldBuilder& b, std::uint32_t m) { b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor"); },
      [](WorldBuilder& b, std::uint32_t m) {
        b.add_body({.shape = {Shape{Box{{0.05, 0.05, 0.01}}}, {}}, .material = m, .position = {0, 0, -0.01}, .fixed = true});
      },
      [](WorldBuilder& b, std::uint32_t m) {  // a surface slab, its top at z = 0
        b.add_body({.shape = {.surface = shared(test::box_surface({-0.05, -0.05, -0.02}, {0.05, 0.05, 0}))},
                    .material = m, .fixed = true});
      }};
  for (std::size_t k = 0; k < std::size(partners); ++k) {
    const Push grain = push_of(volume_settings(), {.surface = u}, partners[k], placed(tilt, depth));
    const Push part = push_of(volume_settings(), {.surface_parts = {{u, {}}}}, partners[k], placed(tilt, depth));
    EXPECT_EQ(grain.contacts, 2) << k;  // one a foot
    EXPECT_EQ(part.contacts, grain.contacts) << k;
    EXPECT_GT(length(grain.force), 1e-3) << k;
    EXPECT_LT(length(part.force - grain.force), 1e-9 * length(grain.force)) << k;
    EXPECT_LT(length(part.torque - grain.torque), 1e-9 * length(grain.force) * 0.01) << k;
  }
  // Under the Hertz law on a mesh floor (the margin model): its pieces are
  // triangles with a margin of 1 mm, the seam y = 0.5 cm under both feet.
  WorldSettings hertz;
  hertz.model = ContactModel::Hertz;
  const auto mesh_floor = [](WorldBuilder& b, std::uint32_t m) {
    const std::vector<Vec3> v{{-0.1, -0.1, 0}, {0.1, -0.1, 0}, {0.1, 0.005, 0}, {-0.1, 0.005, 0}, {0.1, 0.1, 0}, {-0.1, 0.1, 0}};
    const std::vector<std::array<std::uint32_t, 3>> t{{0, 1, 2}, {0, 2, 3}, {3, 2, 4}, {3, 4, 5}};
    b.add_mesh_walls(v, t, 0.002, m, "floor");
  };
  const Push grain = push_of(hertz, {.surface = u}, mesh_floor, placed(tilt, depth));
  const Push part = push_of(hertz, {.surface_parts = {{u, {}}}}, mesh_floor, placed(tilt, depth));
  EXPECT_EQ(grain.contacts, 2);
  EXPECT_EQ(part.contacts, 2);
  EXPECT_GT(length(grain.force), 1e-3);
  EXPECT_LT(length(part.force - grain.force), 1e-9 * length(grain.force));
  EXPECT_LT(length(part.torque - grain.torque), 1e-9 * length(grain.force) * 0.01);
}

TEST(SurfaceCompound, AUAndTheBoxInItsHollowAreTheSolidBox) {
  const BodyShape filled{.parts = {kHollowBox}, .surface_parts = {{u_arms_down(), {}}}};
  const BodyShape solid{Shape{Box{{0.015, 0.005, 0.01}}}, Transform::from({0.015, 0.005, -0.01}, Quat{})};
  // The same mass properties.
  const ShapeTemplate tf = make_compound_template(filled.parts, false, filled.surface_parts);
  const ShapeTemplate ts = make_template(solid.shape);
  EXPECT_NEAR(tf.unit_mass.volume, ts.unit_mass.volume, 1e-15);
  EXPECT_LT(length(tf.unit_mass.centroid - solid.pose.translation), 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_LT(length(tf.unit_mass.inertia.row[i] - ts.unit_mass.inertia.row[i]), 1e-15) << i;
  // The same push, tilted onto a plane so that all three bottoms dip in:
  // the volume law's forces add over the pieces of one flat overlap.
  const Quat tilt = normalized(Quat{1, 0.003, -0.004, 0.01});
  const Real depth = 5e-4;
  const auto floor = [](WorldBuilder& b, std::uint32_t m) { b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor"); };
  const Push compound = push_of(volume_settings(), filled, floor, placed(tilt, depth));
  const Push box = push_of(volume_settings(), solid, floor, placed(tilt, depth));
  EXPECT_EQ(compound.contacts, 3);  // each foot and the box
  EXPECT_EQ(box.contacts, 1);
  EXPECT_GT(length(box.force), 1e-3);
  EXPECT_LT(length(compound.force - box.force), 1e-9 * length(box.force));
  EXPECT_LT(length(compound.torque - box.torque), 1e-9 * length(box.force) * 0.01);

  // Dropped, it stands on its three contacts, level, the keys of its
  // patches and its part's contact strictly increasing.
  WorldBuilder builder(volume_settings());
  const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  builder.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor");
  builder.add_body({.shape = filled, .material = rock, .position = {0, 0, 0.0201}});
  World w = builder.build();
  for (int i = 0; i < 20000; ++i) ASSERT_EQ(step(w, 2e-5).status, StepStatus::Ok) << i;
  const Body& b = w.bodies[0];
  EXPECT_EQ(w.stats.contacts, 3);
  EXPECT_LT(length(b.velocity), 1e-4);
  EXPECT_GT(rotate(shape_orientation(w.templates[b.shape], b), Vec3{0, 0, 1}).z, 1 - 1e-6);
  const std::vector<PairKey>& keys = w.results.keys;
  EXPECT_TRUE(std::adjacent_find(keys.begin(), keys.end(), std::greater_equal<PairKey>()) == keys.end());
}

// Two compounds, each a box and a surface cube side by side, the second
// turned a half turn and pressed into the first so that each one's box
// meets the other's surface: the patches of parts (0, 1) and (1, 0) keep
// springs of their own (keys strictly increasing), and the moving one is
// pushed as by the fixed one's parts as separate bodies.
TEST(SurfaceCompound, TwoCompoundsKeepEachPairOfPartsApart) {
  const PlacedShape box{Shape{Box{{0.005, 0.005, 0.005}}}, Transform::from({0.005, 0.005, 0.005}, Quat{})};
  const std::shared_ptr<const Surface> cube = shared(test::box_surface({0.01, 0, 0}, {0.02, 0.01, 0.01}));
  const BodyShape pair{.parts = {box}, .surface_parts = {{cube, {}}}};
  Vec3 force[2], torque[2];
  int patches[2] = {};
  for (int compound = 0; compound < 2; ++compound) {
    WorldBuilder builder(volume_settings());
    const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
    if (compound) {
      builder.add_body({.shape = pair, .material = rock, .fixed = true});
    } else {
      builder.add_body({.shape = {box.shape, box.pose}, .material = rock, .fixed = true});
      builder.add_body({.shape = {.surface = cube}, .material = rock, .fixed = true});
    }
    builder.add_body({.shape = pair, .material = rock, .position = {0.02, 0.0195, 0}, .rotation = Quat{0, 0, 0, 1},
                      .velocity = {0.01, -0.02, 0.005}, .angular_velocity = {1, -2, 3}});
    builder.accept_initial_overlaps();
    World w = builder.build();
    for (int i = 0; i < 100; ++i) ASSERT_EQ(step(w, 1e-6).status, StepStatus::Ok) << i;  // springs build up
    for (const StepContact& c : w.results.contacts) patches[compound] += c.surface && c.active;
    const std::vector<PairKey>& keys = w.results.keys;
    EXPECT_TRUE(std::adjacent_find(keys.begin(), keys.end(), std::greater_equal<PairKey>()) == keys.end()) << compound;
    force[compound] = w.bodies.back().force, torque[compound] = w.bodies.back().torque;
  }
  EXPECT_GE(patches[0], 2);  // each box in the other's surface (and the surfaces, as the turn tilts them)
  EXPECT_EQ(patches[1], patches[0]);
  EXPECT_GT(length(force[0]), 1e-3);
  EXPECT_LT(length(force[1] - force[0]), 1e-9 * length(force[0]));
  EXPECT_LT(length(torque[1] - torque[0]), 1e-9 * length(force[0]) * 0.01);
}

// Frames draw a surface part's own triangles (the U's 28), placed, and the
// convex part's faces (the box's 6).
TEST(SurfaceCompound, FramesDrawTheSurfacePartsOwnTriangles) {
  const std::shared_ptr<const Surface> u = u_arms_down();
  const Transform shift = Transform::from({0.1, 0, 0}, Quat{});
  const std::vector<PlacedShape> box{kHollowBox};
  const std::vector<PlacedSurface> surfaces{{u, shift}};
  const io::DisplayMesh m = io::display_mesh(make_compound_template(box, false, surfaces));
  ASSERT_EQ(u->triangles.size(), 28u);
  EXPECT_EQ(m.polygon_begin.size(), 1u + 6u + 28u);
  Aabb drawn{m.vertices[0], m.vertices[0]};
  for (const Vec3& v : m.vertices) drawn.lo = min(drawn.lo, v), drawn.hi = max(drawn.hi, v);
  EXPECT_LT(length(drawn.hi - Vec3{0.13, 0.01, 0}), 1e-12);  // the U moved 10 cm along x
  EXPECT_LT(length(drawn.lo - Vec3{0.01, 0, -0.02}), 1e-12);  // the box
}

// A fixed U, as a compound of its three boxes or of its one surface, leaves
// its notch free: a generator fills it and an inflow inserts into it (the
// U's hull, which fills the notch, held both back), every sphere clear of
// the U's parts.
TEST(SurfaceCompound, AGeneratorAndAnInflowFillTheNotchOfACompound) {
  gjkdem::test::Mesh mesh = gjkdem::test::u_prism(1);  // notch x, y in [1, 2]
  for (Vec3& v : mesh.vertices) v = v * 0.1;
  const auto box = [](const Vec3& lo, const Vec3& hi) {  // dm
    return PlacedShape{Shape{Box{(hi - lo) * 0.05}}, Transform::from((lo + hi) * 0.05, Quat{})};
  };
  const BodyShape boxes{.parts = {box({0, 0, 0}, {3, 1, 1}), box({0, 1, 0}, {1, 2, 1}), box({2, 1, 0}, {3, 2, 1})}};
  const BodyShape surface{.surface_parts = {{shared(mesh), {}}}};
  for (const BodyShape& u : {boxes, surface}) {
    SCOPED_TRACE(u.parts.empty() ? "a surface part" : "three boxes");
    WorldSettings settings;
    settings.model = ContactModel::Hertz;
    settings.gravity = {0, -9.81, 0};  // into the notch
    WorldBuilder builder(settings);
    const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
    builder.add_body({.shape = u, .material = rock, .position = {0, 0, 0}, .fixed = true});  // its frame (a wall: no centroid)
    std::mt19937_64 rng(5);
    RegionFill fill;
    fill.variants = {{make_sphere(0.01), {}}};
    fill.count = 20;
    fill.lo = {0.101, 0.101, 0.001}, fill.hi = {0.199, 0.199, 0.099};
    fill.material = rock;
    fill.label = "fill";
    ASSERT_EQ(builder.fill_region(fill, rng).size(), 20u);
    InflowDef inflow;
    inflow.variants = {{make_sphere(0.008), {}}};
    inflow.lo = {0.12, 0.185, 0.02}, inflow.hi = {0.18, 0.19, 0.08};
    inflow.material = rock;
    inflow.rate = 200, inflow.count = 3, inflow.seed = 3;
    builder.add_inflow(inflow);
    World w = builder.build();
    const Body& fixed_u = w.bodies[0];
    const ShapeTemplate& t = w.templates[fixed_u.shape];
    const auto check = [&](Real allowed) {  // each sphere in the notch, clear of the parts but for `allowed`
      for (std::size_t i = 1; i < w.bodies.size(); ++i) {
        const Body& b = w.bodies[i];
        const ShapeTemplate& ball = w.templates[b.shape];
        for (std::uint32_t k = 0; k < t.parts.size(); ++k) {
          const PartPose part = part_pose(t, fixed_u, k);
          if (t.parts[k].surface_grain) {  // its shape is its hull: the surfaces' overlap
            SurfaceScratch scratch;
            std::vector<SurfacePatchContact> patches;
            if (allowed == 0) {
              EXPECT_FALSE(surfaces_meet(ball.surface, shape_pose(ball, b), t.parts[k].surface, part.pose, scratch, patches))
                  << "sphere " << i;
            }
            continue;
          }
          const PenetrationResult p = penetration(*part.shape, part.pose, ball.shape, shape_pose(ball, b));
          EXPECT_FALSE(p.intersect && p.depth > allowed) << "sphere " << i << " in part " << k << " by " << p.depth;
        }
        EXPECT_GT(b.position.x, 0.1);
        EXPECT_LT(b.position.x, 0.2);
        EXPECT_GT(b.position.y, 0.1);
      }
    };
    check(0);  // as placed
    for (int i = 0; i < 300; ++i) ASSERT_EQ(step(w, 5e-5).status, StepStatus::Ok) << i;
    EXPECT_EQ(w.inflow_states[0].inserted, 3u);
    ASSERT_EQ(w.bodies.size(), 24u);
    check(1e-3);  // fallen onto the notch's floor and onto each other (Hertz overlaps)
  }
}

TEST(SurfaceCompound, OverlappingPartsAreRefusedNamingThem) {
  WorldBuilder builder(volume_settings());
  const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  const std::shared_ptr<const Surface> u = u_arms_down();
  const auto refused = [&](const BodyShape& shape, const std::string& why) {
    try {
      builder.add_body({.shape = shape, .material = rock, .label = "grain"});
      ADD_FAILURE() << "accepted; expected: " << why;
    } catch (const BuildError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  // A box sunk 1 mm into the U's left arm.
  refused({.parts = {{Shape{Box{{0.005, 0.005, 0.005}}}, Transform::from({-0.004, 0.005, -0.015}, Quat{})}},
           .surface_parts = {{u, {}}}},
          "grain: parts 0 and 1 overlap by");
  // A box wholly inside the U's bridge.
  refused({.parts = {{Shape{Box{{0.002, 0.002, 0.002}}}, Transform::from({0.015, 0.005, -0.005}, Quat{})}},
           .surface_parts = {{u, {}}}},
          "grain: parts 0 and 1 overlap (one wholly inside the other)");
  // Two copies of the U, the second moved 1 cm along x into the first.
  refused({.surface_parts = {{u, {}}, {u, Transform::from({0.01, 0, 0}, Quat{})}}}, "grain: parts 0 and 1 overlap by");
  // The box in the hollow touches, and the U beside the first touches it.
  EXPECT_NO_THROW(builder.add_body({.shape = {.parts = {kHollowBox}, .surface_parts = {{u, {}}, {u, Transform::from({0.03, 0, 0}, Quat{})}}},
                                    .material = rock, .position = {0, 0, 0.5}}));
  // A surface part of two shells.
  test::Mesh two = test::box_surface({0.04, 0, 0}, {0.05, 0.01, 0.01});
  test::append(two, test::box_surface({0.06, 0, 0}, {0.07, 0.01, 0.01}));
  refused({.surface_parts = {{u, {}}, {shared(two), {}}}},
          "grain: cannot be a moving body: surface part 1 of a compound is one closed shell; this surface has 2");
  // A surface grain given surface parts too: neither wins silently.
  refused({.surface_parts = {{u, {}}}, .surface = u}, "grain: a shape is one of a thin shell, a surface and a compound's parts");
  refused({.parts = {kHollowBox}, .surface = u}, "grain: a shape is one of");
}

}  // namespace
}  // namespace gjkdem::dem
