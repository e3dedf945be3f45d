// WorldBuilder's rules (world_builder.hpp), written once: each refuses the
// field it names, with the key a scene reader maps to its line; what passes
// them builds. The scene reader's use of them is in tests/io/scene_test.cpp.
#include "gjkdem/dem/world_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/io/scene.hpp"
#include "gjkdem/shape/hull_surface_slot.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();
constexpr Real kInf = std::numeric_limits<Real>::infinity();

using KeyRule = std::pair<std::string, std::string>;

// The key and rule of the BuildError `call` throws ("" when it throws none).
KeyRule broken(const std::function<void()>& call) {
  try {
    call();
  } catch (const BuildError& e) {
    EXPECT_EQ(std::string(e.what()).find(e.key + " " + e.rule) != std::string::npos, true) << e.what();
    return {e.key, e.rule};
  }
  return {"", ""};
}

TEST(WorldBuilderRules, EachMaterialValueOutOfRangeIsRefusedByItsKey) {
  const Material good{"rock", 2600, 1e7};
  EXPECT_EQ(broken([&] { check_material(good); }).first, "");
  struct Bad {
    Real Material::*field;
    Real value;
    const char* key;
    const char* rule;
  };
  for (const Bad& b : {Bad{&Material::density, 0, "density", "must be > 0"},
                       Bad{&Material::density, kInf, "density", "must be finite"},
                       Bad{&Material::youngs_modulus, -1, "youngs_modulus", "must be > 0"},
                       Bad{&Material::poisson_ratio, 0.5, "poisson_ratio", "must lie in (-1, 0.5)"},
                       Bad{&Material::poisson_ratio, -1, "poisson_ratio", "must lie in (-1, 0.5)"},
                       Bad{&Material::restitution, 0, "restitution", "must lie in (0, 1]"},
                       Bad{&Material::restitution, 1.0000001, "restitution", "must lie in (0, 1]"},
                       Bad{&Material::friction, -0.1, "friction", "must be >= 0"},
                       Bad{&Material::friction, kNaN, "friction", "must be finite"},
                       Bad{&Material::rolling_friction, -1e-9, "rolling_friction", "must be >= 0"},
                       Bad{&Material::rolling_damping, 1.5, "rolling_damping", "must lie in [0, 1]"}}) {
    Material m = good;
    m.*b.field = b.value;
    const auto [key, rule] = broken([&] { check_material(m); });
    EXPECT_EQ(key, b.key) << b.key << " = " << b.value;
    EXPECT_EQ(rule, b.rule) << b.key << " = " << b.value;
    // The builder applies the same rule, naming the material.
    WorldBuilder builder;
    try {
      builder.add_material(m);
      ADD_FAILURE() << b.key << " = " << b.value << " was accepted";
    } catch (const BuildError& e) {
      EXPECT_EQ(std::string(e.what()), "material 'rock': " + std::string(b.key) + " " + b.rule);
    }
  }
}

TEST(WorldBuilderRules, TheDefaultMaterialAndSettingsPassTheirRules) {
  Material m;
  m.name = "default";
  EXPECT_EQ(broken([&] { check_material(m); }).first, "");
  EXPECT_EQ(broken([] { check_settings(WorldSettings{}); }).first, "");
}

TEST(WorldBuilderRules, SettingsOutOfRangeAreRefusedByTheirKeyWhenTheBuilderIsMade) {
  struct Bad {
    std::function<void(WorldSettings&)> set;
    const char* key;
  };
  for (const Bad& b : {Bad{[](WorldSettings& s) { s.tessellation = kMinTessellation - 1; }, "tessellation"},
                       Bad{[](WorldSettings& s) { s.tessellation = kMaxTessellation + 1; }, "tessellation"},
                       Bad{[](WorldSettings& s) { s.volume_stiffness = kNaN; }, "volume_stiffness"},
                       Bad{[](WorldSettings& s) { s.volume_stiffness = -1; }, "volume_stiffness"},
                       Bad{[](WorldSettings& s) { s.linear_stiffness = -1; }, "linear_stiffness"},
                       Bad{[](WorldSettings& s) { s.box_skin = -0.01; }, "box_skin"},
                       Bad{[](WorldSettings& s) { s.threads = -7; }, "threads"},
                       Bad{[](WorldSettings& s) { s.threads = kMaxThreads + 1; }, "threads"},
                       Bad{[](WorldSettings& s) { s.gravity.z = kInf; }, "gravity"},
                       Bad{[](WorldSettings& s) { s.periodic.axes[0] = true, s.periodic.hi.x = -1; }, "periodic.x"}}) {
    WorldSettings s;
    b.set(s);
    EXPECT_EQ(broken([&] { WorldBuilder builder(s); }).first, b.key);
  }
  // The edges of the ranges pass.
  WorldSettings edges;
  edges.tessellation = kMaxTessellation;
  edges.threads = kMaxThreads;
  edges.box_skin = 0;
  EXPECT_EQ(broken([&] { WorldBuilder builder(edges); }).first, "");
}

TEST(WorldBuilderRules, ACellAndItsControlAreRefusedByTheFieldAtFault) {
  PeriodicCell cube;
  cube.axes[0] = cube.axes[1] = cube.axes[2] = true;
  cube.lo = {0, 0, 0}, cube.hi = {0.1, 0.1, 0.1};
  const auto servo = [] {
    CellControl c;
    c.mode[0] = CellMode::Stress, c.value[0] = 1e4, c.max_strain_rate = 1;
    return c;
  };
  EXPECT_EQ(broken([&] { check_cell(cube, servo()); }).first, "");
  CellControl tension = servo();
  tension.value[0] = -1e4;
  EXPECT_EQ(broken([&] { check_cell(cube, tension); }).first, "stress.x");
  CellControl unbounded = servo();
  unbounded.max_strain_rate = 0;
  EXPECT_EQ(broken([&] { check_cell(cube, unbounded); }),
            KeyRule("stress", "needs max_strain_rate too (1/s): the servo's largest strain rate"));
  CellControl shear_only;
  shear_only.mode[kXY] = CellMode::Stress, shear_only.max_strain_rate = 1;
  EXPECT_EQ(broken([&] { check_cell(cube, shear_only); }).first, "stress");
  CellControl rate_alone;
  rate_alone.max_strain_rate = 1;
  EXPECT_EQ(broken([&] { check_cell(cube, rate_alone); }).first, "max_strain_rate");
  PeriodicCell slab = cube;
  slab.axes[2] = false;
  CellControl shear;
  shear.mode[kXZ] = CellMode::StrainRate, shear.value[kXZ] = 1;
  EXPECT_EQ(broken([&] { check_cell(slab, shear); }), KeyRule("strain_rate.xz", "the cell is not periodic on z"));
  EXPECT_EQ(broken([&] { check_cell(slab, servo()); }).first, "stress");  // a servo needs x, y and z
  PeriodicCell tilted = cube;
  tilted.tilt.x = 0.01;
  EXPECT_EQ(broken([&] { check_cell(tilted, {}); }).first, "tilt");
  // Through check_settings, the keys are those of the scene's [simulation] table.
  WorldSettings s;
  s.periodic = cube, s.cell_control = tension;
  EXPECT_EQ(broken([&] { check_settings(s); }).first, "periodic.stress.x");
}

TEST(WorldBuilderRules, ASceneNamesTheBuildersRuleAtTheLineOfTheField) {
  // The scene reader has no rule of its own for these: the builder's, at the key's line.
  const std::string head = "[simulation]\nduration = 0.01\n[[material]]\nname = \"m\"\ndensity = 2500.0\n"
                           "youngs_modulus = 1.0e7\n";
  const std::string body = "[[body]]\nmaterial = \"m\"\nshape = { type = \"sphere\", radius = 0.01 }\n";
  struct Case {
    std::string text;
    std::string message;
  };
  for (const Case& c : {Case{head + "poisson_ratio = 0.7\n" + body, "material[0].poisson_ratio: must lie in (-1, 0.5) (line 7)"},
                        Case{"[contact]\ntessellation = 4\n" + head + body,
                             "contact.tessellation: must be between 8 and 100000 directions (line 2)"},
                        Case{"[contact]\ntessellation = 99999999999\n" + head + body,
                             "contact.tessellation: must be between 8 and 100000 directions (line 2)"},
                        Case{"[contact]\nvolume_stiffness = -5.0\n" + head + body, "contact.volume_stiffness: must be finite and >= 0"},
                        Case{head + body + "[simulation.periodic]\nx = [0.1, 0.0]\n", "simulation.periodic.x: must be [min, max]"}}) {
    try {
      io::load_scene(c.text, "scene.toml", ".");
      ADD_FAILURE() << "accepted: " << c.message;
    } catch (const io::SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
}

TEST(WorldBuilder, AGeneratorMakesFixedBodiesThatStayPut) {
  // A rough floor of fixed cubes from a generator, and a ball dropped on it.
  const std::string scene = R"([simulation]
duration = 0.01
[[material]]
name = "m"
density = 2500.0
youngs_modulus = 1.0e7
[[generator]]
count = 10
fixed = true
material = "m"
shape = { type = "box", half_extents = [0.01, 0.01, 0.01] }
region = { min = [0.0, 0.0, 0.0], max = [0.2, 0.1, 0.04] }
[[body]]
material = "m"
position = [0.1, 0.05, 0.1]
shape = { type = "sphere", radius = 0.01 }
)";
  io::Scene s = io::load_scene(scene, "scene.toml", ".");
  World& w = s.world;
  ASSERT_EQ(w.bodies.size(), 11u);
  std::vector<Vec3> before;
  std::size_t fixed = 0, ball = 0;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    before.push_back(w.bodies[i].position);
    if (w.bodies[i].fixed) ++fixed;
    else ball = i;
  }
  EXPECT_EQ(fixed, 10u);
  for (int k = 0; k < 200; ++k) ASSERT_EQ(step(w, 5e-5).status, StepStatus::Ok);
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    if (i == ball) continue;
    EXPECT_EQ(w.bodies[i].position, before[i]);
  }
  EXPECT_LT(w.bodies[ball].position.z, 0.1);  // the ball fell
  // Fixed bodies cannot be given a velocity.
  const std::string moving = std::string(scene).replace(scene.find("fixed = true"), 12, "fixed = true\nvelocity = [0.0, 0.0, -1.0]");
  try {
    io::load_scene(moving, "scene.toml", ".");
    ADD_FAILURE() << "a moving fixed generator was accepted";
  } catch (const io::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("velocity must be zero for fixed bodies"), std::string::npos) << e.what();
  }
}

// Issue 54, point 14: a scene of 20 bonded boxes of 2,000 pieces printed
// nothing for 5 minutes. The builder now says what it starts on where that
// can take long (run and run --check print it after the build's first
// second, tests/cli_bonded.sh): each assembly's cut, each region's fill, the
// start's check.
TEST(WorldBuilder, SaysWhatALongBuildStartsOn) {
  std::vector<std::string> said;
  WorldBuilder b;
  b.set_progress([&](const std::string& what) { said.push_back(what); });
  Material m{.name = "rock", .density = 2500, .youngs_modulus = 1e8};
  m.glue = {.tensile_strength = 1e5, .shear_strength = 4e5};
  const std::uint32_t rock = b.add_material(m);
  b.add_bonded({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .pieces = 12, .material = rock, .label = "block"});
  std::mt19937_64 rng(1);
  b.fill_region({.variants = {{make_sphere(0.002), {}}}, .count = 5, .lo = {0.1, 0, 0}, .hi = {0.2, 0.1, 0.1},
                 .material = rock, .label = "heap"},
                rng);
  b.build();
  ASSERT_EQ(said.size(), 3u);
  EXPECT_EQ(said[0], "block: cutting it into 12 pieces");
  EXPECT_EQ(said[1], "heap: placing 5 bodies");
  EXPECT_EQ(said[2], "checking that the 17 bodies start apart");
}

}  // namespace
}  // namespace gjkdem::dem

namespace gjkdem::dem {
namespace {

// A big hull's kept surface (hull_surface) is made when the world is built
// under the volume law, and when breakage makes a fragment's template: a
// step's overlap() never makes one (issue 53). Small hulls keep none.
TEST(WorldBuilderPrepares, BigHullsSurfacesBeforeTheFirstStep) {
  std::mt19937_64 rng(7);
  const Shape big = random_polyhedron(300, 0.02, rng), small = random_polyhedron(12, 0.02, rng);
  const auto kept = [](const Shape& s) {
    const HullSurfaceSlot* slot = std::get<Polytope>(s.core).data->surface_slot;
    return slot && slot->surface != nullptr;
  };
  ASSERT_GE(std::get<Polytope>(big.core).data->triangles.size(), 256u);
  ASSERT_FALSE(kept(big));
  WorldSettings s;
  s.model = ContactModel::Volume;
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"rock", 2600, 1e7});
  b.add_body({.shape = {big, {}}, .material = m, .position = {0, 0, 0}});
  b.add_body({.shape = {small, {}}, .material = m, .position = {0.1, 0, 0}});
  const World w = b.build();
  EXPECT_TRUE(kept(w.templates[w.bodies[0].shape].shape));
  EXPECT_EQ(std::get<Polytope>(w.templates[w.bodies[1].shape].shape.core).data->surface_slot, nullptr);
  const ShapeTemplate fragment = fragment_template(std::get<Polytope>(random_polyhedron(300, 0.02, rng).core), 1, false);
  EXPECT_TRUE(kept(fragment.shape));
}

}  // namespace
}  // namespace gjkdem::dem
