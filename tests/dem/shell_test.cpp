// Thin shells (shape/shell.hpp, BodyShape::shell): open triangle surfaces
// with a thickness, moving or fixed, under the Hertz and linear laws.
// - Mass properties: a plate is the box it is; a tray the union of its five
//   plates as boxes; bad shells refused naming the triangle.
// - A surface grain pushes on a fixed shell as on a mesh wall of the same
//   triangles and thickness (the same margin model).
// - A shell plate falls onto a plane and rests on its margin; a cube rests
//   on a fixed shell plate; a generator and an inflow fill a tray's hollow.
// - A plate rests on a fixed shell and on a mesh floor on both margins, at
//   the same height; the volume law refuses shells.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "shape/surface_shapes.hpp"

namespace gjkdem::dem {
namespace {

// A square plate of side `side` in the plane z = 0, centred on the origin.
std::shared_ptr<const Shell> plate(Real side, Real thickness) {
  const Real h = side / 2;
  return std::make_shared<const Shell>(
      make_shell({{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}}, {{{0, 1, 2}}, {{0, 2, 3}}}, thickness));
}

WorldSettings hertz() {
  WorldSettings s;
  s.model = ContactModel::Hertz;
  return s;
}

TEST(Shell, APlateIsTheBoxItIsAndATrayTheUnionOfItsPlates) {
  const Real side = 0.04, t = 0.002;
  const MassProperties p = mass_properties(*plate(side, t));
  const MassProperties box = mass_properties(Shape{Box{{side / 2, side / 2, t / 2}}});
  EXPECT_NEAR(p.volume, box.volume, 1e-15 * box.volume);
  EXPECT_LT(length(p.centroid), 1e-15);
  for (int i = 0; i < 3; ++i) EXPECT_LT(length(p.inertia.row[i] - box.inertia.row[i]), 1e-12 * box.inertia.row[2][2]) << i;

  // An open tray: a floor and four walls, each a square of two triangles.
  const Real h = side / 2;
  const std::vector<Vec3> v{{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0},
                            {-h, -h, side}, {h, -h, side}, {h, h, side}, {-h, h, side}};
  const std::vector<TriangleIndices> tris{{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                          {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  const Shell tray = make_shell(v, tris, t);
  // The same plates as boxes, placed: the floor, then the walls at x = +-h, y = +-h.
  const Shape wall_x{Box{{t / 2, h, h}}}, wall_y{Box{{h, t / 2, h}}}, floor{Box{{h, h, t / 2}}};
  const std::vector<PlacedShape> plates{{floor, Transform::from({0, 0, 0}, Quat{})},
                                        {wall_y, Transform::from({0, -h, h}, Quat{})},
                                        {wall_x, Transform::from({h, 0, h}, Quat{})},
                                        {wall_y, Transform::from({0, h, h}, Quat{})},
                                        {wall_x, Transform::from({-h, 0, h}, Quat{})}};
  const MassProperties m = mass_properties(tray), u = mass_properties(plates);
  EXPECT_NEAR(m.volume, u.volume, 1e-14 * u.volume);
  EXPECT_LT(length(m.centroid - u.centroid), 1e-14);
  for (int i = 0; i < 3; ++i) EXPECT_LT(length(m.inertia.row[i] - u.inertia.row[i]), 1e-12 * u.inertia.row[2][2]) << i;

  const auto refused = [](std::vector<Vec3> vertices, std::vector<TriangleIndices> triangles, Real thickness,
                          const std::string& why) {
    try {
      make_shell(std::move(vertices), std::move(triangles), thickness);
      ADD_FAILURE() << "accepted; expected: " << why;
    } catch (const ShellError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refused({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}, t, "triangle 0 has no area");
  refused({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}}, t, "triangle 0 refers to vertex 3 but there are 3 vertices");
  refused({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, 0, "thickness must be > 0");
  refused({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, t, "at least one triangle");
  refused({{0, 0, 0}, {1, 0, std::nan("")}, {0, 1, 0}}, {{0, 1, 2}}, t, "vertex 1 is not finite");
}

// A cube's corner within the margin of a fixed shell plate and of a mesh
// wall of the same two triangles: the same margin model, the same push.
TEST(Shell, AGrainPushesOnAFixedShellAsOnAMeshWallOfItsTriangles) {
  const Real t = 0.002;
  const std::shared_ptr<const Shell> floor = plate(0.2, t);
  // The mesh wall; the shell added before the grain (body a of the pair); after it (b).
  Vec3 force[3], torque[3];
  int contacts[3];
  for (int run = 0; run < 3; ++run) {
    WorldBuilder builder(hertz());
    const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
    if (run == 1) {
      builder.add_body({.shape = {.shell = floor}, .material = rock, .fixed = true});
    } else if (run == 0) {
      const std::vector<std::array<std::uint32_t, 3>> tris(floor->triangles.begin(), floor->triangles.end());
      builder.add_mesh_walls(floor->vertices, tris, t, rock, "floor");
    }
    BodyShape cube;
    cube.surface = std::make_shared<const Surface>(test::surface_of(test::box_surface({-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01})));
    const std::uint32_t grain = builder.add_body({.shape = cube, .material = rock, .position = {0.003, 0.002, 0.03}});
    if (run == 2) builder.add_body({.shape = {.shell = floor}, .material = rock, .fixed = true});
    World w = builder.build();
    Body& b = w.bodies[grain];  // tilted so that one corner dips into the margin, 0.4 mm
    b.orientation = normalized(Quat{1, 0.3, -0.2, 0.1});
    const Vec3 low = rotate(b.orientation, support(w.templates[b.shape].shape, rotate(conjugate(b.orientation), Vec3{0, 0, -1})));
    b.position.z = t / 2 - 0.0004 - low.z;
    b.velocity = {0.01, 0, -0.02};
    ASSERT_EQ(compute_forces_now(w).status, StepStatus::Ok);
    force[run] = b.force, torque[run] = b.torque, contacts[run] = w.stats.contacts;
  }
  EXPECT_GT(length(force[0]), 1e-2);
  for (int run = 0; run < 3; ++run) {
    EXPECT_EQ(contacts[run], 1) << run;
    EXPECT_LT(length(force[run] - force[0]), 1e-9 * length(force[0])) << run;
    EXPECT_LT(length(torque[run] - torque[0]), 1e-9 * length(force[0]) * 0.01) << run;
  }
}

// A moving plate falls flat onto a plane and rests on its margin (its
// middle rho above the plane, less the Hertz depth of its weight), then a
// cube dropped onto a fixed plate rests on it.
TEST(Shell, APlateRestsOnAPlaneAndACubeOnAPlate) {
  const Real t = 0.002;
  {
    WorldBuilder builder(hertz());
    const std::uint32_t steel = builder.add_material({"steel", 7800, 1e8, 0.3, 0.3, 0.5});
    builder.add_plane({0, 0, 0}, {0, 0, 1}, steel, "floor");
    builder.add_body({.shape = {.shell = plate(0.04, t)}, .material = steel, .position = {0, 0, 0.005},
                      .rotation = normalized(Quat{1, 0.02, 0.01, 0})});
    World w = builder.build();
    for (int i = 0; i < 20000; ++i) ASSERT_EQ(step(w, 2e-5).status, StepStatus::Ok) << i;
    const Body& b = w.bodies.back();
    EXPECT_LT(length(b.velocity), 1e-3);
    EXPECT_NEAR(b.position.z, t / 2, 0.05 * t);  // on its margin
    EXPECT_GT(b.position.z, t / 4);
    EXPECT_GE(w.stats.contacts, 1);
  }
  {
    WorldBuilder builder(hertz());
    const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
    builder.add_body({.shape = {.shell = plate(0.2, t)}, .material = rock, .fixed = true});
    builder.add_body({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .material = rock, .position = {0.01, 0, 0.0115}});
    World w = builder.build();
    for (int i = 0; i < 20000; ++i) ASSERT_EQ(step(w, 2e-5).status, StepStatus::Ok) << i;
    const Body& b = w.bodies.back();
    EXPECT_LT(length(b.velocity), 1e-3);
    EXPECT_NEAR(b.position.z, t / 2 + 0.01, 0.05 * t);
    EXPECT_EQ(w.stats.contacts, 1);  // the face on the plate: one patch
  }
}

// A generator fills the hollow of a fixed tray (its hull is not its
// solid), clear of its margin: the grains start touching nothing; an
// inflow inserts there.
TEST(Shell, AGeneratorAndAnInflowFillTheHollowOfATray) {
  const Real h = 0.04, t = 0.002;
  const std::vector<Vec3> v{{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}};
  const std::vector<TriangleIndices> tris{{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                          {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  WorldBuilder builder(hertz());
  const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  builder.add_body({.shape = {.shell = std::make_shared<const Shell>(make_shell(v, tris, t))}, .material = rock,
                    .fixed = true});
  std::mt19937_64 rng(7);
  RegionFill fill;
  fill.variants = {{Shape{Box{{0.004, 0.004, 0.004}}}, {}}};
  fill.count = 40;
  fill.lo = {-0.038, -0.038, 0.002}, fill.hi = {0.038, 0.038, 0.038};
  fill.material = rock;
  fill.label = "fill";
  ASSERT_EQ(builder.fill_region(fill, rng).size(), 40u);
  World w = builder.build();
  ASSERT_EQ(compute_forces_now(w).status, StepStatus::Ok);
  EXPECT_EQ(w.stats.contacts, 0);
  for (const Body& b : w.bodies) EXPECT_LT(std::fmax(std::fabs(b.position.x), std::fabs(b.position.y)), h);

  // An inflow inserts into the hollow too (its hull would hold it back).
  WorldBuilder flowing(hertz());
  const std::uint32_t glass = flowing.add_material({"glass", 2500, 1e7, 0.25, 0.3, 0.5});
  flowing.add_body({.shape = {.shell = std::make_shared<const Shell>(make_shell(v, tris, t))}, .material = glass,
                    .fixed = true});
  InflowDef inflow;
  inflow.variants = {{make_sphere(0.004), {}}};
  inflow.lo = {-0.03, -0.03, 0.02}, inflow.hi = {0.03, 0.03, 0.02};
  inflow.material = glass;
  inflow.rate = 1000, inflow.count = 5, inflow.seed = 3;
  flowing.add_inflow(inflow);
  World f = flowing.build();
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(step(f, 1e-5).status, StepStatus::Ok) << i;
  EXPECT_EQ(f.bodies.size(), 6u);
}

// A plate dropped flat onto a fixed plate and onto a mesh floor of the
// same triangles and thickness rests on both margins, at the same height
// on both (the same margin model: the triangles with both margins).
TEST(Shell, APlateRestsOnAShellAndOnAMeshFloorOnBothMargins) {
  const Real t = 0.002, thin = 0.001;
  const std::shared_ptr<const Shell> floor = plate(0.2, t);
  Real height[2];
  for (int mesh = 0; mesh < 2; ++mesh) {
    WorldBuilder builder(hertz());
    const std::uint32_t steel = builder.add_material({"steel", 7800, 1e8, 0.3, 0.3, 0.5});
    if (mesh) {
      const std::vector<std::array<std::uint32_t, 3>> tris(floor->triangles.begin(), floor->triangles.end());
      builder.add_mesh_walls(floor->vertices, tris, t, steel, "floor");
    } else {
      builder.add_body({.shape = {.shell = floor}, .material = steel, .fixed = true});
    }
    builder.add_body({.shape = {.shell = plate(0.04, thin)}, .material = steel, .position = {0.003, 0.002, 0.004},
                      .rotation = normalized(Quat{1, 0.02, 0.01, 0})});
    World w = builder.build();
    for (int i = 0; i < 20000; ++i) ASSERT_EQ(step(w, 2e-5).status, StepStatus::Ok) << i;
    const Body& b = w.bodies.back();
    EXPECT_LT(length(b.velocity), 1e-3) << mesh;
    EXPECT_NEAR(b.position.z, (t + thin) / 2, 0.05 * thin) << mesh;
    EXPECT_GE(w.stats.contacts, 1) << mesh;
    height[mesh] = b.position.z;
  }
  EXPECT_NEAR(height[1], height[0], 1e-9);
}

// A plate crossing the top face of a fixed surface slab deeper than the
// margin is pushed out of the slab, wherever the slab's frame has its
// origin (here 5 cm above it: the side is the solid's centroid's, not the
// body's position); a plate wholly through a plane stops the run.
TEST(Shell, ACrossingPlateIsPushedOutOfTheSolidAndThroughAPlaneStops) {
  for (const Real origin : {0.0, 0.05}) {
    WorldBuilder builder(hertz());
    const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
    // The slab x, y in [-5, 5] cm, z in [-2, 0] cm, its vertices given from a frame `origin` above.
    builder.add_body({.shape = {.surface = std::make_shared<const Surface>(test::surface_of(
                                    test::box_surface({-0.05, -0.05, -0.02 - origin}, {0.05, 0.05, -origin})))},
                      .material = rock, .position = {0, 0, origin}, .fixed = true});
    builder.add_body({.shape = {.shell = plate(0.02, 0.001)}, .material = rock, .position = {0, 0, 0.01}});
    World w = builder.build();
    Body& b = w.bodies.back();  // tilted 0.2 rad about x, its middle 0.5 mm below the slab's top: crossing it
    b.orientation = normalized(Quat{std::cos(0.1), std::sin(0.1), 0, 0} * w.templates[b.shape].principal.rotation);
    b.position = {0, 0, -0.0005};
    ASSERT_EQ(compute_forces_now(w).status, StepStatus::Ok) << origin;
    EXPECT_GT(b.force.z, 1.0) << "origin " << origin;
  }
  // A stray vertex no triangle uses is dropped (it would touch the floor alone).
  const Shell stray = make_shell({{-0.01, -0.01, 0}, {0.01, -0.01, 0}, {0.5, 0.5, -0.5}, {0.01, 0.01, 0}, {-0.01, 0.01, 0}},
                                 {{0, 1, 3}, {0, 3, 4}}, 0.002);
  EXPECT_EQ(stray.vertices.size(), 4u);
  EXPECT_EQ(stray.triangles[1][1], 2u);

  WorldBuilder builder(hertz());
  const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  builder.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor");
  builder.add_body({.shape = {.shell = plate(0.02, 0.002)}, .material = rock, .position = {0, 0, 0.01}});
  World w = builder.build();
  w.bodies.back().position.z = -0.0015;  // every corner more than the margin below the floor
  EXPECT_EQ(compute_forces_now(w).status, StepStatus::ThroughWall);
}

TEST(Shell, AShellGivenPartsTooIsRefused) {
  WorldBuilder builder{WorldSettings{}};
  const std::uint32_t m = builder.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  try {
    builder.add_body({.shape = {.parts = {{Shape{Box{{0.01, 0.01, 0.01}}}, Transform{}}}, .shell = plate(0.1, 0.002)},
                      .material = m,
                      .label = "scoop"});
    ADD_FAILURE() << "accepted";
  } catch (const BuildError& e) {
    EXPECT_NE(std::string(e.what()).find("scoop: a shape is one of a thin shell, a surface and a compound's parts"),
              std::string::npos)
        << e.what();
  }
}

TEST(Shell, TheVolumeLawRefusesAShell) {
  WorldSettings volume;
  volume.model = ContactModel::Volume;
  WorldBuilder refusing(volume);
  const std::uint32_t m = refusing.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  try {
    refusing.add_body({.shape = {.shell = plate(0.1, 0.002)}, .material = m, .label = "scoop"});
    ADD_FAILURE() << "accepted";
  } catch (const BuildError& e) {
    EXPECT_NE(std::string(e.what()).find("scoop: a thin shell takes the Hertz and linear laws"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gjkdem::dem
