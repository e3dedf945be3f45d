// Energy of the volume law through the engine, without damping or friction,
// in random orientations:
// - a random polyhedron spinning onto a plane wall: the force k V along the
//   wall normal through the centroid of the part below the plane derives
//   from U = k * integral of depth over that part (buoyancy), so kinetic plus
//   gravity energy after the bounce equals the energy before;
// - two random polyhedra colliding under the potential form F = k' V S_A
//   (U = k' V^2 / 2) with Feng's energy-conserving line and couple: kinetic
//   energy after separation equals the energy before (issue 4 asks 1%).
// Measured: both within 2e-11 at dt = 2e-7 s (contacts last ~1e-4 s), so the
// tests ask 1e-8. For comparison, the force k V along the unit normal
// (VolumeForm::Normalized) loses 0.3% to 7.3% in the same six collisions, and
// k V through the cut face's centroid on a plane lost up to 3.8% in a bounce.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {
namespace {

Quat random_orientation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return normalized(Quat{g(rng), g(rng), g(rng), g(rng)});
}

// Steps until the contact that started has ended; false if it never started
// or never ended.
bool run_through_contact(World& w, Real dt, int max_steps) {
  bool touched = false;
  for (int i = 0; i < max_steps; ++i) {
    step(w, dt);
    if (w.stats.contacts > 0) touched = true;
    if (touched && w.stats.contacts == 0) return true;
  }
  return false;
}

TEST(VolumeEnergy, PolyhedronBouncesOnAPlaneWithItsEnergy) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 8; ++trial) {
    WorldSettings settings;
    settings.model = ContactModel::Volume;
    settings.volume_stiffness = 1e9;
    WorldBuilder builder(settings);
    const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 1.0, 0});
    builder.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor");
    builder.add_body({.shape = {random_polyhedron(12, 0.02, rng), {}}, .material = rock, .position = {0, 0, 1}});
    World w = builder.build();
    Body& b = w.bodies[0];  // the state to start from
    b.orientation = random_orientation(rng);
    b.position = {0, 0, 0.0125};
    b.velocity = {0.1, 0, -0.5};
    b.angular_momentum = Vec3{1, -2, 3} * 1e-6;
    const Real e0 = kinetic_energy(w) + potential_energy(w);
    ASSERT_TRUE(run_through_contact(w, 2e-7, 200000)) << trial;
    EXPECT_NEAR((kinetic_energy(w) + potential_energy(w)) / e0, 1, 1e-8) << "trial " << trial;
  }
}


TEST(VolumeEnergy, PolyhedraCollideWithTheirEnergyUnderThePotentialForm) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 6; ++trial) {
    WorldSettings settings;
    settings.model = ContactModel::Volume;
    settings.volume_form = VolumeForm::Potential;
    settings.rocking_resistance = false;
    settings.gravity = {};
    settings.volume_stiffness = 1e10;
    WorldBuilder builder(settings);
    const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 1.0, 0});
    for (int k = 0; k < 2; ++k)
      builder.add_body({.shape = {random_polyhedron(12, 0.02, rng), {}}, .material = rock, .position = {0, 0, k * 1.0}});
    World w = builder.build();
    for (std::uint32_t k = 0; k < 2; ++k) {
      Body& b = w.bodies[k];  // the state to start from
      b.orientation = random_orientation(rng);
      b.position = {k == 0 ? -0.0105 : 0.0105, 0.003 * g(rng), 0.003 * g(rng)};
      b.velocity = {k == 0 ? 0.5 : -0.5, 0, 0};
    }
    const Real e0 = kinetic_energy(w);
    ASSERT_TRUE(run_through_contact(w, 2e-7, 200000)) << trial;
    EXPECT_NEAR(kinetic_energy(w) / e0, 1, 1e-8) << "trial " << trial;
  }
}


}  // namespace
}  // namespace gjkdem::dem
