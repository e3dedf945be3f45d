// A world's state exported as a scene (io::export_scene) and read back is
// the same world: every kind of moving body at the same place, turned the
// same way, with the same mass, velocity and angular momentum; bodies of one
// template still share one; names, fixed bodies and wall files (read from
// another folder) kept; what a scene cannot hold yet refused.
#include "gjkdem/io/scene_export.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/io/scene.hpp"

namespace gjkdem::io {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCommon = R"(
[simulation]
duration = 0.02
dt = 2e-5
seed = 4

[output]
every = 0.01

[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e6
friction = 0.5

[[material]]
name = "steel"
density = 7800.0
youngs_modulus = 2.0e6


[[wall]]
type = "plane"
normal = [0, 0, 1]
material = "steel"

[[wall]]
type = "mesh"
file = "ramp.obj"
material = "steel"

[[body]]
name = "post"
shape = { type = "cylinder", radius = 0.004, half_height = 0.01 }
material = "steel"
fixed = true
position = [0.05, 0.05, 0.01]

[[body]]
name = "tracer"
shape = { type = "platonic", name = "octahedron", size = 0.02 }
material = "rock"
position = [0.0, 0.0, 0.03]
velocity = [0.1, 0.0, -0.5]
angular_velocity = [3.0, 5.0, -1.0]

[[generator]]
count = 4
fixed = true
shape = { type = "platonic", name = "tetrahedron", size = 0.01 }
material = "steel"
region = { min = [0.06, -0.04, 0.0], max = [0.1, 0.04, 0.01] }

[[generator]]
count = 12
shapes = [ { shape = { type = "random_polyhedron", vertices = 9, size = [0.008, 0.012] }, fraction = 0.5 },
           { shape = { type = "sphere", radius = 0.004 }, fraction = 0.25 },
           { shape = { type = "ellipsoid", radii = [0.005, 0.004, 0.003] }, fraction = 0.25 } ]
material = "rock"
region = { min = [-0.04, -0.04, 0.05], max = [0.04, 0.04, 0.09] }
)";

constexpr const char* kCompound = R"(
[[body]]
shape = { type = "compound", parts = [ { type = "box", half_extents = [0.006, 0.002, 0.002], center = [0.006, 0, 0] }, { type = "box", half_extents = [0.002, 0.002, 0.006], center = [0.002, 0, 0.008] } ] }
material = "rock"
position = [-0.03, 0.0, 0.03]
rotation = [0.9238795325112867, 0.0, 0.3826834323650898, 0.0]
angular_velocity = [0.0, 0.0, 4.0]

)";

// A compound of a box and a surface (a 1 cm cube turned a quarter about z
// and moved by its center), touching at x = 0.
constexpr const char* kSurfaceCompound = R"(
[[body]]
shape = { type = "compound", parts = [ { type = "box", half_extents = [0.005, 0.005, 0.005], center = [-0.005, 0.005, 0.005] }, { type = "surface", vertices = [[0, 0, 0], [0.01, 0, 0], [0.01, 0.01, 0], [0, 0.01, 0], [0, 0, 0.01], [0.01, 0, 0.01], [0.01, 0.01, 0.01], [0, 0.01, 0.01]], triangles = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]], center = [0.01, 0, 0], rotation = [0.7071067811865476, 0.0, 0.0, 0.7071067811865476] } ] }
material = "rock"
position = [-0.03, 0.0, 0.03]
angular_velocity = [0.0, 0.0, 4.0]

)";

// Surface grains, in a scene of their own.
constexpr const char* kSurfaces = R"(
[shapes]
tet = { type = "surface", vertices = [[0, 0, 0], [0.012, 0, 0], [0, 0.012, 0], [0, 0, 0.012]], triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] }

[[body]]
shape = "tet"
material = "steel"
position = [0.03, 0.0, 0.03]
[[body]]
shape = "tet"
material = "rock"
position = [0.03, 0.03, 0.03]

)";

struct Folder {
  fs::path dir;
  Folder() : dir(fs::temp_directory_path() / ("gjkdem_export_" + std::to_string(::getpid()))) {
    fs::create_directories(dir / "scene");
    fs::create_directories(dir / "elsewhere");
    std::ofstream ramp(dir / "scene" / "ramp.obj");
    ramp << "v -0.06 -0.06 0.0\nv 0.0 -0.06 0.01\nv 0.0 0.06 0.01\nv -0.06 0.06 0.0\nf 1 2 3\nf 1 3 4\n";
  }
  ~Folder() { fs::remove_all(dir); }
};

// Where a body's shape reaches in a few world directions: the same solid at
// the same place and turn, whatever frame the scene gave it in.
std::vector<Vec3> reach(const dem::World& w, const dem::Body& b) {
  const dem::ShapeTemplate& t = w.templates[b.shape];
  const Transform pose = dem::shape_pose(t, b);
  std::vector<Vec3> out;
  for (const Vec3& d : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}, Vec3{-1, 0.3, 0.2}, Vec3{0.2, -1, 0.5},
                        Vec3{0.4, 0.1, -1}}) {
    const Vec3 local = apply_inverse_rotation(pose, d);
    out.push_back(apply(pose, support(t.shape, local)));
  }
  return out;
}

TEST(SceneExport, AnExportedStateIsTheSameWorldReadFromAnotherFolder) {
  for (const char* extra : {kCompound, kSurfaces, kSurfaceCompound}) {
  SCOPED_TRACE(extra == kCompound ? "with a compound" : extra == kSurfaces ? "with surface grains" : "with a surface part");
  const std::string source = std::string(kCommon) + extra;
  Folder f;
  Scene scene = load_scene(source, "export.toml", f.dir / "scene");
  if (extra == kSurfaceCompound) {  // the surface placed by its center and rotation: the 2 x 1 x 1 cm box they make
    const auto compound = std::find_if(scene.world.templates.begin(), scene.world.templates.end(),
                                       [](const dem::ShapeTemplate& t) { return !t.parts.empty(); });
    ASSERT_NE(compound, scene.world.templates.end());
    const dem::ShapeTemplate& t = *compound;
    ASSERT_EQ(t.parts.size(), 2u);
    EXPECT_TRUE(t.parts[1].surface_grain && !t.parts[0].surface_grain);
    EXPECT_NEAR(t.unit_mass.volume, 2e-6, 1e-18);
    EXPECT_LT(length(t.unit_mass.centroid - Vec3{0, 0.005, 0.005}), 1e-15);
  }
  dem::RunState run = dem::plan_run(0.02, 2e-5, 0.01);
  ASSERT_EQ(dem::run(scene.world, run, {}).status, dem::RunStatus::Completed);
  const dem::World& w = scene.world;
  const std::string text = export_scene(source, f.dir / "scene", w, "a test\nof two lines");
  EXPECT_EQ(text.rfind("# a test\n# of two lines\n", 0), 0u);
  EXPECT_NE(text.find((f.dir / "scene" / "ramp.obj").string()), std::string::npos) << "the wall's file, absolute";
  Scene back = load_scene(text, "exported.toml", f.dir / "elsewhere");  // refused if the wall's file were relative
  const dem::World& v = back.world;

  ASSERT_EQ(v.bodies.size(), w.bodies.size());
  EXPECT_EQ(v.templates.size(), w.templates.size()) << "bodies of one template share one after the export too";
  EXPECT_EQ(v.names.size(), w.names.size());
  const dem::Makeup before{w.templates, w.materials}, after{v.templates, v.materials};
  // The same bodies in the same order: the mesh wall's pieces, the post, the moving ones, the fixed generator's.
  int moving = 0;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const dem::Body &a = w.bodies[i], &b = v.bodies[i];
    SCOPED_TRACE("body " + std::to_string(i));
    ASSERT_EQ(a.fixed, b.fixed);
    moving += !a.fixed;
    const Real size = 0.02;
    EXPECT_NEAR(after.mass(b), before.mass(a), 1e-12 * before.mass(a) + 1e-300);
    EXPECT_LT(length(b.position - a.position), 1e-12 * size);
    const std::vector<Vec3> ra = reach(w, a), rb = reach(v, b);
    for (std::size_t k = 0; k < ra.size(); ++k) EXPECT_LT(length(rb[k] - ra[k]), 1e-12 * size) << "direction " << k;
    EXPECT_LT(length(b.velocity - a.velocity), 1e-12 * (1 + length(a.velocity)));
    EXPECT_LT(length(b.angular_momentum - a.angular_momentum), 1e-9 * length(a.angular_momentum) + 1e-18);
    EXPECT_EQ(v.materials[b.material].name, w.materials[a.material].name);
  }
  EXPECT_EQ(moving, extra == kSurfaces ? 15 : 14);
  for (std::size_t k = 0; k < w.names.size(); ++k) EXPECT_EQ(v.names[k].name, w.names[k].name);
  EXPECT_GT(w.stats.contacts, 0) << "a state with contacts to start from";

  // The exported scene runs on (its bodies touching as they were).
  dem::RunState more = dem::plan_run(0.005, 2e-5, 0.005);
  EXPECT_EQ(dem::run(back.world, more, {}).status, dem::RunStatus::Completed);
  }
}

// A thin shell (a tray) with a grain in it, under the Hertz law: exported
// as its triangles and thickness, read back the same body.
TEST(SceneExport, AShellComesBackAsItWas) {
  const std::string text = R"(
[simulation]
duration = 0.02
dt = 2e-5
[contact]
model = "hertz"
[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e6
[[wall]]
type = "plane"
normal = [0, 0, 1]
material = "rock"
[[body]]
shape = { type = "shell", thickness = 0.002, center = [0.0, 0.0, 0.001], rotation = [0.9238795325112867, 0.0, 0.0, 0.3826834323650898], vertices = [[-0.04, -0.04, 0], [0.04, -0.04, 0], [0.04, 0.04, 0], [-0.04, 0.04, 0], [-0.04, -0.04, 0.03], [0.04, -0.04, 0.03], [0.04, 0.04, 0.03], [-0.04, 0.04, 0.03]], triangles = [[0, 2, 1], [0, 3, 2], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]] }
material = "rock"
[[body]]
shape = { type = "box", half_extents = [0.01, 0.01, 0.01] }
material = "rock"
position = [0.0, 0.0, 0.0122]
)";
  Scene scene = load_scene(text, "shell.toml", fs::temp_directory_path());
  dem::RunState run = dem::plan_run(0.02, 2e-5, 0.02);
  ASSERT_EQ(dem::run(scene.world, run, {}).status, dem::RunStatus::Completed);
  const dem::World& w = scene.world;
  ASSERT_TRUE(w.templates[w.bodies[0].shape].shell);
  EXPECT_GT(w.stats.contacts, 1) << "the tray on the floor, the box in the tray";
  const std::string exported = export_scene(text, fs::temp_directory_path(), w, "");
  Scene back = load_scene(exported, "exported.toml", fs::temp_directory_path());
  const dem::World& v = back.world;
  ASSERT_EQ(v.bodies.size(), w.bodies.size());
  const dem::Makeup before{w.templates, w.materials}, after{v.templates, v.materials};
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const dem::Body &a = w.bodies[i], &b = v.bodies[i];
    EXPECT_NEAR(after.mass(b), before.mass(a), 1e-12 * before.mass(a));
    EXPECT_LT(length(b.position - a.position), 1e-12 * 0.08);
    const std::vector<Vec3> ra = reach(w, a), rb = reach(v, b);
    for (std::size_t k = 0; k < ra.size(); ++k) EXPECT_LT(length(rb[k] - ra[k]), 1e-12 * 0.08) << i << " direction " << k;
  }
  ASSERT_TRUE(v.templates[v.bodies[0].shape].shell);
  EXPECT_EQ(v.templates[v.bodies[0].shape].shell->margin, 0.001);
  dem::RunState more = dem::plan_run(0.005, 2e-5, 0.005);
  EXPECT_EQ(dem::run(back.world, more, {}).status, dem::RunStatus::Completed);
}

TEST(SceneExport, APeriodicCellTakesTheWorldsBoundsAndAShearedOneIsRefused) {
  const std::string text = R"(
[simulation]
duration = 0.01
dt = 1e-5
periodic = { x = [-0.02, 0.02], y = [-0.02, 0.02] }
[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e6
[[wall]]
type = "plane"
normal = [0, 0, 1]
material = "rock"
[[body]]
shape = { type = "sphere", radius = 0.004 }
material = "rock"
position = [0.0, 0.0, 0.005]
)";
  Scene scene = load_scene(text, "cell.toml", fs::temp_directory_path());
  scene.world.cell.now.lo.x = -0.025, scene.world.cell.now.hi.x = 0.025;
  const std::string exported = export_scene(text, fs::temp_directory_path(), scene.world, "");
  const Scene back = load_scene(exported, "exported.toml", fs::temp_directory_path());
  EXPECT_EQ(back.world.cell.now.lo.x, -0.025);
  EXPECT_EQ(back.world.cell.now.hi.x, 0.025);
  EXPECT_EQ(back.world.cell.now.hi.y, 0.02);
  scene.world.cell.now.tilt.x = 0.001;
  try {
    export_scene(text, fs::temp_directory_path(), scene.world, "");
    ADD_FAILURE() << "a sheared cell was exported";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("sheared"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gjkdem::io
