// Walls through the engine: a sphere settling on a plane wall and on a mesh
// wall of two coplanar triangles, right above their shared edge. Merged by
// clustering, the two triangle contacts act as one: the sphere sinks as deep
// as on the plane (Hertz: m g = 4/3 E* sqrt(R) d^1.5), not 2^(2/3) less.
#include <gtest/gtest.h>

#include <cmath>

#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kRadius = 0.01, kRho = 0.001;

// A sphere above the floor, and the floor made by `add_floor`.
template <class AddFloor>
World sphere_world(AddFloor add_floor) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder builder(settings);
  const std::uint32_t rubber = builder.add_material({"rubber", 1000, 1e7, 0.3, 0.2, 0.5});
  builder.add_body({.shape = {make_sphere(kRadius), {}}, .material = rubber,
                    .position = {0, 0, kRadius + kRho + 1e-4}, .label = "sphere"});
  add_floor(builder, rubber);
  return builder.build();
}

Real settle(World& w) {
  for (int i = 0; i < 20000; ++i) step(w, 1e-5);
  EXPECT_LT(length(w.bodies[0].velocity), 1e-4);
  return w.bodies[0].position.z;
}

TEST(Walls, MeshTrianglesActAsOneContactLikeAPlane) {
  World plane = sphere_world([](WorldBuilder& b, std::uint32_t m) { b.add_plane({0, 0, kRho}, {0, 0, 1}, m, "floor"); });
  const Real z_plane = settle(plane);

  // Square [-0.05, 0.05]^2 split along its diagonal through the origin, the
  // triangles thickened by kRho on each side (top surface at z = kRho).
  World mesh = sphere_world([](WorldBuilder& b, std::uint32_t m) {
    const Vec3 c[4] = {{-0.05, -0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0}, {-0.05, 0.05, 0}};
    const std::array<std::uint32_t, 3> tris[2] = {{0, 1, 2}, {0, 2, 3}};
    b.add_mesh_walls(c, tris, 2 * kRho, m, "square");
  });
  const Real z_mesh = settle(mesh);
  EXPECT_EQ(mesh.stats.contacts, 1);

  const Real m = 1000 * 4.0 / 3 * kPi * std::pow(kRadius, 3);
  const Real e_pair = 1 / (2 * (1 - 0.09) / 1e7);  // the walls share the sphere's material
  const Real depth = std::pow(m * 9.81 / (4.0 / 3 * e_pair * std::sqrt(kRadius)), 2.0 / 3);
  EXPECT_NEAR(kRadius + kRho - z_plane, depth, 0.01 * depth);
  EXPECT_NEAR(z_mesh, z_plane, 0.01 * depth);
}

// A mesh wall's triangles pass the one index rule of every mesh
// (triangle_index_problem): an index out of range or a vertex named twice
// is refused naming the triangle; a triangle of three distinct collinear
// corners holds nothing and is left out.
TEST(Walls, MeshTrianglesAreCheckedByTheOneIndexRule) {
  const Vec3 c[4] = {{-0.05, -0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0}, {0, 0, 0}};
  const auto refusal = [&](std::array<std::uint32_t, 3> bad) -> std::string {
    WorldBuilder b;
    const std::uint32_t m = b.add_material({"rubber", 1000, 1e7, 0.3, 0.2, 0.5});
    const std::array<std::uint32_t, 3> tris[2] = {{0, 1, 2}, bad};
    try {
      b.add_mesh_walls(c, tris, 2 * kRho, m, "square");
    } catch (const BuildError& e) {
      return e.what();
    }
    return "(accepted, " + std::to_string(b.build().bodies.size()) + " pieces)";
  };
  EXPECT_EQ(refusal({0, 2, 4}), "square: triangle 1 refers to vertex 4 but there are 4 vertices");
  EXPECT_EQ(refusal({0, 0, 0}), "square: triangle 1 repeats a vertex (0, 0, 0)");
  EXPECT_EQ(refusal({2, 1, 2}), "square: triangle 1 repeats a vertex (2, 1, 2)");
  EXPECT_EQ(refusal({0, 3, 2}), "(accepted, 1 pieces)") << "collinear corners: no piece";
}

}  // namespace
}  // namespace gjkdem::dem
