#include "gjkdem/io/mesh.hpp"

#include "gjkdem/shape/surface.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace gjkdem::io {
namespace {

namespace fs = std::filesystem;

class MeshTest : public ::testing::Test {
 protected:
  // One folder per test and process: ctest runs the tests side by side, and
  // one test's TearDown must not remove another's files.
  fs::path dir = fs::temp_directory_path() /
                 ("gjkdem_mesh_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                  "_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::string error_of(const fs::path& p) {
    try {
      convex_from_mesh(read_mesh(p), p.string());
    } catch (const MeshError& e) {
      return e.what();
    }
    return "";
  }
};

const char* kCubeObj = R"(# unit cube, outward faces
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

TEST_F(MeshTest, ConvexObjIsKeptWithoutWarning) {
  const ConvexMesh m = convex_from_mesh(read_mesh(write("cube.obj", kCubeObj)), "cube.obj");
  EXPECT_TRUE(m.watertight);
  EXPECT_TRUE(m.convex);
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_NEAR(m.polytope.data->volume, 1.0, 1e-14);
  EXPECT_EQ(m.polytope.data->vertices.size(), 8u);
}

// The winding number tells inside from outside a closed mesh wherever the
// point is, on the lines through its edges and vertices too.
TEST_F(MeshTest, TheWindingNumberIsOneInsideAClosedMeshAndZeroOutside) {
  TriangleMesh cube = read_mesh(write("cube.obj", kCubeObj));
  EXPECT_TRUE(is_watertight(cube));
  for (const Vec3& p : {Vec3{0.5, 0.5, 0.5}, Vec3{0.01, 0.99, 0.02}, Vec3{0.999, 0.5, 0.001}})
    EXPECT_NEAR(winding_number(cube, p), 1.0, 1e-9) << p.x << " " << p.y << " " << p.z;
  // Outside, among them points on the lines of an edge, of a face diagonal and of a vertex.
  for (const Vec3& p : {Vec3{1.5, 0.5, 0.5}, Vec3{2, 0, 0}, Vec3{2, 2, 0}, Vec3{2, 2, 2}, Vec3{-0.001, 0.5, 0.5}})
    EXPECT_NEAR(winding_number(cube, p), 0.0, 1e-9) << p.x << " " << p.y << " " << p.z;
  // Faces turned inward wind the other way; an open mesh is not watertight.
  TriangleMesh inward = cube;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(winding_number(inward, {0.5, 0.5, 0.5}), -1.0, 1e-9);
  std::string open = kCubeObj;
  open.erase(open.rfind("f 4 1 5 8"));
  EXPECT_FALSE(is_watertight(read_mesh(write("open.obj", open))));
}

TEST_F(MeshTest, OpenAndNonConvexMeshesBecomeTheirHullWithAWarning) {
  std::string open = kCubeObj;
  open.erase(open.rfind("f 4 1 5 8"));  // drop one face: not watertight
  const ConvexMesh o = convex_from_mesh(read_mesh(write("open.obj", open)), "open.obj");
  EXPECT_FALSE(o.watertight);
  ASSERT_EQ(o.warnings.size(), 1u);
  EXPECT_NE(o.warnings[0].find("open.obj: the mesh is not watertight"), std::string::npos);
  // A cube with its top centre pushed down: watertight, not convex.
  const std::string dent = std::string(kCubeObj).replace(std::string(kCubeObj).find("f 5 6 7 8"), 9,
                                                         "v 0.5 0.5 0.5\nf 5 6 9\nf 6 7 9\nf 7 8 9\nf 8 5 9");
  const ConvexMesh d = convex_from_mesh(read_mesh(write("dent.obj", dent)), "dent.obj");
  EXPECT_TRUE(d.watertight);
  EXPECT_FALSE(d.convex);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("not convex"), std::string::npos);
  EXPECT_NEAR(d.polytope.data->volume, 1.0, 1e-14);
}

TEST_F(MeshTest, StlAsciiAndBinaryAgree) {
  const std::string ascii = R"(solid tet
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 0 1
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 1
  vertex 0 1 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 1 0 0
  vertex 0 1 0
  vertex 0 0 1
 endloop
endfacet
endsolid tet
)";
  const TriangleMesh a = read_mesh(write("tet.stl", ascii));
  EXPECT_EQ(a.vertices.size(), 4u);  // corners welded
  std::string bin(80, ' ');
  const std::uint32_t count = 4;
  bin.append(reinterpret_cast<const char*>(&count), 4);
  const float tris[4][3][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
                               {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (const auto& t : tris) {
    bin.append(12, '\0');  // normal
    bin.append(reinterpret_cast<const char*>(t), 36);
    bin.append(2, '\0');   // attribute
  }
  const ConvexMesh b = convex_from_mesh(read_mesh(write("tet_bin.STL", bin)), "tet_bin.STL");
  EXPECT_TRUE(b.convex);
  EXPECT_NEAR(b.polytope.data->volume, 1.0 / 6, 1e-15);
}

TEST_F(MeshTest, BadFilesAreRefusedWithTheirNameAndProblem) {
  EXPECT_NE(error_of(dir / "missing.obj").find("missing.obj: cannot open"), std::string::npos);
  EXPECT_NE(error_of(write("empty.obj", "# nothing\n")).find("empty.obj: the mesh has no triangles"), std::string::npos);
  EXPECT_NE(error_of(write("nan.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).find("nan.obj: line 1: coordinate is not finite"),
            std::string::npos);
  EXPECT_NE(error_of(write("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")).find("flat.obj: the mesh is flat"),
            std::string::npos);
  EXPECT_NE(error_of(write("range.obj", "v 0 0 0\nf 1 2 3\n")).find("range.obj: line 2: face index 2 out of range"),
            std::string::npos);
  EXPECT_NE(error_of(write("shape.ply", "ply\n")).find("unknown mesh format '.ply'"), std::string::npos);
  EXPECT_NE(error_of(write("short.stl", "abc")).find("short.stl: binary STL shorter"), std::string::npos);
  EXPECT_NE(error_of(write("bad.stl", "solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0\n")).find("bad.stl: line 4"),
            std::string::npos);
}

// Issue 11: face indices that are not integers were read as their integer
// part; a directory, a FIFO or /dev/zero named as a mesh hung or read until
// memory ran out; a symlink loop gave no file name.
TEST_F(MeshTest, NotIntegersAndNotFilesAreRefused) {
  EXPECT_NE(error_of(write("frac.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1.9 2 3\n")).find("bad face index '1.9'"),
            std::string::npos);
  EXPECT_NE(error_of(write("junk.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2x 3\n")).find("bad face index '2x'"),
            std::string::npos);
  fs::create_directories(dir / "folder.stl");
  EXPECT_NE(error_of(dir / "folder.stl").find("is not a regular file"), std::string::npos);
  const fs::path fifo = dir / "pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_of(fifo).find("is not a regular file"), std::string::npos);  // returns at once, no reader needed
  fs::create_symlink(dir / "zero.stl", dir / "zero.stl.link");
  fs::create_symlink("/dev/zero", dir / "zero.stl");
  EXPECT_NE(error_of(dir / "zero.stl").find("is not a regular file"), std::string::npos);
  fs::create_symlink(dir / "loop_b.obj", dir / "loop_a.obj");
  fs::create_symlink(dir / "loop_a.obj", dir / "loop_b.obj");
  EXPECT_NE(error_of(dir / "loop_a.obj").find("loop_a.obj: cannot open"), std::string::npos);
}

// Issue 54, point 9: a non-convex polygon face was fanned from its first
// corner, over its notch: a phantom triangle a ball rested on, and a surface
// grain refused naming triangles not in the file. Now every polygon is cut
// inside itself: L-prisms whose caps start at each of their six corners (so
// that some fans would cross the notch) bound the L's solid, volume 3, with
// the notch empty; convex polygons keep their fan; a polygon that crosses
// itself (a bow tie, a pentagram) or has no area is fanned as before (a
// convex particle takes the hull) and refused, naming its line, where the
// triangles are taken as they are (surfaces, shells, mesh walls).
TEST_F(MeshTest, PolygonFacesAreCutInsideThemselvesOrRefusedByLine) {
  const Real l[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // counter-clockwise from +z
  for (int start = 0; start < 6; ++start) {
    std::ostringstream obj;
    for (int z = 0; z < 2; ++z)
      for (const auto& c : l) obj << "v " << c[0] << " " << c[1] << " " << z << "\n";
    obj << "f";
    for (int k = 0; k < 6; ++k) obj << " " << 1 + (start + 6 - k) % 6;
    obj << "\nf";
    for (int k = 0; k < 6; ++k) obj << " " << 7 + (start + k) % 6;
    obj << "\n";
    for (int k = 0; k < 6; ++k) {
      const int i = k + 1, j = (k + 1) % 6 + 1;
      obj << "f " << i << " " << j << " " << j + 6 << " " << i + 6 << "\n";
    }
    const TriangleMesh mesh = read_mesh(write(std::string("l") += std::to_string(start) += ".obj", obj.str()));
    ASSERT_EQ(mesh.triangles.size(), 2u * 4 + 6 * 2) << start;
    const Surface surface = make_surface(mesh.vertices, mesh.triangles);
    EXPECT_NEAR(surface.volume, 3, 1e-12) << start;
    EXPECT_NEAR(winding_number(mesh, {1.5, 1.5, 0.5}), 0, 1e-9) << start;  // the notch
    EXPECT_NEAR(winding_number(mesh, {0.5, 1.5, 0.5}), 1, 1e-9) << start;
  }
  const TriangleMesh quad = read_mesh(write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  ASSERT_EQ(quad.triangles.size(), 2u);
  EXPECT_EQ(quad.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(quad.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  // Faces that cannot be cut: kept as a fan (a convex hull does not mind),
  // the problem said for the readers that take the triangles as they are.
  const auto uncut = [&](const std::string& name, const std::string& text) {
    const TriangleMesh m = read_mesh(write(name, text));
    EXPECT_EQ(error_of(dir / name), "") << name;  // as a convex particle: its hull
    try {
      refuse_uncut_polygons(m);
    } catch (const MeshError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(uncut("bowtie.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 1 0\nv 0 0 1\n# crossing\nf 1 2 3 4\nf 1 2 5\n")
                .find("bowtie.obj: line 7: the face's polygon crosses itself"),
            std::string::npos);
  std::ostringstream star;
  for (int k = 0; k < 5; ++k) star << "v " << std::cos(4 * kPi * k / 5) << " " << std::sin(4 * kPi * k / 5) << " 0\n";
  EXPECT_NE(uncut("star.obj", star.str() + "v 0 0 1\nf 1 2 3 4 5\nf 1 2 6\n").find("star.obj: line 7: the face's polygon crosses itself"),
            std::string::npos);
  EXPECT_NE(uncut("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nv 0 1 1\nv 0 0 2\nf 1 2 3 4\nf 1 5 6\n").find("line 7: the face's polygon has no area"),
            std::string::npos);
  EXPECT_EQ(uncut("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1 2 5\n"), "");
}

}  // namespace
}  // namespace gjkdem::io
