// split_body (dem/split_body.hpp): a spinning, moving polyhedron cut by a
// plane through it gives two fragments that keep, to round-off, its mass
// (1e-12 relative), linear momentum, angular momentum about any point and
// kinetic energy (the issue 31's first validation), and that fill exactly
// the space the parent filled (every point of it lies in one fragment).
#include "gjkdem/dem/split_body.hpp"

#include <gtest/gtest.h>

#include <random>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

Real kinetic(Real mass, const Vec3& v, const Quat& r, const Vec3& moments, const Vec3& l) {
  const Vec3 local = rotate(conjugate(r), l);
  return 0.5 * mass * dot(v, v) +
         0.5 * (local.x * local.x / moments.x + local.y * local.y / moments.y + local.z * local.z / moments.z);
}

TEST(SplitBody, FragmentsKeepMassMomentaAndKineticEnergy) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  const Real density = 2650;
  int splits = 0;
  for (int trial = 0; trial < 100; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Real size = std::pow(10.0, 2 * u(rng) - 1);  // 1 mm to 10 m
    WorldBuilder builder;
    const std::uint32_t rock = builder.add_material({"rock", density, 1e7, 0.25, 0.3, 0.5});
    const Shape shape = trial % 10 == 0 ? Shape{Box{Vec3{0.3, 0.5, 0.2} * size}}
                                        : random_polyhedron(6 + static_cast<int>(rng() % 40), size, rng);
    builder.add_body({.shape = {shape, {}}, .material = rock, .position = Vec3{u(rng), u(rng), u(rng)} * 10 * size,
                      .rotation = random_rotation(rng), .velocity = Vec3{u(rng), u(rng), u(rng)} * 3,
                      .angular_velocity = Vec3{u(rng), u(rng), u(rng)} * (20 / size)});
    const World w = builder.build();
    const Body& b = w.bodies[0];
    const ShapeTemplate& t = w.templates[b.shape];
    const Real mass = density * t.unit_mass.volume;
    const Vec3 moments = t.principal.moments * density;
    // A plane through a point near the centre, turned at random.
    const Vec3 point = b.position + Vec3{u(rng), u(rng), u(rng)} * (0.1 * size);
    const Vec3 normal{u(rng), u(rng), u(rng)};
    const std::vector<Fragment> pieces = split_body(t, b, density, point, normal);
    if (pieces.empty()) continue;
    ASSERT_EQ(pieces.size(), 2u);
    ++splits;
    Real m = 0, energy = 0;
    Vec3 p, l_origin, l_centre;
    for (const Fragment& f : pieces) {
      const Real mf = density * f.unit_mass.volume;
      m += mf;
      p += f.velocity * mf;
      l_origin += f.angular_momentum + cross(f.position, f.velocity * mf);
      l_centre += f.angular_momentum + cross(f.position - b.position, f.velocity * mf);
      energy += kinetic(mf, f.velocity, f.orientation, f.principal.moments * density, f.angular_momentum);
    }
    const Real parent_energy = kinetic(mass, b.velocity, b.orientation, moments, b.angular_momentum);
    EXPECT_NEAR(m, mass, 1e-12 * mass);
    EXPECT_LT(length(p - b.velocity * mass), 1e-12 * mass * (length(b.velocity) + 1e-300));
    const Real l_scale = length(b.angular_momentum) + mass * length(b.position) * length(b.velocity);
    EXPECT_LT(length(l_origin - (b.angular_momentum + cross(b.position, b.velocity * mass))), 1e-12 * l_scale);
    EXPECT_LT(length(l_centre - b.angular_momentum), 1e-12 * (length(b.angular_momentum) + mass * size * length(b.velocity)));
    EXPECT_NEAR(energy, parent_energy, 1e-12 * parent_energy);
    // The same solid: points of the parent lie in exactly one fragment (off the cut), and fragments' points in it.
    for (int k = 0; k < 20; ++k) {
      const Vec3 q = b.position + Vec3{u(rng), u(rng), u(rng)} * (0.3 * size);
      const Transform at = Transform::from(q, Quat{});
      const bool in_parent = intersect(Shape{Point{}}, at, t.shape, shape_pose(t, b));
      if (std::fabs(dot(normalized(normal), q - point)) < 1e-9 * size) continue;
      int in_pieces = 0;
      for (const Fragment& f : pieces) {
        ShapeTemplate own;
        own.shape = f.shape, own.unit_mass = f.unit_mass, own.principal = f.principal;
        Body placed;
        placed.position = f.position, placed.orientation = f.orientation;
        in_pieces += intersect(Shape{Point{}}, at, f.shape, shape_pose(own, placed));
      }
      EXPECT_EQ(in_pieces, in_parent ? 1 : 0) << "point " << k;
    }
  }
  EXPECT_GT(splits, 80);
}

TEST(SplitBody, WhatCannotSplitIsRefused) {
  WorldBuilder builder;
  const std::uint32_t rock = builder.add_material({"rock", 2650, 1e7, 0.25, 0.3, 0.5});
  builder.add_body({.shape = {make_sphere(0.01), {}}, .material = rock, .position = {0, 0, 0}});
  builder.add_body({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .material = rock, .position = {0.1, 0, 0}, .fixed = true});
  const World w = builder.build();
  EXPECT_THROW(split_body(w.templates[w.bodies[0].shape], w.bodies[0], 2650, {0, 0, 0}, {0, 0, 1}),
               std::invalid_argument);  // curved (a tessellation under the volume law)
  EXPECT_THROW(split_body(w.templates[w.bodies[1].shape], w.bodies[1], 2650, {0.1, 0, 0}, {0, 0, 1}),
               std::invalid_argument);  // fixed
}

}  // namespace
}  // namespace gjkdem::dem
