// Walls through the engine: a sphere settling on a plane wall and on a mesh
// wall of two coplanar triangles, right above their shared edge. Merged by
// clustering, the two triangle contacts act as one: the sphere sinks as deep
// as on the plane (Hertz: m g = 4/3 E* sqrt(R) d^1.5), not 2^(2/3) less.
#include <gtest/gtest.h>

#include <cmath>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kRadius = 0.01, kRho = 0.001;

World sphere_world() {
  World w;
  w.model = ContactModel::Hertz;
  w.materials.push_back({"rubber", 1000, 1e7, 0.3, 0.2, 0.5});
  w.templates.push_back(make_template(make_sphere(kRadius)));
  Body b;
  b.id = 0;
  b.position = {0, 0, kRadius + kRho + 1e-4};
  w.bodies.push_back(b);
  return w;
}

Real settle(World& w) {
  for (int i = 0; i < 20000; ++i) step(w, 1e-5);
  EXPECT_LT(length(w.bodies[0].velocity), 1e-4);
  return w.bodies[0].position.z;
}

TEST(Walls, MeshTrianglesActAsOneContactLikeAPlane) {
  World plane = sphere_world();
  plane.planes.push_back({1000, {0, 0, kRho}, {0, 0, 1}, 0});
  const Real z_plane = settle(plane);

  World mesh = sphere_world();
  // Square [-0.05, 0.05]^2 split along its diagonal through the origin, the
  // triangles thickened by kRho on each side (top surface at z = kRho).
  const Vec3 c[4] = {{-0.05, -0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0}, {-0.05, 0.05, 0}};
  const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& t : tris) {
    const Vec3 centre = (c[t[0]] + c[t[1]] + c[t[2]]) / 3.0;
    mesh.templates.push_back(make_wall_template(Shape{Triangle{{c[t[0]] - centre, c[t[1]] - centre, c[t[2]] - centre}}, kRho}));
    Body piece;
    piece.id = mesh.bodies.size();
    piece.shape = static_cast<std::uint32_t>(mesh.templates.size() - 1);
    piece.fixed = true;
    piece.group = 1;
    piece.position = centre;
    mesh.bodies.push_back(piece);
  }
  const Real z_mesh = settle(mesh);
  EXPECT_EQ(mesh.last_contacts, 1);

  const Real m = 1000 * 4.0 / 3 * 3.14159265358979323846 * std::pow(kRadius, 3);
  const Real e_pair = 1 / (2 * (1 - 0.09) / 1e7);  // the walls share the sphere's material
  const Real depth = std::pow(m * 9.81 / (4.0 / 3 * e_pair * std::sqrt(kRadius)), 2.0 / 3);
  EXPECT_NEAR(kRadius + kRho - z_plane, depth, 0.01 * depth);
  EXPECT_NEAR(z_mesh, z_plane, 0.01 * depth);
}

}  // namespace
}  // namespace gjkdem::dem
