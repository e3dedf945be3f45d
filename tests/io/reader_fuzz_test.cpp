// Fuzzing the readers (issue 11): mutated and generated inputs thrown at the
// scene reader, the mesh readers and the checkpoint reader must each give an
// answer or the reader's own error, never a crash, a hang, another exception
// (bad_optional_access, bad_alloc, out_of_range) or an unbounded allocation.
// Seeds are fixed; each test runs in seconds.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/io/mesh.hpp"
#include "gjkdem/io/scene.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::io {
namespace {

// Text pieces a mutation may splice in: numbers at the edges of the double
// range, TOML punctuation, keys, and bytes that are not text.
const std::vector<std::string> kPieces = {
    "0", "-1", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "9223372036854775807", "9007199254740993", "1.9",
    "[", "]", "{", "}", "=", "\"", ",", ".", "#", "\n", "[[body]]", "[[wall]]", "[[generator]]", "[simulation]",
    "count = ", "variants = ", "size = ", "normal = [0.0, 0.0, 0.0]", "type = \"mesh\"", "type = \"sphere\"",
    "file = \"/dev/zero\"", "file = \".\"", std::string("\0", 1), "\xff\xfe", "1e10", "100000"};

const std::vector<std::string> kNumbers = {"0", "-1", "1e308", "-1e308", "1e-320", "9223372036854775807",
                                           "9007199254740993", "1e10", "100000", "0.0", "-0.0", "1e-9", "3", "2.5"};

std::string mutate(std::string text, std::mt19937_64& rng) {
  const int edits = 1 + static_cast<int>(rng() % 2);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    const std::size_t at = rng() % text.size();
    switch (rng() % 7) {
      case 5:
      case 6: {  // a number replaced by another (the scene stays well formed)
        const std::size_t begin = text.find_first_of("0123456789", at);
        if (begin == std::string::npos) break;
        const std::size_t end = text.find_first_not_of("0123456789.e-+", begin);
        text.replace(begin, (end == std::string::npos ? text.size() : end) - begin, kNumbers[rng() % kNumbers.size()]);
        break;
      }
      case 0:  // flip a byte
        text[at] = static_cast<char>(rng() % 256);
        break;
      case 1:  // delete a run
        text.erase(at, 1 + rng() % 12);
        break;
      case 2:  // splice in a piece
        text.insert(at, kPieces[rng() % kPieces.size()]);
        break;
      case 3:  // duplicate a line
      {
        const std::size_t begin = text.rfind('\n', at), end = text.find('\n', at);
        const std::size_t b = begin == std::string::npos ? 0 : begin + 1;
        text.insert(b, text.substr(b, (end == std::string::npos ? text.size() : end + 1) - b));
        break;
      }
      default:  // cut the text short
        text.resize(at);
    }
  }
  return text;
}

const std::string kScene = R"(# a small scene using most keys
[simulation]
duration = 0.1
dt = "auto"
gravity = [0.0, 0.0, -9.81]
seed = 4
guards = "warn"

[output]
dir = "out"
every = 0.01

[contact]
model = "volume"
tessellation = 24

[[material]]
name = "rock"
density = 2500.0
youngs_modulus = 1.0e7
restitution = 0.5
friction = 0.4

[[wall]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "rock"

[[wall]]
type = "box"
min = [-0.1, -0.1, 0.0]
max = [0.1, 0.1, 0.2]
open_top = true
material = "rock"

[[body]]
name = "ball"
shape = { type = "sphere", radius = 0.01 }
material = "rock"
position = [0.0, 0.0, 0.15]
velocity = [0.0, 0.0, -1.0]

[[body]]
shape = { type = "polytope", vertices = [[0.0, 0.0, 0.0], [0.02, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.02]] }
material = "rock"
position = [0.05, 0.05, 0.15]

[[generator]]
count = 12
variants = 3
shape = { type = "random_polyhedron", vertices = 8, size = [0.01, 0.02] }
material = "rock"
region = { min = [-0.09, -0.09, 0.01], max = [0.09, 0.09, 0.1] }
)";

TEST(ReaderFuzz, ScenesAreReadOrRefusedWithASceneError) {
  std::mt19937_64 rng(2026);
  int accepted = 0, refused = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int trial = 0; trial < 1500; ++trial) {
    const std::string text = mutate(kScene, rng);
    try {
      const Scene s = load_scene(text, "fuzz.toml", std::filesystem::temp_directory_path());
      ++accepted;
      // What was accepted can also be planned, or is refused with the range.
      try {
        dem::plan_run(s.duration, s.dt, s.output_every);
      } catch (const std::invalid_argument&) {
      }
    } catch (const SceneError&) {
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "trial " << trial << ": " << typeid(e).name() << ": " << e.what() << "\n" << text;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("scenes: %d accepted, %d refused in %.1f s\n", accepted, refused, seconds);
  EXPECT_GT(accepted, 150);  // the mutations are not all fatal: the reader is exercised past the syntax
  EXPECT_GT(refused, 300);
}

const std::string kObj = "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const std::string kStlAscii =
    "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
    "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
    "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
    "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid t\n";

std::string binary_stl() {
  std::string b(80, ' ');
  const std::uint32_t n = 4;
  b.append(reinterpret_cast<const char*>(&n), 4);
  const float tris[4][9] = {{0, 0, 0, 0, 1, 0, 1, 0, 0}, {0, 0, 0, 1, 0, 0, 0, 0, 1}, {0, 0, 0, 0, 0, 1, 0, 1, 0},
                            {1, 0, 0, 0, 1, 0, 0, 0, 1}};
  for (const auto& t : tris) {
    const float normal[3] = {0, 0, 0};
    b.append(reinterpret_cast<const char*>(normal), 12);
    b.append(reinterpret_cast<const char*>(t), 36);
    b.append(2, '\0');
  }
  return b;
}

TEST(ReaderFuzz, MeshesAreReadOrRefusedWithAMeshError) {
  std::mt19937_64 rng(7);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gjkdem_mesh_fuzz";
  std::filesystem::create_directories(dir);
  int accepted = 0, refused = 0;
  const std::pair<std::string, std::string> bases[] = {{"m.obj", kObj}, {"m.stl", kStlAscii}, {"b.stl", binary_stl()}};
  for (int trial = 0; trial < 900; ++trial) {
    const auto& [name, base] = bases[trial % 3];
    const std::filesystem::path file = dir / name;
    std::ofstream(file, std::ios::binary | std::ios::trunc) << mutate(base, rng);
    try {
      const TriangleMesh m = read_mesh(file);
      convex_from_mesh(m, name);
      ++accepted;
    } catch (const MeshError&) {
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "trial " << trial << " (" << name << "): " << e.what();
    }
  }
  // Not files: a directory named like a mesh, a device, a missing file.
  std::filesystem::create_directories(dir / "x.stl");
  for (const std::filesystem::path& p : {dir / "x.stl", std::filesystem::path("/dev/zero.stl"), dir / "none.obj"})
    EXPECT_THROW(read_mesh(p), MeshError) << p;
  std::filesystem::remove_all(dir);
  std::printf("meshes: %d accepted, %d refused\n", accepted, refused);
  EXPECT_GT(accepted, 50);
  EXPECT_GT(refused, 100);
}

TEST(ReaderFuzz, CheckpointsAreRestoredOrRefusedWithACheckpointError) {
  dem::WorldBuilder b;
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e6, 0.25, 0.4, 0.5});
  b.add_plane({}, {0, 0, 1}, rock, "floor");
  std::mt19937_64 rng(3);
  dem::RegionFill fill;
  fill.variants = {{random_polyhedron(8, 0.015, rng), {}}};
  fill.count = 20;
  fill.lo = {-0.03, -0.03, 0};
  fill.hi = {0.03, 0.03, 0.1};
  fill.material = rock;
  b.fill_region(fill, rng);
  const dem::World built = b.build();
  dem::World w = built;
  dem::RunState run = dem::plan_run(0.02, 1e-4, 0.01);
  dem::run(w, run, {});
  const std::string good = encode_checkpoint(w, {run, {1, 2, 0, 3, {{"frame_000000.vtk", 0.0}}}}, 9);
  int refused = 0, unchecked = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    std::string bad = good;
    // Bytes changed anywhere; half the time the checksum is made to match,
    // so that the section parser itself meets the damage.
    for (int k = 1 + static_cast<int>(rng() % 4); k > 0; --k) bad[rng() % bad.size()] = static_cast<char>(rng());
    if (trial % 2 == 0 && bad.size() > 40) {
      const std::uint64_t sum = fnv1a64(std::string_view(bad).substr(40));
      for (int k = 0; k < 8; ++k) bad[24 + k] = static_cast<char>(sum >> (8 * k));
      for (int k = 0; k < 8; ++k) bad[16 + k] = static_cast<char>(static_cast<std::uint64_t>(bad.size() - 40) >> (8 * k));
    }
    dem::World target = built;
    try {
      decode_checkpoint(bad, target, 9, "fuzz");
      // Accepted: only with a checksum made to match (changed reals, say), or no change at all.
      EXPECT_TRUE(trial % 2 == 0 || bad == good) << "trial " << trial << ": damage accepted";
      ++unchecked;
    } catch (const CheckpointError&) {
      ++refused;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "trial " << trial << ": " << e.what();
    }
  }
  std::printf("checkpoints: %d refused, %d accepted\n", refused, unchecked);
  EXPECT_GT(refused, 750);
}

}  // namespace
}  // namespace gjkdem::io
