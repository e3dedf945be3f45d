// Scenes: a scene using every key loads into the expected world, and a set of
// bad scenes is refused with a message naming the problem (and its line).
#include "gjkdem/io/scene.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/run.hpp"

namespace gjkdem::io {
namespace {

const std::string kHead = R"(
[simulation]
duration = 0.1
dt = 1e-5

[[material]]
name = "rock"
density = 2000.0
youngs_modulus = 1.0e7
)";

const std::string kCube = R"(
[[body]]
name = "c"
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.01, 0.01, 0.01] }
material = "rock"
position = [0.0, 0.0, 0.05]
)";

const std::string kPlane = R"(
[[wall]]
type = "plane"
normal = [0.0, 0.0, 1.0]
material = "rock"
)";

const std::string kInflow = R"(
[[inflow]]
shape = { type = "sphere", radius = 0.005 }
material = "rock"
region = { min = [0.0, 0.0, 1.0], max = [0.1, 0.1, 1.1] }
)";

std::string refusal(const std::string& toml) {
  try {
    load_scene(toml, "test.toml", std::filesystem::temp_directory_path());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Scene, FullSceneLoads) {
  const std::string toml = "[simulation]\nduration = 0.1\ndt = 1e-5\ngravity = [0.0, 0.0, -9.81]\n" +
                           kHead.substr(kHead.find("[[material]]")) + R"(
[output]
dir = "somewhere"
every = 0.01
[contact]
model = "hertz"
[[wall]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 2.0]
material = "rock"
[[wall]]
type = "box"
min = [-0.2, -0.2, 0.0]
max = [0.2, 0.2, 0.3]
open_top = true
material = "rock"
[[generator]]
count = 40
shape = { type = "random_polyhedron", vertices = 10, size = [0.01, 0.02] }
material = "rock"
region = { min = [-0.15, -0.15, 0.05], max = [0.15, 0.15, 0.25] }
[[generator]]
count = 10
shape = { type = "platonic", name = "tetrahedron", size = 0.02 }
material = "rock"
region = { min = [-0.15, -0.15, 0.05], max = [0.15, 0.15, 0.25] }
)" + kCube;
  // The explicit cube sits at z = 0.05, so the generators fill around it.
  const Scene s = load_scene(toml, "full.toml", ".");
  EXPECT_EQ(s.output_dir, "somewhere");
  EXPECT_DOUBLE_EQ(s.dt, 1e-5);
  EXPECT_FALSE(s.dt_auto);
  ASSERT_EQ(s.world.planes.size(), 1u);
  EXPECT_NEAR(s.world.planes[0].normal.z, 1, 1e-15);  // normalised
  int moving = 0, fixed = 0;
  for (const dem::Body& b : s.world.bodies) (b.fixed ? fixed : moving)++;
  EXPECT_EQ(moving, 51);
  EXPECT_EQ(fixed, 5);  // open box: floor and four sides
  const std::vector<io::TracedBody> traced = io::traced_bodies(s.world);
  ASSERT_EQ(traced.size(), 1u);
  EXPECT_EQ(traced[0].name, "c");
  // The cube's centre of mass is where the author put its centre.
  EXPECT_NEAR(length(s.world.bodies[traced[0].body].position - Vec3{0, 0, 0.05}), 0, 1e-15);
  // No two moving bodies overlap, none crosses the floor.
  const auto& w = s.world;
  for (std::size_t i = 0; i < w.bodies.size(); ++i)
    for (std::size_t j = i + 1; j < w.bodies.size(); ++j) {
      if (w.bodies[i].fixed && w.bodies[j].fixed) continue;
      EXPECT_FALSE(intersect(w.templates[w.bodies[i].shape].shape, dem::shape_pose(w, w.bodies[i]),
                             w.templates[w.bodies[j].shape].shape, dem::shape_pose(w, w.bodies[j])))
          << i << " " << j;
    }
  EXPECT_NE(s.resolved_json.find("\"model\": \"hertz\""), std::string::npos);
}

TEST(Scene, SameSeedSameBodies) {
  const std::string toml = kHead + R"(
[[generator]]
count = 30
shape = { type = "random_polyhedron", vertices = 8, size = [0.01, 0.02] }
material = "rock"
region = { min = [-0.1, -0.1, 0.0], max = [0.1, 0.1, 0.2] }
)";
  const Scene a = load_scene(toml, "a", "."), b = load_scene(toml, "b", ".");
  ASSERT_EQ(a.world.bodies.size(), b.world.bodies.size());
  for (std::size_t i = 0; i < a.world.bodies.size(); ++i) {
    EXPECT_EQ(a.world.bodies[i].position, b.world.bodies[i].position);
    EXPECT_EQ(a.world.bodies[i].orientation.w, b.world.bodies[i].orientation.w);
  }
  const Scene c = load_scene(toml + "\n", "c", ".");
  EXPECT_EQ(c.world.bodies[3].position, a.world.bodies[3].position);
}

TEST(Scene, DefaultSceneLoads) {
  const Scene s = load_scene(default_scene_toml(), "default", ".");
  EXPECT_GT(s.world.bodies.size(), 1990u);
  EXPECT_TRUE(s.dt_auto);
  EXPECT_GT(s.dt, 0);
  EXPECT_EQ(s.world.settings.model, dem::ContactModel::Volume);
}

TEST(Scene, VolumeFormIsRead) {
  EXPECT_EQ(load_scene(kHead + kCube, "x", ".").world.settings.volume_form, dem::VolumeForm::Normalized);
  const Scene s =
      load_scene(kHead + "[contact]\nvolume_form = \"potential\"\nrocking_resistance = false\n" + kCube, "x", ".");
  EXPECT_EQ(s.world.settings.volume_form, dem::VolumeForm::Potential);
  EXPECT_FALSE(s.world.settings.rocking_resistance);
  EXPECT_NE(s.resolved_json.find("\"volume_form\": \"potential\""), std::string::npos) << s.resolved_json;
}

// Issue 11: an integer beyond 2^53 in a number key is read (rounded), and the
// run it asks for is refused by the planner with the range it supports; a
// time step longer than the run is refused; a plane normal with huge
// components is normalised, not turned into zero.
TEST(Scene, ExtremeNumbersAreReadOrRefusedWithTheirRange) {
  const Scene s = load_scene("[simulation]\nduration = 9007199254740993\ndt = 1e-5\n" +
                                 kHead.substr(kHead.find("[[material]]")) + kCube,
                             "x", ".");
  EXPECT_EQ(s.duration, 9007199254740992.0);
  try {
    dem::plan_run(s.duration, s.dt, s.output_every);
    ADD_FAILURE() << "planned";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("more than 2^53"), std::string::npos) << e.what();
  }
  EXPECT_THROW(dem::plan_run(0.01, 1.0, 0.001), std::invalid_argument);  // dt longer than the run
  EXPECT_THROW(dem::plan_run(1.0, 0.0, 0.1), std::invalid_argument);
  const Scene p = load_scene(kHead + kCube + R"(
[[wall]]
type = "plane"
point = [0.0, 0.0, -1.0]
normal = [0.0, 1e200, 1e200]
material = "rock"
)", "x", ".");
  ASSERT_EQ(p.world.planes.size(), 1u);
  EXPECT_NEAR(p.world.planes[0].normal.y, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(p.world.planes[0].normal.z, std::sqrt(0.5), 1e-15);
}

// Issue 11: restitutions of 1e-162 passed the check and failed mid-run (the
// pair's sqrt(e_a e_b) underflowed to 0). They now calibrate like any small e.
TEST(Scene, TinyRestitutionCalibrates) {
  const Scene s = load_scene(kHead + "restitution = 1e-200\n" + kCube, "x", ".");
  const dem::MaterialPair& p = s.world.material_pairs(0, 0);
  EXPECT_GT(p.restitution, 0);
  EXPECT_TRUE(std::isfinite(p.damping) && p.damping > 0);
}

// Issue 11: a mesh scaled by 1e300 was accepted: refused, naming the key and line.
// Surface grains (issue 30): bodies, generators (sized) and inflows take a
// closed mesh as it is, sharing one surface per file and scale; a mesh that
// is not closed, or faces inward, is refused naming the file and the edge.
TEST(Scene, SurfaceGrainsComeFromClosedMeshes) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gjkdem_surface_scene";
  std::filesystem::create_directories(dir);
  // An L-shaped prism (non-convex), 8 mm thick.
  {
    std::ofstream obj(dir / "ell.obj");
    const double xy[6][2] = {{0, 0}, {0.02, 0}, {0.02, 0.01}, {0.01, 0.01}, {0.01, 0.02}, {0, 0.02}};
    for (double z : {0.0, 0.008})
      for (const auto& p : xy) obj << "v " << p[0] - 0.008 << " " << p[1] - 0.008 << " " << z - 0.004 << "\n";
    obj << "f 1 3 2\nf 1 4 3\nf 1 5 4\nf 1 6 5\nf 7 8 9\nf 7 9 10\nf 7 10 11\nf 7 11 12\n";
    for (int i = 0; i < 6; ++i) {
      const int j = (i + 1) % 6;
      obj << "f " << i + 1 << " " << j + 1 << " " << j + 7 << "\nf " << i + 1 << " " << j + 7 << " " << i + 7 << "\n";
    }
    std::ofstream open(dir / "open.obj");  // an octahedron without its last face
    open << "v 0.01 0 0\nv -0.01 0 0\nv 0 0.01 0\nv 0 -0.01 0\nv 0 0 0.01\nv 0 0 -0.01\n"
            "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\n";
    std::ofstream inward(dir / "inward.obj");  // a tetrahedron facing in
    inward << "v 0 0 0\nv 0.01 0 0\nv 0 0.01 0\nv 0 0 0.01\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
  }
  const std::string head = kHead + "[contact]\nmodel = \"volume\"\n" + kPlane;
  Scene scene = load_scene(head + R"(
[[body]]
shape = { type = "surface", file = "ell.obj" }
material = "rock"
position = [0.0, 0.0, 0.05]
[[generator]]
count = 30
shape = { type = "surface", file = "ell.obj" }
sizes = [[0.02, 0.03, 1.0]]
material = "rock"
region = { min = [-0.2, -0.2, 0.1], max = [0.2, 0.2, 0.3] }
[[inflow]]
shape = { type = "surface", file = "ell.obj" }
material = "rock"
rate = 100.0
region = { min = [-0.2, -0.2, 0.5], max = [0.2, 0.2, 0.6] }
)", "test.toml", dir);
  const dem::World& w = scene.world;
  ASSERT_EQ(w.bodies.size(), 31u);
  const dem::ShapeTemplate& body = w.templates[w.bodies[0].shape];
  ASSERT_TRUE(body.surface_grain);
  EXPECT_NEAR(body.unit_mass.volume, 3 * 1e-4 * 0.008, 1e-15);  // the L, not its hull (4 of 1e-4 m^2)
  for (const dem::Body& b : w.bodies) {
    const dem::ShapeTemplate& t = w.templates[b.shape];
    ASSERT_TRUE(t.surface_grain);
    Real size = 0;  // the diameter of the sphere about its frame holding it: in the size class
    for (const Vec3& v : t.surface->vertices) size = std::fmax(size, 2 * length(v));
    if (&b == &w.bodies[0]) continue;
    EXPECT_GE(size, 0.02 * (1 - 1e-12));
    EXPECT_LE(size, 0.03 * (1 + 1e-12));
  }
  ASSERT_EQ(w.inflows.size(), 1u);
  EXPECT_TRUE(w.templates[w.inflows[0].templates[0]].surface_grain);
  for (const auto& [file, what] : {std::pair{"open.obj", "edge"}, std::pair{"inward.obj", "inward"}}) {
    const std::string message = refusal(head + "[[body]]\nshape = { type = \"surface\", file = \"" +
                                        (dir / file).string() + "\" }\nmaterial = \"rock\"\n");
    EXPECT_NE(message.find("body[0].shape.file"), std::string::npos) << message;
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
  std::filesystem::remove_all(dir);
}

TEST(Scene, MeshScaledBeyondDoublesIsRefused) {
  const std::filesystem::path obj = std::filesystem::temp_directory_path() / "gjkdem_scene_test_tetra.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string message = refusal(kHead + kCube + "[[wall]]\ntype = \"mesh\"\nfile = \"" + obj.string() +
                                      "\"\nscale = 1e300\nmaterial = \"rock\"\n");
  EXPECT_NE(message.find("wall[0].scale: puts the mesh beyond 1e100 m"), std::string::npos) << message;
  std::filesystem::remove(obj);
}

// A mesh wall's STL facet whose corners weld into one vertex twice (a CAD
// sliver) holds nothing: it is left out, and the scene says so; the others
// are the wall's pieces.
TEST(Scene, MeshWallFacetsWithoutAreaAreLeftOutAndSaid) {
  const std::filesystem::path stl = std::filesystem::temp_directory_path() / "gjkdem_scene_test_sliver.stl";
  const auto facet = [](const char* a, const char* b, const char* c) {
    return std::string("facet normal 0 0 1\nouter loop\nvertex ") + a + "\nvertex " + b + "\nvertex " + c +
           "\nendloop\nendfacet\n";
  };
  std::ofstream(stl) << "solid floor\n" + facet("-1 -1 0", "1 -1 0", "1 1 0") + facet("-1 -1 0", "1 1 0", "-1 1 0") +
                            facet("1 1 0", "1 1 0", "-1 1 0") + "endsolid floor\n";
  const Scene s = load_scene(kHead + kCube + "[[wall]]\ntype = \"mesh\"\nfile = \"" + stl.string() +
                                 "\"\nthickness = 0.002\nmaterial = \"rock\"\n",
                             "sliver.toml", ".");
  std::size_t pieces = 0;
  for (const dem::Body& b : s.world.bodies) pieces += b.fixed;
  EXPECT_EQ(pieces, 2u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "wall[0]: 1 triangles of gjkdem_scene_test_sliver.stl name a vertex twice (no area): left out");
  std::filesystem::remove(stl);
}

// A generator's region drawn past the side of a closed mesh (a box region in
// a drum) puts bodies outside it, which fall away for the whole run: the
// scene says how many. Inside, or around a closed obstacle, it says nothing.
TEST(Scene, BodiesGeneratedOutsideTheContainerHoldingTheOthersAreWarnedOf) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gjkdem_container_scene";
  std::filesystem::create_directories(dir);
  {
    std::ofstream obj(dir / "drum.obj");  // a closed 32-sided drum along y, radius 0.1, length 0.1, faces inward
    const int n = 32;
    for (const double y : {-0.05, 0.05})
      for (int k = 0; k < n; ++k)
        obj << "v " << 0.1 * std::cos(2 * kPi * k / n) << " " << y << " " << 0.1 * std::sin(2 * kPi * k / n) << "\n";
    obj << "v 0 -0.05 0\nv 0 0.05 0\n";
    for (int k = 0; k < n; ++k) {
      const int k2 = (k + 1) % n;
      obj << "f " << k + 1 << " " << k2 + 1 << " " << n + k2 + 1 << "\nf " << k + 1 << " " << n + k2 + 1 << " " << n + k + 1
          << "\nf " << 2 * n + 1 << " " << k2 + 1 << " " << k + 1 << "\nf " << 2 * n + 2 << " " << n + k + 1 << " "
          << n + k2 + 1 << "\n";
    }
  }
  const auto scene_with = [&](const std::string& region) {
    return load_scene(kHead + R"([[wall]]
type = "mesh"
file = "drum.obj"
material = "rock"
thickness = 0.004

[[generator]]
count = 200
shape = { type = "sphere", radius = 0.004 }
material = "rock"
region = )" + region + "\n", "drum.toml", dir);
  };
  // A box as wide as the drum: its corners stick out.
  const Scene wide = scene_with("{ min = [-0.1, -0.04, -0.1], max = [0.1, 0.04, 0.1] }");
  ASSERT_EQ(wide.warnings.size(), 1u);
  EXPECT_NE(wide.warnings[0].find("generator[0]: "), std::string::npos) << wide.warnings[0];
  EXPECT_NE(wide.warnings[0].find("of its 200 bodies lie outside the closed mesh wall[0] (drum.obj)"), std::string::npos)
      << wide.warnings[0];
  // Count the bodies outside the drum's round side here, and compare.
  std::size_t outside = 0;
  for (const dem::Body& b : wide.world.bodies)
    if (!b.fixed && std::hypot(b.position.x, b.position.z) > 0.1 * std::cos(kPi / 32)) ++outside;
  ASSERT_GT(outside, 0u);
  EXPECT_EQ(wide.warnings[0].substr(wide.warnings[0].find(": ") + 2, std::to_string(outside).size() + 1),
            std::to_string(outside) + " ");
  EXPECT_TRUE(scene_with("{ min = [-0.06, -0.04, -0.06], max = [0.06, 0.04, 0.06] }").warnings.empty());
  // All outside (the drum an obstacle in a bigger region's way): nothing to say.
  EXPECT_TRUE(scene_with("{ min = [-0.3, -0.04, 0.11], max = [0.3, 0.04, 0.3] }").warnings.empty());
  std::filesystem::remove_all(dir);
}

// A stack may start at its resting overlap when the scene says so.
TEST(Scene, InitialOverlapsCanBeAccepted) {
  const std::string stack = kCube + R"(
[[body]]
shape = { type = "box", half_extents = [0.01, 0.01, 0.01] }
material = "rock"
position = [0.0, 0.0, 0.0699999]
)";
  EXPECT_NE(refusal(kHead + stack).find("overlaps"), std::string::npos);
  const Scene s = load_scene("[simulation]\nduration = 0.1\ninitial_overlaps = \"accept\"\n" +
                                 kHead.substr(kHead.find("[[material]]")) + stack,
                             "x", ".");
  EXPECT_EQ(s.world.bodies.size(), 2u);
  EXPECT_NE(s.resolved_json.find("\"initial_overlaps\": \"accept\""), std::string::npos);
  EXPECT_NE(refusal("[simulation]\nduration = 0.1\ninitial_overlaps = \"maybe\"\n" +
                    kHead.substr(kHead.find("[[material]]")) + kCube)
                .find("initial_overlaps: must be"),
            std::string::npos);
}

// Issue 11: these messages named neither key nor line.
TEST(Scene, MotionsAreReadAndResolved) {
  const Scene scene = load_scene(kHead + kCube + kPlane + R"(motion = { velocity = [0.1, 0.0, 0.0], vibration = { amplitude = [0.0, 0.0, 0.002], frequency = 20.0 } }
[[wall]]
type = "box"
min = [-0.2, -0.2, -0.5]
max = [0.2, 0.2, 0.5]
material = "rock"
motion = { center = [0.0, 0.0, 0.1], angular_velocity = [0.0, 2.0, 0.0], table = [[0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.5]] }
)", "test.toml", std::filesystem::temp_directory_path());
  const dem::World& w = scene.world;
  ASSERT_EQ(w.motions.size(), 2u);
  EXPECT_EQ(w.planes.at(0).motion, 1u);
  EXPECT_EQ(w.motions[0].velocity, (Vec3{0.1, 0, 0}));
  EXPECT_EQ(w.motions[0].frequency, 20.0);
  EXPECT_EQ(w.motions[1].center, (Vec3{0, 0, 0.1}));
  EXPECT_EQ(w.motions[1].table_times.size(), 2u);
  std::size_t driven = 0;
  for (const dem::Body& b : w.bodies) driven += b.motion == 2;
  EXPECT_EQ(driven, 6u);  // the box's six slabs
  EXPECT_EQ(w.driven.size(), 6u);
  const nlohmann::json resolved = nlohmann::json::parse(scene.resolved_json);
  EXPECT_EQ(resolved["wall"][1]["motion"]["angular_velocity"], nlohmann::json::parse("[0.0, 2.0, 0.0]"));
  EXPECT_EQ(resolved["wall"][0]["motion"]["vibration"]["frequency"], 20.0);
}

// Mass fraction of the bodies in each group (`group_of` a body, < groups)
// and its sampling error: the standard error of a ratio of sums, by the
// delta method, from the sample itself.
struct Fractions {
  std::vector<double> value, error;
};
template <class F>
Fractions mass_fractions(const dem::World& w, std::size_t groups, F group_of) {
  double total = 0;
  std::vector<double> mass(groups, 0);
  std::vector<std::pair<std::size_t, double>> bodies;
  for (const dem::Body& b : w.bodies) {
    if (b.fixed) continue;
    const double m = dem::mass_of(w, b);
    const std::size_t g = group_of(b);
    mass.at(g) += m;
    total += m;
    bodies.emplace_back(g, m);
  }
  Fractions f;
  for (std::size_t g = 0; g < groups; ++g) {
    const double p = mass[g] / total;
    double variance = 0;
    for (const auto& [group, m] : bodies) variance += std::pow(m * ((group == g) - p), 2);
    f.value.push_back(p);
    f.error.push_back(std::sqrt(variance) / total);
  }
  return f;
}

TEST(Scene, SieveTablesAndShapeMixesGiveTheirMassFractions) {
  // 3,000 spheres and cubes, 70% of the mass in cubes, in three size classes
  // of 20%, 50% and 30% of the mass.
  const Scene scene = load_scene(R"(
[simulation]
duration = 0.1
[contact]
model = "hertz"
[[material]]
name = "rock"
density = 2000.0
youngs_modulus = 1.0e7
[[generator]]
count = 3000
shapes = [ { shape = { type = "platonic", name = "cube", size = 0.01 }, fraction = 0.7 },
           { shape = { type = "sphere", radius = 0.005 }, fraction = 0.3 } ]
fractions = "mass"
sizes = [[0.004, 0.006, 0.2], [0.006, 0.010, 0.5], [0.010, 0.014, 0.3]]
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [1.0, 1.0, 1.0] }
)", "test.toml", std::filesystem::temp_directory_path());
  const dem::World& w = scene.world;
  const auto size_of = [&](const dem::Body& b) { return 2 * bounding_radius(w.templates[b.shape].shape); };
  const Fractions by_size = mass_fractions(w, 3, [&](const dem::Body& b) {
    const double d = size_of(b);
    EXPECT_TRUE(d >= 0.004 - 1e-12 && d <= 0.014 + 1e-12) << d;
    return d < 0.006 ? 0u : d < 0.010 ? 1u : 2u;
  });
  const double expected_size[3] = {0.2, 0.5, 0.3};
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(by_size.value[c], expected_size[c], 4 * by_size.error[c]) << "size class " << c;
  const Fractions by_shape = mass_fractions(w, 2, [&](const dem::Body& b) {
    return std::holds_alternative<Polytope>(w.templates[b.shape].shape.core) ? 0u : 1u;
  });
  EXPECT_NEAR(by_shape.value[0], 0.7, 4 * by_shape.error[0]);
  EXPECT_GT(by_size.error[0], 0.003);  // a real sample: the test could fail
  EXPECT_LT(by_size.error[1], 0.03);
  EXPECT_NE(scene.resolved_json.find("\"sizes\""), std::string::npos);
}

TEST(Scene, InflowsAreReadAndRun) {
  Scene scene = load_scene(R"(
[simulation]
duration = 0.5
[[material]]
name = "rock"
density = 2000.0
youngs_modulus = 1.0e7
[[inflow]]
shape = { type = "random_polyhedron", vertices = 10 }
sizes = [[0.004, 0.006, 0.5], [0.006, 0.008, 0.5]]
material = "rock"
rate = 100.0
start = 0.1
region = { min = [0.0, 0.0, 1.0], max = [0.1, 0.1, 1.0] }
velocity = [0.0, 0.0, -1.0]
)", "test.toml", std::filesystem::temp_directory_path());
  dem::World& w = scene.world;
  ASSERT_EQ(w.inflows.size(), 1u);
  EXPECT_EQ(w.inflows[0].stop, 0.5);  // the run's end
  EXPECT_EQ(w.inflows[0].templates.size(), 20u);  // 10 variants per size class
  EXPECT_TRUE(w.bodies.empty());
  EXPECT_LT(scene.dt, 1e-4) << "dt = auto sees the bodies to come";
  dem::RunState run = dem::plan_run(scene.duration, scene.dt, scene.output_every);
  const dem::RunOutcome outcome = dem::run(w, run, {});
  ASSERT_EQ(outcome.status, dem::RunStatus::Completed) << outcome.error;
  EXPECT_NEAR(static_cast<double>(w.bodies.size()), 41, 1);  // bodies 0..40 due in [0.1, 0.5]
}

TEST(Scene, CompoundsComeFromPartsOrTheObjectsOfAMesh) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gjkdem_compound_scene";
  std::filesystem::create_directories(dir);
  {
    std::ofstream obj(dir / "ell.obj");  // two boxes as two objects, as V-HACD writes them
    for (const auto& [name, x0, x1, z0, z1] : {std::tuple{"foot", 0.0, 0.04, 0.0, 0.01}, std::tuple{"leg", 0.0, 0.01, 0.01, 0.04}}) {
      obj << "o " << name << "\n";
      for (int k = 0; k < 8; ++k)
        obj << "v " << ((k & 1) ? x1 : x0) << " " << ((k & 2) ? 0.005 : -0.005) << " " << ((k & 4) ? z1 : z0) << "\n";
      for (const char* f : {"1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6"}) {
        obj << "f";
        std::istringstream idx(f);
        for (int i; idx >> i;) obj << " " << -(9 - i);  // relative indices into this object's 8 vertices
        obj << "\n";
      }
    }
  }
  const std::string parts_scene = kHead + R"([[body]]
shape = { type = "compound", parts = [ { type = "box", center = [0.02, 0.0, 0.005], half_extents = [0.02, 0.005, 0.005] },
                                       { type = "box", center = [0.005, 0.0, 0.025], half_extents = [0.005, 0.005, 0.015] } ] }
material = "rock"
position = [0.0, 0.0, 0.1]
)";
  const std::string file_scene = kHead + R"([[body]]
shape = { type = "compound", file = "ell.obj" }
material = "rock"
position = [0.0, 0.0, 0.1]
)";
  const Scene from_parts = load_scene(parts_scene, "parts.toml", dir);
  const Scene from_file = load_scene(file_scene, "file.toml", dir);
  for (const Scene* scene : {&from_parts, &from_file}) {
    const dem::ShapeTemplate& t = scene->world.templates.at(scene->world.bodies.at(0).shape);
    ASSERT_EQ(t.parts.size(), 2u);
    EXPECT_NEAR(t.unit_mass.volume / 2000.0 * 2000.0, 7e-6, 1e-15);
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings.front();
  }
  const dem::ShapeTemplate &a = from_parts.world.templates[0], &b = from_file.world.templates[0];
  EXPECT_LT(length(a.unit_mass.centroid - b.unit_mass.centroid), 1e-15);
  EXPECT_NEAR(a.principal.moments.z, b.principal.moments.z, 1e-12 * a.principal.moments.z);
  // A non-convex mesh of one object stays its hull, with a warning that points to compounds.
  {
    std::ofstream obj(dir / "one.obj");
    std::ifstream in(dir / "ell.obj");
    for (std::string line; std::getline(in, line);)
      if (line.rfind("o ", 0) != 0) obj << line << "\n";
  }
  const Scene hull = load_scene(kHead + R"([[body]]
shape = { type = "mesh", file = "one.obj" }
material = "rock"
position = [0.0, 0.0, 0.1]
)", "one.toml", dir);
  ASSERT_FALSE(hull.warnings.empty());
  EXPECT_NE(hull.warnings.front().find("compound"), std::string::npos) << hull.warnings.front();
  EXPECT_NE(refusal(kHead + R"([[body]]
shape = { type = "compound", parts = [ { type = "compound", parts = [] } ] }
material = "rock"
)"), "(accepted)");
  EXPECT_NE(refusal(kHead + R"([[body]]
shape = { type = "compound", parts = [ { type = "box", half_extents = [0.01, 0.01, 0.01] },
                                       { type = "box", center = [0.01, 0.0, 0.0], half_extents = [0.01, 0.01, 0.01] } ] }
material = "rock"
)").find("parts 0 and 1 overlap"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Scene, BuildMessagesNameTheirLines) {
  const std::string overlap = refusal(kHead + kCube + R"(
[[body]]
shape = { type = "box", half_extents = [0.01, 0.01, 0.01] }
material = "rock"
position = [0.0, 0.0, 0.055]
)");
  EXPECT_NE(overlap.find("body[0] overlaps body[1] by 0.015 m at the start (line 11, line 17)"), std::string::npos)
      << overlap;
  const std::string inside = refusal(kHead + kCube + "[[wall]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.1]\n"
                                                     "normal = [0.0, 0.0, 1.0]\nmaterial = \"rock\"\n");
  EXPECT_NE(inside.find("body[0] starts inside a plane wall (point 0, 0, 0.1) (line 11)"), std::string::npos) << inside;
  for (const std::string& missing :
       {refusal(kHead + "[[body]]\nmaterial = \"rock\"\n"), refusal(kHead + "[[wall]]\ntype = \"plane\"\nmaterial = \"rock\"\n"),
        refusal(kHead + "[[wall]]\ntype = \"box\"\nmaterial = \"rock\"\n"),
        refusal(kHead + "[[generator]]\ncount = 3\nmaterial = \"rock\"\nshape = { type = \"sphere\", radius = 0.01 }\n")})
    EXPECT_NE(missing.find("(line 10)"), std::string::npos) << missing;
}

struct Bad {
  std::string name, toml, expected;  // expected: a piece of the message
};

class BadScene : public ::testing::TestWithParam<Bad> {};

// A generator (or with `table` "inflow" and `amount` "rate = 100.0", an
// inflow) of bonded assemblies of `pieces`.
std::string bonded_generator(int pieces = 6, const std::string& table = "generator",
                             const std::string& amount = "count = 4") {
  return "[[" + table + "]]\n" + amount + "\nshape = { type = \"bonded\", shape = { type = \"box\", half_extents = "
         "[0.01, 0.01, 0.01] }, pieces = " + std::to_string(pieces) + " }\nmaterial = \"rock\"\n"
         "region = { min = [-0.1, -0.1, 0.0], max = [0.1, 0.1, 0.1] }\n";
}
const std::string kBondedGenerator = bonded_generator();

TEST_P(BadScene, IsRefusedNamingTheProblem) {
  const Bad& b = GetParam();
  const std::string message = refusal(b.toml);
  EXPECT_NE(message.find(b.expected), std::string::npos) << "message: " << message;
}

const std::string kNoSim = R"(
[[material]]
name = "rock"
density = 2000.0
youngs_modulus = 1.0e7
)";

INSTANTIATE_TEST_SUITE_P(
    Scenes, BadScene,
    ::testing::Values(
        Bad{"syntax", "[simulation\nduration = 1", "line 1"},
        Bad{"no_simulation", kNoSim + kCube, "[simulation]"},
        Bad{"no_duration", "[simulation]\ndt = 1e-5\n" + kNoSim + kCube, "'duration'"},
        Bad{"unknown_top_key", kHead + kCube + "\n[extra]\nx = 1\n", "unknown key 'extra' (line"},
        // A misspelt section is refused first, before any body is read (and
        // cut or placed: minutes on a big scene), not after.
        Bad{"misspelt_section_first",
            kHead + "[[plane]]\nnormal = [0.0, 0.0, 1.0]\n[[body]]\nshape = { type = \"box\", half_extents = [0.01, 0.01, 0.01] }\nmaterial = \"nope\"\n",
            "unknown key 'plane' (line"},
        Bad{"unknown_body_key", kHead + kCube + "colour = \"red\"\n", "unknown key 'colour' (line 16)"},
        Bad{"unknown_simulation_key", "[simulation]\nduration = 1.0\nsubsteps = 3\n" + kNoSim + kCube,
            "simulation: unknown key 'substeps' (line 3)"},
        Bad{"string_for_number", "[simulation]\nduration = \"long\"\n" + kNoSim + kCube,
            "simulation.duration: must be a number (line 2)"},
        Bad{"bad_dt", "[simulation]\nduration = 1.0\ndt = \"fast\"\n" + kNoSim + kCube, "\"auto\""},
        Bad{"negative_dt", "[simulation]\nduration = 1.0\ndt = -1.0\n" + kNoSim + kCube, "dt: must be > 0"},
        Bad{"negative_density", "[simulation]\nduration = 1.0\n[[material]]\nname = \"rock\"\ndensity = -5.0\n"
                                "youngs_modulus = 1e7\n" + kCube,
            "material[0].density: must be > 0 (line 5)"},
        Bad{"restitution_zero", kHead + "restitution = 0.0\n" + kCube, "restitution: must lie in (0, 1]"},
        Bad{"negative_friction", kHead + "friction = -0.1\n" + kCube, "friction: must be >= 0"},
        Bad{"negative_rolling_friction", kHead + "rolling_friction = -0.1\n" + kCube, "rolling_friction: must be >= 0"},
        Bad{"infinite_rolling_friction", kHead + "rolling_friction = inf\n" + kCube, "rolling_friction: must be finite"},
        Bad{"rolling_damping_above_one", kHead + "rolling_damping = 1.5\n" + kCube,
            "rolling_damping: must lie in [0, 1]"},
        Bad{"unknown_material", kHead + kCube + "\n" + R"([[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.01, 0.01, 0.01] }
material = "wood"
position = [1.0, 0.0, 0.05]
)",
            "no [[material]] is named 'wood'"},
        Bad{"wrong_shape_type", kHead + R"([[body]]
shape = { type = "blob", center = [0.0, 0.0, 0.0] }
material = "rock"
)",
            "body[0].shape"},
        Bad{"negative_radius", kHead + R"([[body]]
shape = { type = "sphere", center = [0.0, 0.0, 0.0], radius = -1.0 }
material = "rock"
)",
            "radius"},
        Bad{"overlapping_bodies", kHead + kCube + R"(
[[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.01, 0.01, 0.01] }
material = "rock"
position = [0.0, 0.0, 0.055]
)",
            "body[0] overlaps body[1]"},
        Bad{"body_in_plane", kHead + kCube + R"(
[[wall]]
type = "plane"
point = [0.0, 0.0, 0.1]
normal = [0.0, 0.0, 1.0]
material = "rock"
)",
            "body[0] starts inside a plane wall"},
        Bad{"missing_mesh_file", kHead + kCube + R"(
[[wall]]
type = "mesh"
file = "no-such-hopper.stl"
material = "rock"
)",
            "file not found"},
        Bad{"bad_quaternion", kHead + R"([[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.01, 0.01, 0.01] }
material = "rock"
rotation = [1.0, 1.0, 0.0, 0.0]
)",
            "rotation: must be a unit quaternion"},
        Bad{"region_too_small", kHead + R"([[generator]]
count = 1000
shape = { type = "platonic", name = "cube", size = 0.02 }
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [0.1, 0.1, 0.1] }
)",
            "the region holds only 125 of the 1000 bodies"},
        Bad{"zero_count", kHead + R"([[generator]]
count = 0
shape = { type = "platonic", name = "cube", size = 0.02 }
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [0.1, 0.1, 0.1] }
)",
            "count: must be a positive integer"},
        Bad{"bad_platonic", kHead + R"([[generator]]
count = 1
shape = { type = "platonic", name = "sphere", size = 0.02 }
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [0.1, 0.1, 0.1] }
)",
            "unknown platonic solid 'sphere'"},
        Bad{"bad_model", kHead + "[contact]\nmodel = \"magic\"\n" + kCube, "contact.model: must be"},
        Bad{"bad_volume_form", kHead + "[contact]\nvolume_form = \"exact\"\n" + kCube, "contact.volume_form: must be"},
        Bad{"wall_type", kHead + kCube + "[[wall]]\ntype = \"torus\"\nmaterial = \"rock\"\n", "wall[0].type"},
        Bad{"duplicate_material", kHead + "[[material]]\nname = \"rock\"\ndensity = 1.0\nyoungs_modulus = 1.0\n" + kCube,
            "defined twice"},
        Bad{"only_fixed", kHead + R"([[body]]
shape = { type = "box", center = [0.0, 0.0, 0.0], half_extents = [0.01, 0.01, 0.01] }
material = "rock"
fixed = true
)",
            "no moving body"},
        Bad{"gravity_length", "[simulation]\nduration = 1.0\ngravity = [0.0, -9.81]\n" + kNoSim + kCube,
            "gravity: must have 3 numbers"},
        Bad{"body_not_array", kHead + "[body]\nmaterial = \"rock\"\n", "write [[body]]"},
        // Motions of walls and fixed bodies.
        Bad{"motion_on_moving_body", kHead + kCube + "motion = { velocity = [1.0, 0.0, 0.0] }\n",
            "body[0].motion: is for fixed bodies"},
        Bad{"fixed_body_velocity", kHead + kCube + "fixed = true\nvelocity = [1.0, 0.0, 0.0]\n", "give it a 'motion'"},
        Bad{"fixed_body_applied_force", kHead + kCube + "fixed = true\napplied_force = [1.0, 0.0, 0.0]\n", "takes no applied load"},
        Bad{"applied_torque_not_a_vector", kHead + kCube + "applied_torque = [1.0, 0.0]\n", "applied_torque"},
        Bad{"motion_unknown_key", kHead + kCube + kPlane + "motion = { speed = 2.0 }\n",
            "wall[0].motion: unknown key 'speed'"},
        Bad{"motion_not_table", kHead + kCube + kPlane + "motion = 3.0\n", "wall[0].motion: must be a table"},
        Bad{"vibration_no_amplitude", kHead + kCube + kPlane + "motion = { vibration = { frequency = 5.0 } }\n",
            "wall[0].motion.vibration: missing required key 'amplitude'"},
        Bad{"vibration_zero_frequency",
            kHead + kCube + kPlane + "motion = { vibration = { amplitude = [0.0, 0.0, 0.001], frequency = 0.0 } }\n",
            "wall[0].motion.vibration.frequency: must be > 0"},
        Bad{"table_times_decrease",
            kHead + kCube + kPlane + "motion = { table = [[0.0, 0.0, 0.0, 0.0], [0.0, 0.1, 0.0, 0.0]] }\n",
            "wall[0].motion.table: times must increase"},
        Bad{"table_short_row", kHead + kCube + kPlane + "motion = { table = [[0.0, 0.0, 0.0]] }\n",
            "wall[0].motion.table: must be an array of rows [time, x, y, z]"},
        Bad{"table_empty", kHead + kCube + kPlane + "motion = { table = [] }\n", "wall[0].motion.table: must be"},
        Bad{"inflow_two_rates", kHead + kCube + kInflow + "rate = 10.0\nmass_rate = 1.0\n", "give one of 'rate'"},
        Bad{"inflow_no_rate", kHead + kCube + kInflow, "give one of 'rate'"},
        Bad{"inflow_negative_rate", kHead + kCube + kInflow + "rate = -1.0\n", "inflow[0].rate: must be > 0"},
        Bad{"inflow_stop_before_start", kHead + kCube + kInflow + "rate = 1.0\nstart = 0.5\nstop = 0.2\n",
            "inflow[0].stop: must come after the start"},
        Bad{"inflow_too_many", kHead + kCube + kInflow + "rate = 1e12\n", "more than 10000000 bodies"},
        Bad{"sizes_not_summing", kHead + kCube + kInflow + "rate = 1.0\nsizes = [[0.01, 0.02, 0.5]]\n",
            "inflow[0].sizes: the mass fractions add up to 0.5"},
        Bad{"sizes_bad_row", kHead + kCube + kInflow + "rate = 1.0\nsizes = [[0.02, 0.01, 1.0]]\n",
            "0 < min_size <= max_size"},
        Bad{"shapes_and_shape", kHead + kCube + kInflow +
            "rate = 1.0\nshapes = [ { shape = { type = \"sphere\", radius = 0.01 }, fraction = 1.0 } ]\n",
            "give either 'shape' or 'shapes'"},
        Bad{"shapes_zero_fraction", kHead + kCube + R"([[generator]]
count = 10
shapes = [ { shape = { type = "sphere", radius = 0.01 }, fraction = 0.0 } ]
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [0.1, 0.1, 0.1] }
)",
            "generator[0].shapes[0].fraction: must be > 0"},
        Bad{"bad_fractions", kHead + kCube + kInflow + "rate = 1.0\nfractions = \"volume\"\nsizes = [[0.01, 0.02, 1.0]]\n",
            "inflow[0].fractions: must be \"number\" or \"mass\""},
        Bad{"periodic_empty", "[simulation]\nduration = 1.0\nperiodic = {}\n" + kNoSim + kCube,
            "simulation.periodic: needs at least one axis"},
        Bad{"periodic_reversed", "[simulation]\nduration = 1.0\nperiodic = { x = [1.0, 0.0] }\n" + kNoSim + kCube,
            "simulation.periodic.x: must be [min, max] with max > min"},
        Bad{"periodic_too_short", "[simulation]\nduration = 1.0\nperiodic = { x = [0.0, 0.05] }\n" + kNoSim + kCube,
            "it must exceed four times the largest body's reach"},
        Bad{"cell_rate_not_periodic", "[simulation]\nduration = 1.0\nperiodic = { x = [-0.1, 0.1], strain_rate = { xz = 1.0 } }\n" + kNoSim + kCube,
            "simulation.periodic.strain_rate.xz: the cell is not periodic on z"},
        Bad{"cell_both", "[simulation]\nduration = 1.0\n[simulation.periodic]\nx = [-0.1, 0.1]\ny = [-0.1, 0.1]\nz = [-0.1, 0.1]\nstrain_rate = { x = -0.1 }\nstress = { x = 1.0e4 }\nmax_strain_rate = 1.0\n" + kNoSim + kCube,
            "simulation.periodic.stress.x: a component takes either a strain rate or a stress, not both"},
        Bad{"cell_no_max_rate", "[simulation]\nduration = 1.0\n[simulation.periodic]\nx = [-0.1, 0.1]\ny = [-0.1, 0.1]\nz = [-0.1, 0.1]\nstress = { x = 1.0e4 }\n" + kNoSim + kCube,
            "simulation.periodic.stress: needs max_strain_rate too"},
        Bad{"cell_tension", "[simulation]\nduration = 1.0\n[simulation.periodic]\nx = [-0.1, 0.1]\ny = [-0.1, 0.1]\nz = [-0.1, 0.1]\nstress = { x = -1.0e4 }\nmax_strain_rate = 1.0\n" + kNoSim + kCube,
            "simulation.periodic.stress.x: must be > 0"},
        Bad{"cell_shear_only", "[simulation]\nduration = 1.0\n[simulation.periodic]\nx = [-0.1, 0.1]\ny = [-0.1, 0.1]\nz = [-0.1, 0.1]\nstress = { xz = 0.0 }\nmax_strain_rate = 1.0\n" + kNoSim + kCube,
            "simulation.periodic.stress: needs a normal stress"},
        Bad{"cell_stress_not_3d", "[simulation]\nduration = 1.0\nperiodic = { x = [-0.1, 0.1], stress = { x = 1.0e4 }, max_strain_rate = 1.0 }\n" + kNoSim + kCube,
            "simulation.periodic.stress: needs a cell periodic on x, y and z"},
        Bad{"cell_unknown_component", "[simulation]\nduration = 1.0\n[simulation.periodic]\nx = [-0.1, 0.1]\ny = [-0.1, 0.1]\nz = [-0.1, 0.1]\nstrain_rate = { zx = 1.0 }\n" + kNoSim + kCube,
            "simulation.periodic.strain_rate: unknown key 'zx'"},
        Bad{"cell_max_rate_alone", "[simulation]\nduration = 1.0\n[simulation.periodic]\nx = [-0.1, 0.1]\ny = [-0.1, 0.1]\nz = [-0.1, 0.1]\nmax_strain_rate = 1.0\n" + kNoSim + kCube,
            "simulation.periodic.max_strain_rate: bounds the servo"},
        Bad{"motion_nan", kHead + kCube + kPlane + "motion = { angular_velocity = [nan, 0.0, 0.0] }\n",
            "wall[0].motion.angular_velocity: must be finite"},
        // Issue 11: limits stated and checked before anything is drawn.
        Bad{"huge_variants", kHead + R"([[generator]]
count = 100
variants = 1000000000000
shape = { type = "random_polyhedron", vertices = 12, size = 0.01 }
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [1.0, 1.0, 1.0] }
)",
            "variants: must be a positive integer up to the count"},
        Bad{"huge_count", kHead + R"([[generator]]
count = 100000000
shape = { type = "platonic", name = "cube", size = 0.02 }
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [0.1, 0.1, 0.1] }
)",
            "count: must be a positive integer up to 10000000"},
        Bad{"huge_empty_region", kHead + R"([[wall]]
type = "plane"
point = [0.0, 0.0, 1000.0]
normal = [0.0, 0.0, 1.0]
material = "rock"
[[generator]]
count = 10
shape = { type = "platonic", name = "cube", size = 0.001 }
material = "rock"
region = { min = [0.0, 0.0, 0.0], max = [100.0, 100.0, 100.0] }
)",
            "found room for only 0 of the 10 bodies"},
        Bad{"mesh_is_a_folder", kHead + kCube + R"([[wall]]
type = "mesh"
file = "/tmp"
material = "rock"
)",
            "file: /tmp is not a regular file"},
        Bad{"name_with_comma", kHead + R"([[body]]
name = "a,b"
shape = { type = "box", half_extents = [0.01, 0.01, 0.01] }
material = "rock"
)",
            "body[0]: its name holds a comma"},
        Bad{"name_with_newline", kHead + "[[body]]\nname = \"a\\nb\"\nshape = { type = \"sphere\", radius = 0.01 }\n"
                                           "material = \"rock\"\n",
            "a quote or a control character"},
        Bad{"bonded_generator_with_variants", kHead + "bond_tensile_strength = 3e4\nbond_shear_strength = 3e4\n" +
                                                  kBondedGenerator + "variants = 4\n",
            "generator[0].variants: is not for a generator of bonded assemblies"},
        Bad{"bonded_generator_fixed", kHead + "bond_tensile_strength = 3e4\nbond_shear_strength = 3e4\n" +
                                          kBondedGenerator + "fixed = true\n",
            "generator[0].fixed: bonded assemblies move"},
        Bad{"bonded_generator_one_piece", kHead + "bond_tensile_strength = 3e4\nbond_shear_strength = 3e4\n" +
                                              bonded_generator(1),
            "generator[0].shape.pieces: must be given, between 2 and"},
        Bad{"bonded_generator_without_glue", kHead + kBondedGenerator, "has no glue"},
        Bad{"bonded_inflow", kHead + "bond_tensile_strength = 3e4\nbond_shear_strength = 3e4\n" +
                                 bonded_generator(6, "inflow", "rate = 100.0"),
            "\"bonded\" is the shape of a [[body]] or of a [[generator]]'s single `shape` only"}),
    [](const ::testing::TestParamInfo<Bad>& param_info) { return param_info.param.name; });

}  // namespace
// Issue 35: a cylindrical container without a mesh file. Its pieces'
// inner faces lie on the radius and the floor on the base; a region poking
// out of a closed one is warned of, as for a drum mesh.
// Named shapes ([shapes]): the moving bodies naming one share a template;
// generators, mixes and inflows take names too (a random_polyhedron named
// so is drawn by them, refused for a body); a surface may be given inline.
TEST(Scene, NamedShapesAreSharedAndInlineSurfacesRead) {
  const std::string shapes = R"(
[shapes]
cube = { type = "platonic", name = "cube", size = 0.01 }
rock = { type = "random_polyhedron", vertices = 8, size = [0.008, 0.01] }
tet = { type = "surface", vertices = [[0, 0, 0], [0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]], triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] }
)";
  std::string bodies;
  for (int k = 0; k < 3; ++k)
    bodies += "[[body]]\nshape = \"cube\"\nmaterial = \"rock\"\nposition = [" + std::to_string(0.03 * k) + ", 0, 0.02]\n";
  for (const char* x : {"0.5", "0.6"})
    bodies += "[[body]]\nshape = \"cube\"\nmaterial = \"rock\"\nfixed = true\nposition = [" + std::string(x) + ", 0, 0.02]\n";
  const std::string generator = R"(
[[generator]]
count = 6
shapes = [ { shape = "rock", fraction = 0.5 }, { shape = "cube", fraction = 0.5 } ]
material = "rock"
region = { min = [-0.05, -0.05, 0.1], max = [0.05, 0.05, 0.2] }
)";
  const Scene scene = load_scene(kHead + shapes + kPlane + bodies + generator, "test.toml", std::filesystem::temp_directory_path());
  const dem::World& w = scene.world;
  ASSERT_EQ(w.bodies.size(), 11u);
  EXPECT_EQ(w.bodies[0].shape, w.bodies[1].shape);
  EXPECT_EQ(w.bodies[1].shape, w.bodies[2].shape);
  EXPECT_NE(w.bodies[3].shape, w.bodies[0].shape) << "fixed bodies take a (wall) template of their own";
  EXPECT_EQ(w.bodies[3].shape, w.bodies[4].shape) << "and share it";
  const Real cube_volume = std::pow(0.01 / std::sqrt(3.0), 3);  // inscribed in a sphere of 0.01
  EXPECT_NEAR(w.templates[w.bodies[0].shape].unit_mass.volume, cube_volume, 1e-12 * cube_volume);

  const Scene tets = load_scene(kHead + shapes + kPlane + "[[body]]\nshape = \"tet\"\nmaterial = \"rock\"\n"
                                "position = [0, 0, 0.02]\n", "test.toml", std::filesystem::temp_directory_path());
  EXPECT_TRUE(tets.world.templates[tets.world.bodies[0].shape].surface_grain);
  EXPECT_NEAR(tets.world.templates[tets.world.bodies[0].shape].unit_mass.volume, 1e-6 / 6, 1e-18);

  EXPECT_NE(refusal(kHead + shapes + "[[body]]\nshape = \"pebble\"\nmaterial = \"rock\"\n")
                .find("body[0].shape: names no shape of the [shapes] table ('pebble')"),
            std::string::npos);
  EXPECT_NE(refusal(kHead + shapes + "[[body]]\nshape = \"rock\"\nmaterial = \"rock\"\n").find("random_polyhedron"),
            std::string::npos);
  EXPECT_NE(refusal(kHead + "[shapes]\nbad = { type = \"surface\", vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "
                            "triangles = [[0, 1, 3]] }\n" + kCube)
                .find("shapes.bad.triangles: must hold indices of vertices"),
            std::string::npos);
  EXPECT_NE(refusal(kHead + "[shapes]\nopen = { type = \"surface\", vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "
                            "triangles = [[0, 1, 2]] }\n" + kCube)
                .find("not a closed surface"),
            std::string::npos);
  EXPECT_NE(refusal(kHead + "[shapes]\nbad = 3\n" + kCube).find("shapes.bad: must be a SHAPE table"), std::string::npos);
}

TEST(Scene, ACylinderWallIsAMeshOfFlatsWhoseInnerFacesLieOnItsRadius) {
  const std::string wall = R"(
[[wall]]
type = "cylinder"
base = [1.0, 2.0, 3.0]
axis = [0.0, 1.0, 0.0]
radius = 0.05
height = 0.2
top = true
segments = 12
thickness = 0.004
material = "rock"

[[body]]
shape = { type = "sphere", radius = 0.005 }
material = "rock"
position = [1.0, 2.1, 3.0]
)";
  const Scene s = load_scene(kHead + wall, "cylinder", ".");
  ASSERT_EQ(s.world.bodies.size(), 12u * 2 + 12 + 12 + 1);  // sides, floor and roof fans, the ball
  // Every side piece's middle is half a thickness behind the inner face at
  // the radius: its centre lies at (radius + t/2) from the axis (the middle
  // of a flat's triangle is nearer than the corners).
  const Vec3 base{1, 2, 3}, axis{0, 1, 0};
  int sides = 0;
  for (const dem::Body& b : s.world.bodies) {
    if (!b.fixed) continue;
    const Vec3 rel = b.position - base;
    const Real along = dot(rel, axis), across = length(rel - axis * along);
    if (std::fabs(along + 0.002) < 1e-12 || std::fabs(along - 0.202) < 1e-12) {  // a cap's fan, t/2 beyond the end
      EXPECT_LT(across, 0.052 / std::cos(kPi / 12)) << along;
      continue;
    }
    EXPECT_TRUE(along > 0 && along < 0.2) << along;
    ++sides;
    EXPECT_GT(across, 0.052 - 1e-12);
    EXPECT_LT(across, 0.052 / std::cos(kPi / 12) + 1e-12);
  }
  EXPECT_EQ(sides, 24);
  const Scene poking = load_scene(kHead + wall + R"(
[[generator]]
count = 40
shape = { type = "sphere", radius = 0.005 }
material = "rock"
region = { min = [0.94, 2.02, 2.97], max = [1.06, 2.18, 3.03] }
)",
                                  "cylinder", ".");
  ASSERT_FALSE(poking.warnings.empty());
  EXPECT_NE(poking.warnings[0].find("wall[0] (cylinder)"), std::string::npos) << poking.warnings[0];
  for (const auto& [key, text] : {std::pair{"radius", "radius = 0.05\n"}, std::pair{"segments", "segments = 12\n"}}) {
    std::string bad = kHead + wall;
    bad.replace(bad.find(text), std::string(text).size(), key == std::string("radius") ? "" : "segments = 4\n");
    try {
      load_scene(bad, "cylinder", ".");
      ADD_FAILURE() << "a cylinder without a good " << key << " was read";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

// Issue 35: generators fill cylinders and spheres; each body's bounding
// ball lies inside. Inflows keep to boxes, and say so.
TEST(Scene, GeneratorsFillCylindersAndSpheres) {
  const auto filled = [](const std::string& region, int count) {
    return load_scene(kHead + R"(
[[generator]]
count = )" + std::to_string(count) + R"(
shape = { type = "sphere", radius = 0.004 }
material = "rock"
region = )" + region + "\n",
                      "regions", ".");
  };
  const Scene cylinder = filled(R"({ type = "cylinder", base = [0.1, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = 0.03, height = 0.1 })", 120);
  ASSERT_EQ(cylinder.world.bodies.size(), 120u);
  for (const dem::Body& b : cylinder.world.bodies) {
    const Vec3 rel = b.position - Vec3{0.1, 0, 0};
    EXPECT_GE(rel.x, 0.004 - 1e-12);
    EXPECT_LE(rel.x, 0.1 - 0.004 + 1e-12);
    EXPECT_LE(std::hypot(rel.y, rel.z) + 0.004, 0.03 + 1e-12);
  }
  const Scene ball = filled(R"({ type = "sphere", centre = [0.0, 0.0, 0.5], radius = 0.03 })", 60);
  ASSERT_EQ(ball.world.bodies.size(), 60u);
  for (const dem::Body& b : ball.world.bodies) EXPECT_LE(length(b.position - Vec3{0, 0, 0.5}) + 0.004, 0.03 + 1e-12);
  for (const auto& [region, expected] :
       {std::pair{R"({ type = "cone", radius = 0.03 })", "must be \"box\", \"cylinder\" or \"sphere\""},
        std::pair{R"({ type = "sphere", radius = 0.03 })", "needs 'centre'"},
        std::pair{R"({ type = "cylinder", radius = 0.03, height = 0.1, min = [0.0, 0.0, 0.0] })", "min"},
        std::pair{R"({ type = "sphere", centre = [0.0, 0.0, 0.0], radius = 0.005 })", "holds only"}}) {
    try {
      filled(region, 10);
      ADD_FAILURE() << region << " was read";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  // An inflow takes a disc (a cylinder of height 0), a cylinder or a ball;
  // a generator's cylinder must have a height.
  const auto inflow = [](const std::string& region) {
    return load_scene(kHead + "[[inflow]]\nrate = 100.0\ncount = 20\nshape = { type = \"sphere\", radius = 0.004 }\n"
                      "material = \"rock\"\nregion = " + region + "\n",
                      "regions", ".");
  };
  const Scene disc = inflow(R"({ type = "cylinder", base = [0.0, 0.0, 0.5], radius = 0.03, height = 0 })");
  ASSERT_TRUE(disc.world.inflows[0].round.has_value());
  EXPECT_EQ(disc.world.inflows[0].round->height, 0);
  EXPECT_NE(disc.resolved_json.find("\"cylinder\""), std::string::npos);
  const Scene ball_inflow = inflow(R"({ type = "sphere", centre = [0.0, 0.0, 0.5], radius = 0.02 })");
  EXPECT_EQ(ball_inflow.world.inflows[0].round->kind, dem::RoundRegion::Kind::Ball);
  EXPECT_EQ(ball_inflow.world.inflows[0].lo.z, 0.48) << "its bounding box";
  for (const auto& [region, expected] :
       {std::pair{R"({ type = "cylinder", radius = 0.03, height = -0.1 })", "height: must be >= 0"},
        std::pair{R"({ type = "cone", radius = 0.03 })", "must be \"box\", \"cylinder\" or \"sphere\""}}) {
    try {
      inflow(region);
      ADD_FAILURE() << region << " was read";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  try {
    filled(R"({ type = "cylinder", radius = 0.03, height = 0 })", 10);
    ADD_FAILURE() << "a generator took a flat cylinder";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("height: must be > 0"), std::string::npos) << e.what();
  }
}

TEST(Scene, ADeformingPeriodicCellIsRead) {
  const Scene s = load_scene("[simulation]\nduration = 1.0\ngravity = [0.0, 0.0, 0.0]\n[simulation.periodic]\n"
                             "x = [-0.1, 0.1]\ny = [-0.1, 0.1]\nz = [-0.1, 0.1]\nstrain_rate = { xz = 2.0 }\n"
                             "stress = { x = 1.0e4, y = 2.0e4, z = 3.0e4, xy = 0.0 }\nmax_strain_rate = 0.5\n" +
                                 kNoSim + kCube,
                             "cell", ".");
  const dem::CellControl& c = s.world.settings.cell_control;
  EXPECT_EQ(c.mode[dem::kXZ], dem::CellMode::StrainRate);
  EXPECT_EQ(c.value[dem::kXZ], 2.0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(c.mode[k], dem::CellMode::Stress);
  EXPECT_EQ(c.value[2], 3e4);
  EXPECT_EQ(c.mode[dem::kXY], dem::CellMode::Stress);
  EXPECT_EQ(c.mode[dem::kYZ], dem::CellMode::Fixed);
  EXPECT_EQ(c.max_strain_rate, 0.5);
  EXPECT_EQ(s.world.cell.now.hi.x, 0.1);
}

}  // namespace gjkdem::io
