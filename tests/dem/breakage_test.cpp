// Grains that break during a run (breakage.hpp, docs/breakage.md): a split
// keeps mass, volume, momenta and kinetic energy; a cube pressed between
// two platens splits along the press's axis, again and again until its
// fragments are smaller than unbreakable_below; a run stopped and restored
// from its checkpoint across the splits gives the same bits.
#include "gjkdem/dem/breakage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "gjkdem/dem/break_criterion.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/checkpoint.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kHalf = 0.005;  // the cube's half side (m)

// A cube between a fixed floor and a plate coming down at `speed` (m/s),
// turning and drifting a little so that every momentum is in play.
World press(Real strength, Real speed = 0.05, ContactModel model = ContactModel::Volume, Real smallest = 0.0055) {
  WorldSettings s;
  s.gravity = {};
  s.model = model;
  WorldBuilder b(s);
  Material rock{.name = "rock", .density = 2500, .youngs_modulus = 1e7};
  // The strength's size is the cube's: its mean is `strength`; quarters of it
  // are the last to break (an eighth is 0.0062 m across, a sixteenth 0.0049).
  rock.strength = {.mean = strength, .weibull_modulus = 5, .reference_size = 0.0124, .smallest = smallest, .seed = 3};
  const std::uint32_t m = b.add_material(rock);
  const std::uint32_t down = b.add_motion({.velocity = {0, 0, -speed}}, "press");
  b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor");
  b.add_plane({0, 0, 2 * kHalf + 1e-5}, {0, 0, -1}, m, "plate", down);
  b.add_body({.shape = {Shape{Box{{kHalf, kHalf, kHalf}}}, {}}, .material = m, .position = {0, 0, kHalf},
              .rotation = quat_from_axis_angle({0, 0, 1}, 0.3), .velocity = {0.001, -0.002, 0},
              .angular_velocity = {0, 0, 0.5}, .label = "cube"});
  return b.build();
}

struct Totals {
  Real mass = 0, volume = 0, energy = 0;
  Vec3 momentum, angular_momentum;  // about the origin
};

Totals totals(const World& w) {
  Totals t;
  for (const Body& b : w.bodies) {
    if (b.fixed) continue;
    const Real m = mass_of(w, b);
    t.mass += m, t.volume += w.templates[b.shape].unit_mass.volume;
    t.momentum += b.velocity * m;
    t.angular_momentum += cross(b.position, b.velocity * m) + b.angular_momentum;
  }
  t.energy = kinetic_energy(w);
  return t;
}

void expect_same(const Totals& a, const Totals& b) {
  EXPECT_NEAR(b.mass, a.mass, 1e-12 * a.mass);
  EXPECT_NEAR(b.volume, a.volume, 1e-12 * a.volume);
  const Real p = length(a.momentum), l = length(a.angular_momentum);
  EXPECT_LE(length(b.momentum - a.momentum), 1e-12 * p);
  EXPECT_LE(length(b.angular_momentum - a.angular_momentum), 1e-12 * l);
  EXPECT_NEAR(b.energy, a.energy, 1e-12 * a.energy);
}

TEST(Breakage, ASplitKeepsMassMomentaAndEnergyAndCutsAlongThePress) {
  World w = press(1e12);  // too strong to break: forces first
  const Real dt = critical_time_step(w);
  for (int k = 0; k < 200 && w.stats.contacts < 2; ++k) ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
  ASSERT_EQ(w.stats.contacts, 2);
  const Totals before = totals(w);
  w.bodies[0].applied_force = {0.3, -0.6, 0.9}, w.bodies[0].applied_work = 2;  // shared by mass (their rows)
  const Body parent = w.bodies[0];
  w.materials[0].strength.mean = 1;  // now the stress is past any draw
  ASSERT_EQ(break_grains(w), 1);
  ASSERT_EQ(w.bodies.size(), 2u);
  expect_same(before, totals(w));
  EXPECT_EQ(w.broken, 1u);
  EXPECT_FALSE(w.forces_current);
  // The first fragment keeps the id, the second takes the next one; both
  // have templates of their own, one generation on.
  EXPECT_EQ(w.bodies[0].id, parent.id);
  EXPECT_EQ(w.bodies[1].id, parent.id + 1);
  EXPECT_EQ(w.templates.size(), 3u);
  EXPECT_EQ(built_templates(w), 1u);
  for (const Body& b : w.bodies) {
    const ShapeTemplate& t = w.templates[b.shape];
    EXPECT_EQ(t.generation, 1u);
    // About its own centroid, so that its reach (and its box) fits it: a
    // half cube reaches less far than the cube.
    EXPECT_LT(length(t.unit_mass.centroid), 1e-12 * kHalf);
    EXPECT_LT(t.reach, w.templates[0].reach);
  }
  EXPECT_TRUE(w.pairs.empty());  // the cube's springs are forgotten
  // Each fragment takes its share by volume of the grain's applied load and
  // its work; the last evaluation's force and torque are found again.
  const Real volume = w.templates[1].unit_mass.volume + w.templates[2].unit_mass.volume;
  for (const Body& b : w.bodies) {
    const Real share = w.templates[b.shape].unit_mass.volume / volume;
    EXPECT_GT(share, 0.1);
    EXPECT_LT(length(b.applied_force - parent.applied_force * share), 1e-15);
    EXPECT_DOUBLE_EQ(b.applied_work, parent.applied_work * share);
    EXPECT_EQ(b.force, Vec3{});
    EXPECT_EQ(b.torque, Vec3{});
  }
  EXPECT_DOUBLE_EQ(w.bodies[0].applied_work + w.bodies[1].applied_work, parent.applied_work);
  // Pressed along z, the cube splits on a plane holding z (but for the
  // friction of its slide and spin): the fragments' centres lie side by side.
  const Vec3 a = w.bodies[0].position, c = w.bodies[1].position;
  EXPECT_GT(length(a - c), 0.5 * kHalf);
  EXPECT_LT(std::fabs(a.z - c.z), 0.01 * length(a - c));
  // A split with nothing past its strength changes nothing.
  w.materials[0].strength.mean = 1e12;
  ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
  EXPECT_EQ(w.stats.broken, 0);
  EXPECT_EQ(w.bodies.size(), 2u);
}

// Runs the press for `steps` steps; returns the grains broken.
std::uint64_t run_press(World& w, Real dt, int steps) {
  for (int k = 0; k < steps; ++k) {
    const StepReport r = step(w, dt);
    EXPECT_EQ(r.status, StepStatus::Ok) << "step " << k;
    if (r.status != StepStatus::Ok) break;
  }
  return w.broken;
}

TEST(Breakage, APressedCubeBreaksUntilItsFragmentsAreTooSmall) {
  World w = press(2e4);
  const Totals start = totals(w);
  const Real dt = critical_time_step(w);
  run_press(w, dt, 300);  // the plate comes down 0.12 mm
  EXPECT_GE(w.broken, 3u);
  EXPECT_EQ(w.bodies.size(), 1 + w.broken);
  // Volume is kept through every split, and the ids stay in order.
  Real volume = 0;
  for (const Body& b : w.bodies) volume += w.templates[b.shape].unit_mass.volume;
  EXPECT_NEAR(volume, start.volume, 1e-12 * start.volume);
  for (std::size_t i = 1; i < w.bodies.size(); ++i) EXPECT_LT(w.bodies[i - 1].id, w.bodies[i].id);
  // A fragment broke only while as large as unbreakable_below: none is
  // smaller than 3/4 of it (Gruenbaum's bound on a cut through the centroid).
  for (const Body& b : w.bodies) EXPECT_GE(grain_size(w.templates[b.shape]), 0.75 * 0.0055);
  EXPECT_LE(w.bodies.capacity(), 1 + most_fragments(w.templates[0], w.materials[0]));
  EXPECT_GE(w.bodies.capacity(), w.bodies.size());
}

// A split stores energy (issue 54): a fragment's contacts start on its
// grain's overlap, where the smaller, stiffer fragments hold more than the
// grain did (under the volume law about twice; under Hertz and linear one
// contact becomes two), and the balance showed energy from nowhere. The
// balance counts what each split stored (World::split_energy: the contacts'
// energy on the fragments less on the grain, at the split's positions). A
// cascade of splits under each law: the energy dissipated (what the plate
// and the splits put in less what the grains hold) never falls at a split
// by more than a step's own error, nor below it elsewhere; without the
// splits' term it falls by what they stored.
TEST(Breakage, TheBalanceCountsWhatACascadeOfSplitsStoresUnderAnyLaw) {
  for (const ContactModel model : {ContactModel::Volume, ContactModel::Hertz, ContactModel::Linear}) {
    SCOPED_TRACE(static_cast<int>(model));
    World w = press(2e4, 0.05, model, 0.0035);
    const Real dt = critical_time_step(w);
    const Real start = kinetic_energy(w);
    auto dissipated = [&] { return energy_balance(w, start).dissipated; };
    Real most_elastic = 0, worst_uncounted = 0;
    int split_steps = 0;
    for (int k = 0; k < 6000 && w.broken < 6; ++k) {
      const Real before = dissipated(), stored_before = w.split_energy;
      ASSERT_EQ(step(w, dt).status, StepStatus::Ok) << "step " << k;
      most_elastic = std::fmax(most_elastic, w.stats.elastic_energy);
      const Real now = dissipated();
      if (w.stats.broken > 0) {
        ++split_steps;
        EXPECT_GE(now - before, -1e-3 * most_elastic) << "split at step " << k;
        // What the balance would have lost at this split without its term.
        worst_uncounted = std::fmin(worst_uncounted, now - before - (w.split_energy - stored_before));
      } else {
        EXPECT_EQ(w.split_energy, stored_before);
      }
      EXPECT_GE(now, -1e-3 * most_elastic) << "step " << k;
    }
    EXPECT_GE(split_steps, 3);
    EXPECT_GE(w.broken, 6u);
    EXPECT_LT(worst_uncounted, -1e-2 * most_elastic);  // the term is what keeps the balance
  }
}

TEST(Breakage, ARunRestoredAcrossSplitsGivesTheSameBits) {
  World whole = press(2e4);
  const Real dt = critical_time_step(whole);
  const int steps = 300;
  run_press(whole, dt, steps);
  ASSERT_GE(whole.broken, 3u);

  World first = press(2e4);
  run_press(first, dt, 135);  // the first splits at step 107, the last at 164
  ASSERT_GE(first.broken, 1u);
  ASSERT_LT(first.broken, whole.broken);  // splits on both sides of the stop
  io::Checkpoint c;
  c.run.dt = dt, c.run.steps_total = steps, c.run.steps_per_output = 1, c.run.step = 135;
  const std::string bytes = io::encode_checkpoint(first, c, 7);
  World restored = press(2e4);
  io::decode_checkpoint(bytes, restored, 7, "test");
  EXPECT_EQ(restored.templates.size(), first.templates.size());
  EXPECT_EQ(restored.broken, first.broken);
  run_press(restored, dt, steps - 135);
  ASSERT_EQ(restored.bodies.size(), whole.bodies.size());
  EXPECT_EQ(restored.time, whole.time);
  EXPECT_NE(whole.split_energy, 0);
  EXPECT_EQ(restored.split_energy, whole.split_energy);
  for (std::size_t i = 0; i < whole.bodies.size(); ++i)
    EXPECT_EQ(std::memcmp(&restored.bodies[i], &whole.bodies[i], sizeof(Body)), 0) << "body " << i;
}

// Single-grain crushing (issue 31): cubes of sizes from 2 to 64 mm pressed
// between platens. A cube loaded by forces F1 and F2 on opposite faces
// feels the stress (F1 + F2) / (2 s^2) along the load (s its side: the
// Love-Weber stress (F1 + F2) s / 2 / s^3), so it breaks when the platens'
// mean force F = (F1 + F2) / 2 reaches strength(d) s^2 (F1 = F2 once the
// press is slow; the plate's first touch is not), and its crushing stress
// F / s^2 follows the size effect d^(-3/m) of its strength's Weibull
// distribution: each grain within 5% of its own drawn strength (the step's
// overshoot), and the slope of ln(F / s^2) against ln d fitted over 200
// grains within 10% of -3/m.
TEST(Breakage, CrushingStressesFollowTheSizeEffectOfTheirWeibullModulus) {
  const Real m = 5, mean = 2e4, d0 = 0.0124;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<Real> log_side(std::log(0.002), std::log(0.064)), turn(0, kPi / 2);
  Real sx = 0, sy = 0, sxx = 0, sxy = 0;
  const int grains = 200;
  for (int g = 0; g < grains; ++g) {
    const Real side = std::exp(log_side(rng));
    WorldSettings settings;
    settings.gravity = {};
    settings.model = ContactModel::Volume;
    WorldBuilder b(settings);
    Material rock{.name = "rock", .density = 2500, .youngs_modulus = 1e7};
    rock.strength = {.mean = mean, .weibull_modulus = m, .reference_size = d0, .smallest = side / 2,
                     .seed = static_cast<std::uint64_t>(g)};
    const std::uint32_t mat = b.add_material(rock);
    const std::uint32_t down = b.add_motion({.velocity = {0, 0, -0.02 * side / 0.01}}, "press");
    b.add_plane({0, 0, 0}, {0, 0, 1}, mat, "floor");
    b.add_plane({0, 0, side * 1.001}, {0, 0, -1}, mat, "plate", down);
    b.add_body({.shape = {Shape{Box{{side / 2, side / 2, side / 2}}}, {}}, .material = mat,
                .position = {0, 0, side / 2}, .rotation = quat_from_axis_angle({0, 0, 1}, turn(rng)), .label = "cube"});
    World w = b.build();
    const ShapeTemplate& cube = w.templates[0];
    const Real own = grain_strength(w.materials[0].strength, grain_size(cube), strength_draw(g, 0, 0));
    const Real dt = critical_time_step(w);
    // The press runs with the grain unbreakable; after each step the
    // engine's own test (find_splits, with the strength restored) says
    // whether it would have broken on that step's forces, which are then read.
    const Strength strength = w.materials[0].strength;
    w.materials[0].strength.mean = 1e30;
    Real force = 0;  // the mean of the platens' forces when it breaks
    bool broke = false;
    for (int k = 0; k < 5000 && !broke; ++k) {
      ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
      w.materials[0].strength = strength;
      broke = !find_splits(w, nullptr).empty();
      w.materials[0].strength.mean = 1e30;
      if (broke)
        for (const StepContact& c : w.results.contacts)
          if (c.active && c.a_is_plane) force += 0.5 * std::fabs(c.force.z);
    }
    ASSERT_TRUE(broke) << "grain " << g << " of side " << side << " did not break";
    const Real stress = force / (side * side);
    EXPECT_NEAR(stress, own, 0.05 * own) << "grain " << g << " of side " << side;
    const Real x = std::log(grain_size(cube)), y = std::log(stress);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const Real n = grains, slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  EXPECT_NEAR(slope, -3 / m, 0.1 * 3 / m) << "fitted slope " << slope;
  RecordProperty("fitted_slope", std::to_string(slope));
}

TEST(Breakage, TheBuilderRefusesMoreFragmentsThanItCanHold) {
  WorldBuilder b;
  Material rock{.name = "rock"};
  rock.strength = {.mean = 1e6, .weibull_modulus = 3, .reference_size = 0.01, .smallest = 1e-6};
  const std::uint32_t m = b.add_material(rock);
  b.add_body({.shape = {Shape{Box{{kHalf, kHalf, kHalf}}}, {}}, .material = m, .label = "cube"});
  EXPECT_THROW(b.build(), BuildError);
}

}  // namespace
}  // namespace gjkdem::dem
