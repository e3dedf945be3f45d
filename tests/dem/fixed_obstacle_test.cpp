// A cube dropped onto each kind of fixed obstacle comes to rest on it under
// each contact law (issue 10). Before the builder prepared fixed shapes for
// the volume law, a cube fell straight through a fixed sphere, cylinder,
// ellipsoid or superellipsoid (the pair had no overlap computation and the
// narrow phase took that as "no contact"). A pair the engine cannot handle is
// now refused when the world is built, or stops the step naming the pair.
//
// The grains have rolling friction (mu_r = 0.1): without it, on the curved
// tops (sphere, ellipsoid, superellipsoid) the volume law leaves the cube
// rocking by rolling on the tessellated surface (measured: 2e-3 to 6e-3 m/s
// after 0.5 s, still 1e-3 after 4 s), since rolling without slip loses
// nothing to the normal or tangential dashpots (rolling_resistance_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kHalf = 0.005;  // the cube's half size (m)

struct Obstacle {
  std::string name;
  Real top = 0;  // height of the obstacle's top under the cube (m)
  std::function<void(WorldBuilder&, std::uint32_t material)> add;
};

void add_fixed(WorldBuilder& b, std::uint32_t m, const Shape& shape, const Quat& rotation = {}) {
  b.add_body({.shape = {shape, {}}, .material = m, .rotation = rotation, .fixed = true, .label = "obstacle"});
}

std::vector<Obstacle> obstacles() {
  const Quat upside_down = quat_from_axis_angle({1, 0, 0}, kPi);
  std::vector<Vec3> prism;  // a hexagonal prism, 2 cm high
  for (int k = 0; k < 6; ++k)
    for (const Real z : {-0.01, 0.01}) prism.push_back({0.03 * std::cos(k * kPi / 3), 0.03 * std::sin(k * kPi / 3), z});
  const Shape hexagon{make_polytope(prism)};
  return {
      {"sphere", 0.03, [](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, make_sphere(0.03)); }},
      {"box", 0.01, [](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, Shape{Box{{0.03, 0.03, 0.01}}}); }},
      {"ellipsoid", 0.015,
       [](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, Shape{Ellipsoid{{0.04, 0.03, 0.015}}}); }},
      {"cylinder", 0.01, [](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, Shape{Cylinder{0.03, 0.01}}); }},
      // Base up: a cube balanced on the apex would topple, which is physics.
      {"cone", 0.01,
       [=](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, Shape{Cone{0.03, 0.01}}, upside_down); }},
      {"superellipsoid", 0.01,
       [](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, Shape{Superellipsoid{{0.03, 0.03, 0.01}, 0.3, 0.3}}); }},
      {"polytope", 0.01, [=](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, hexagon); }},
      {"rounded box", 0.012,
       [](WorldBuilder& b, std::uint32_t m) { add_fixed(b, m, Shape{Box{{0.03, 0.03, 0.01}}, 0.002}); }},
      {"mesh wall", 0.001,
       [](WorldBuilder& b, std::uint32_t m) {
         const Vec3 c[4] = {{-0.05, -0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0}, {-0.05, 0.05, 0}};
         const std::array<std::uint32_t, 3> tris[2] = {{0, 1, 2}, {0, 2, 3}};
         b.add_mesh_walls(c, tris, 0.002, m, "mesh");
       }},
      {"plane", 0, [](WorldBuilder& b, std::uint32_t m) { b.add_plane({}, {0, 0, 1}, m, "plane"); }},
  };
}

TEST(FixedObstacle, CubeLandsAndStaysOnEveryShapeUnderEveryLaw) {
  for (const ContactModel model : {ContactModel::Volume, ContactModel::Hertz, ContactModel::Linear}) {
    for (const Obstacle& o : obstacles()) {
      const std::string what = o.name + (model == ContactModel::Volume ? " (volume law)"
                                         : model == ContactModel::Hertz ? " (Hertz)" : " (linear law)");
      WorldSettings settings;
      settings.model = model;
      WorldBuilder b(settings);
      const std::uint32_t rock = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5, 0.1});
      o.add(b, rock);
      b.add_body({.shape = {Shape{Box{{kHalf, kHalf, kHalf}}}, {}}, .material = rock,
                  .position = {0, 0, o.top + kHalf + 1e-3}, .label = "cube"});
      World w = b.build();
      const Body& cube = w.bodies.back();
      RunState run = plan_run(0.5, critical_time_step(w), 0.5);
      const RunOutcome outcome = dem::run(w, run, {});
      ASSERT_EQ(outcome.status, RunStatus::Completed) << what << ": " << outcome.error;
      EXPECT_GT(cube.position.z, o.top) << what << ": fell through";
      EXPECT_LT(cube.position.z, o.top + kHalf * 1.01) << what << ": not touching";
      EXPECT_LT(length(cube.velocity), 1e-3) << what << ": not at rest";  // it lands at about 0.14 m/s
      EXPECT_GE(w.stats.contacts, 1) << what;
    }
  }
}

TEST(FixedObstacle, ShapesWithoutVolumeAreRefusedUnderTheVolumeLaw) {
  WorldBuilder b;  // the volume law
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  b.add_body({.shape = {Shape{Triangle{{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}}}, {}}, .material = rock, .fixed = true,
              .label = "flat triangle"});
  b.add_body({.shape = {Shape{Box{{kHalf, kHalf, kHalf}}}, {}}, .material = rock, .position = {0, 0, 0.01},
              .label = "cube"});
  try {
    b.build();
    ADD_FAILURE() << "accepted";
  } catch (const BuildError& e) {
    EXPECT_NE(std::string(e.what()).find("flat triangle: a shape without volume"), std::string::npos) << e.what();
  }
}

// A world whose shapes were not prepared (assembled by hand): the step stops
// and names the pair instead of taking it as "no contact".
TEST(FixedObstacle, AnUnsupportedPairStopsTheRunNamingIt) {
  WorldBuilder b;
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  b.add_body({.shape = {Shape{Box{{0.03, 0.03, 0.03}}}, {}}, .material = rock, .fixed = true, .label = "base"});
  b.add_body({.shape = {Shape{Box{{kHalf, kHalf, kHalf}}}, {}}, .material = rock, .position = {0, 0, 0.0351},
              .label = "cube"});
  World w = b.build();
  w.templates[w.bodies[0].shape].shape = make_sphere(0.03);  // not clipped by the volume law
  w.bodies[1].velocity = {0, 0, -0.5};                         // reaches the sphere in a few steps
  RunState run = plan_run(0.01, 1e-5, 0.01);
  const RunOutcome outcome = dem::run(w, run, {});
  ASSERT_EQ(outcome.status, RunStatus::Failed);
  EXPECT_NE(outcome.error.find("no computation for the pair body 0 and body 1"), std::string::npos) << outcome.error;
}

}  // namespace
}  // namespace gjkdem::dem
