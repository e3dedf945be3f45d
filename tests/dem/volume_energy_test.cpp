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

#include "gjkdem/dem/generators.hpp"
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
    if (w.last_contacts > 0) touched = true;
    if (touched && w.last_contacts == 0) return true;
  }
  return false;
}

TEST(VolumeEnergy, PolyhedronBouncesOnAPlaneWithItsEnergy) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 8; ++trial) {
    World w;
    w.model = ContactModel::Volume;
    w.volume_stiffness = 1e9;
    w.materials.push_back({"rock", 2500, 1e7, 0.25, 1.0, 0});
    w.templates.push_back(make_template(random_polyhedron(12, 0.02, rng)));
    w.planes.push_back({1000, {0, 0, 0}, {0, 0, 1}, 0});
    Body b;
    b.orientation = random_orientation(rng);
    b.position = {0, 0, 0.0125};
    b.velocity = {0.1, 0, -0.5};
    b.angular_momentum = Vec3{1, -2, 3} * 1e-6;
    w.bodies.push_back(b);
    const Real e0 = kinetic_energy(w) + potential_energy(w);
    ASSERT_TRUE(run_through_contact(w, 2e-7, 200000)) << trial;
    EXPECT_NEAR((kinetic_energy(w) + potential_energy(w)) / e0, 1, 1e-8) << "trial " << trial;
  }
}


TEST(VolumeEnergy, PolyhedraCollideWithTheirEnergyUnderThePotentialForm) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 6; ++trial) {
    World w;
    w.model = ContactModel::Volume;
    w.volume_form = VolumeForm::Potential;
    w.rocking_resistance = false;
    w.gravity = {};
    w.volume_stiffness = 1e10;
    w.materials.push_back({"rock", 2500, 1e7, 0.25, 1.0, 0});
    w.templates.push_back(make_template(random_polyhedron(12, 0.02, rng)));
    w.templates.push_back(make_template(random_polyhedron(12, 0.02, rng)));
    for (std::uint32_t k = 0; k < 2; ++k) {
      Body b;
      b.id = k;
      b.shape = k;
      b.orientation = random_orientation(rng);
      b.position = {k == 0 ? -0.0105 : 0.0105, 0.003 * g(rng), 0.003 * g(rng)};
      b.velocity = {k == 0 ? 0.5 : -0.5, 0, 0};
      w.bodies.push_back(b);
    }
    const Real e0 = kinetic_energy(w);
    ASSERT_TRUE(run_through_contact(w, 2e-7, 200000)) << trial;
    EXPECT_NEAR(kinetic_energy(w) / e0, 1, 1e-8) << "trial " << trial;
  }
}


}  // namespace
}  // namespace gjkdem::dem
