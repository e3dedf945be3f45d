// The step's stages through step(), begin_step and finish_step:
// - the run loop (dem::run) steps a world as step() does, bit for bit, on a
//   world with body and wall contacts;
// - a free body under gravity follows uniform acceleration to round-off
//   (kick-drift-kick is exact for a constant force), and the clock advances
//   by dt per step;
// - forces are summed in the contact list's order: a bed stepped on one and
//   on two threads gives the same bits;
// - one force evaluation's stats, forces and elastic energy against Hertz's
//   closed forms: a sphere pressed into a plane wall, another far away, two
//   spheres pressed together;
// - a contact that ends forgets its springs, and the pair store drops the
//   pair once its box leaves the wall;
// - a periodic cell compressed below shortest_period stops the step with
//   CellTooShort, its axis and the shortest width allowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

bool same_bodies(const World& x, const World& y) {
  return x.bodies.size() == y.bodies.size() &&
         std::memcmp(x.bodies.data(), y.bodies.data(), x.bodies.size() * sizeof(Body)) == 0;
}

bool same_pairs(const World& x, const World& y) {
  if (x.pairs.size() != y.pairs.size()) return false;
  for (std::size_t k = 0; k < x.pairs.size(); ++k) {
    const PairState &p = x.pairs[k], &q = y.pairs[k];
    if (p.key != q.key || p.history.spring != q.history.spring || p.history.twist != q.history.twist ||
        p.history.roll != q.history.roll)
      return false;
  }
  return true;
}

// Hertz, friction, a plane floor, three spheres: one falling on the floor,
// two flying into each other.
World small_world() {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder b(settings);
  const std::uint32_t m = b.add_material({"m", 2000, 1e7, 0.3, 0.6, 0.4});
  b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor");
  b.add_body({.shape = {make_sphere(0.01), {}}, .material = m, .position = {0, 0, 0.0105},
              .velocity = {0.2, 0.1, -0.3}, .angular_velocity = {0, 5, 0}, .label = "faller"});
  b.add_body({.shape = {Shape{Box{{0.008, 0.006, 0.01}}}, {}}, .material = m, .position = {0.1, 0, 0.05},
              .rotation = quat_from_axis_angle(normalized(Vec3{1, 1, 0}), 0.3), .velocity = {0.4, 0, 0},
              .label = "left"});
  b.add_body({.shape = {make_sphere(0.009), {}}, .material = m, .position = {0.13, 0.004, 0.052},
              .velocity = {-0.4, 0, 0}, .label = "right"});
  return b.build();
}

// The run loop (dem::run: run_domains on one rank, run_loop.cpp) steps a
// world as step() does, bit for bit: it neither cuts, copies nor gathers a
// whole world, and adds nothing to the step.
TEST(StepTest, TheRunLoopStepsAsStepDoes) {
  World stepped = small_world();
  World looped = stepped;
  const Real dt = 2e-5;
  const int n = 2000;
  bool wall_contact = false, body_contact = false;
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(step(stepped, dt).status, StepStatus::Ok);
    wall_contact = wall_contact || stepped.stats.wall_contacts > 0;
    body_contact = body_contact || stepped.stats.contacts > stepped.stats.wall_contacts;
  }
  RunState run = plan_run(n * dt, dt, 10 * dt);
  ASSERT_EQ(run.steps_total, static_cast<std::uint64_t>(n));
  ASSERT_EQ(dem::run(looped, run, {}).status, RunStatus::Completed);
  EXPECT_TRUE(same_bodies(stepped, looped));
  EXPECT_TRUE(same_pairs(stepped, looped));
  EXPECT_EQ(stepped.time, looped.time);
  EXPECT_EQ(stepped.wall_work, looped.wall_work);
  EXPECT_EQ(stepped.stats.elastic_energy, looped.stats.elastic_energy);
  EXPECT_TRUE(wall_contact) << "the faller met the floor";
  EXPECT_TRUE(body_contact) << "the flyers met";
}

// Kick-drift-kick with a constant force: v_n = v0 + g t_n exactly and
// x_{n+1} = x_n + v_n dt + g dt^2 / 2, so x_n = x0 + v0 t_n + g t_n^2 / 2.
// (Kicking once per step before the drift would be off by g t dt / 2, here
// about 5e-3 m at t = 1 s.) No torque: the angular momentum stays, to the bit.
TEST(StepTest, AFreeBodyFollowsUniformAccelerationAndTheClockAdvances) {
  WorldSettings settings;
  settings.gravity = {0.5, -1.5, -9.81};
  WorldBuilder b(settings);
  const std::uint32_t m = b.add_material({"m", 2500, 1e7, 0.25, 0.5, 0.5});
  const Vec3 x0{0.1, 0.2, 3}, v0{1, 0.5, 2};
  b.add_body({.shape = {Shape{Box{{0.01, 0.02, 0.03}}}, {}}, .material = m, .position = x0, .velocity = v0,
              .angular_velocity = {1, -2, 3}, .label = "box"});
  World w = b.build();
  const Vec3 l0 = w.bodies[0].angular_momentum;
  const Real dt = 1e-3;
  const int n = 1000;
  for (int i = 1; i <= n; ++i) {
    ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
    ASSERT_EQ(w.stats.contacts, 0);
    if (i % 250 != 0) continue;
    const Real t = i * dt;
    EXPECT_NEAR(w.time, t, 1e-14 * i) << "step " << i;
    const Body& body = w.bodies[0];
    const Vec3 x = x0 + v0 * t + settings.gravity * (t * t / 2), v = v0 + settings.gravity * t;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(body.position[k], x[k], 1e-11) << "step " << i << ", axis " << k;
      EXPECT_NEAR(body.velocity[k], v[k], 1e-12) << "step " << i << ", axis " << k;
    }
    EXPECT_EQ(body.angular_momentum, l0) << "step " << i;
  }
}

// A bed of random polyhedra thrown about in a box of wall slabs, with
// enough candidate contacts (64) for the narrow phase and the laws to run on
// the threads.
World bed(int threads) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  settings.threads = threads;
  WorldBuilder b(settings);
  const std::uint32_t m = b.add_material({"m", 2500, 1e7, 0.25, 0.4, 0.5});
  b.add_box_walls({0, 0, 0}, {0.05, 0.05, 0.2}, true, 0.01, m, "box");
  std::mt19937_64 rng(5);
  RegionFill fill;
  for (int k = 0; k < 4; ++k) fill.variants.push_back({random_polyhedron(10, 0.01, rng), {}});
  fill.count = 120;
  fill.lo = {0, 0, 0};
  fill.hi = {0.05, 0.05, 0.2};
  fill.material = m;
  b.fill_region(fill, rng);
  World w = b.build();
  // Each grain thrown its own way (the same draws for every call), so that
  // they meet soon.
  std::uniform_real_distribution<Real> speed(-1, 1);
  for (Body& body : w.bodies)
    if (!body.fixed) body.velocity = {speed(rng), speed(rng), speed(rng)};
  return w;
}

TEST(StepTest, OneAndTwoThreadsGiveTheSameBits) {
  World one = bed(1), two = bed(2);
  ASSERT_TRUE(same_bodies(one, two)) << "the same start";
  std::size_t most_candidates = 0;
  int most_contacts = 0;
  for (int i = 0; i < 300; ++i) {
    ASSERT_EQ(step(one, 2e-5).status, StepStatus::Ok);
    ASSERT_EQ(step(two, 2e-5).status, StepStatus::Ok);
    most_candidates = std::max(most_candidates, two.results.contacts.size());
    most_contacts = std::max(most_contacts, two.stats.contacts);
  }
  EXPECT_GE(most_candidates, 64u) << "the contact loops ran on the threads";
  EXPECT_GT(most_contacts, 10);
  EXPECT_TRUE(same_bodies(one, two));
  EXPECT_TRUE(same_pairs(one, two));
  EXPECT_EQ(one.stats.elastic_energy, two.stats.elastic_energy);
  EXPECT_EQ(one.stats.contacts, two.stats.contacts);
}

// E* of two bodies of one material, and Hertz's 4/3 E* sqrt(R* d) d and
// 8/15 E* sqrt(R*) d^(5/2).
constexpr Real kE = 1e7, kNu = 0.3, kRho = 2000;
Real e_star() { return 1 / (2 * (1 - kNu * kNu) / kE); }
Real hertz_force(Real r_star, Real d) { return 4.0 / 3 * e_star() * std::sqrt(r_star * d) * d; }
Real hertz_energy(Real r_star, Real d) { return 8.0 / 15 * e_star() * std::sqrt(r_star) * std::pow(d, 2.5); }

TEST(StepTest, StatsAndForcesOfOneEvaluationMatchHertz) {
  const Real r = 0.01, d = 3e-4, g = 9.81;
  const Real mass = kRho * 4.0 / 3 * kPi * r * r * r;
  {
    WorldSettings settings;
    settings.model = ContactModel::Hertz;
    WorldBuilder b(settings);
    b.accept_initial_overlaps();
    const std::uint32_t m = b.add_material({"m", kRho, kE, kNu, 0.5, 0.5});
    b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor");
    b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {0.02, -0.03, r - d}, .label = "pressed"});
    b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {0.5, 0, 0.3}, .label = "far"});
    World w = b.build();
    ASSERT_EQ(compute_forces_now(w).status, StepStatus::Ok);
    EXPECT_EQ(w.stats.contacts, 1);
    EXPECT_EQ(w.stats.wall_contacts, 1);
    EXPECT_NEAR(w.stats.elastic_energy, hertz_energy(r, d), 1e-9 * hertz_energy(r, d));  // R* = R on a plane
    // At rest: no damping, no friction; the far sphere feels gravity only.
    EXPECT_NEAR(w.bodies[0].force.z, hertz_force(r, d) - mass * g, 1e-9 * hertz_force(r, d));
    EXPECT_NEAR(length(Vec3{w.bodies[0].force.x, w.bodies[0].force.y, 0}), 0, 1e-12);
    EXPECT_NEAR(length(w.bodies[0].torque), 0, 1e-12);
    EXPECT_EQ(w.bodies[1].force.x, 0);
    EXPECT_EQ(w.bodies[1].force.y, 0);
    EXPECT_NEAR(w.bodies[1].force.z, -mass * g, 1e-12 * mass * g);
    // The far sphere alone: nothing touches.
    w.bodies[0].position.z = 0.2;
    w.forces_current = false;
    ASSERT_EQ(compute_forces_now(w).status, StepStatus::Ok);
    EXPECT_EQ(w.stats.contacts, 0);
    EXPECT_EQ(w.stats.wall_contacts, 0);
    EXPECT_EQ(w.stats.elastic_energy, 0);
  }
  {
    // Two spheres of radii r and r / 2 pressed together by d, no gravity:
    // R* = r / 3, forces equal and opposite along the line of centres.
    WorldSettings settings;
    settings.model = ContactModel::Hertz;
    settings.gravity = {};
    WorldBuilder b(settings);
    b.accept_initial_overlaps();
    const std::uint32_t m = b.add_material({"m", kRho, kE, kNu, 0.5, 0.5});
    const Vec3 u = normalized(Vec3{1, -2, 2});
    b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {0, 0, 0}, .label = "big"});
    b.add_body({.shape = {make_sphere(r / 2), {}}, .material = m, .position = u * (1.5 * r - d), .label = "small"});
    World w = b.build();
    ASSERT_EQ(compute_forces_now(w).status, StepStatus::Ok);
    EXPECT_EQ(w.stats.contacts, 1);
    EXPECT_EQ(w.stats.wall_contacts, 0);
    EXPECT_NEAR(w.stats.elastic_energy, hertz_energy(r / 3, d), 1e-9 * hertz_energy(r / 3, d));
    const Vec3 f = u * hertz_force(r / 3, d);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(w.bodies[1].force[k], f[k], 1e-9 * length(f)) << "axis " << k;
      EXPECT_NEAR(w.bodies[0].force[k], -f[k], 1e-9 * length(f)) << "axis " << k;
    }
  }
}

// A sphere sliding into a frictional plane wall at a slant, no gravity: the
// tangential spring loads while it touches; the step after it leaves, the
// pair (still listed: its box reaches the wall) keeps no spring; once its box
// is off the wall the pair store drops it.
TEST(StepTest, AContactThatEndsForgetsItsSprings) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  settings.gravity = {};
  WorldBuilder b(settings);
  const Real r = 0.01;
  const std::uint32_t m = b.add_material({"m", kRho, kE, kNu, 0.8, 0.5});
  b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor");
  b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {0, 0, r + 1e-6}, .velocity = {0.5, 0, -0.3},
              .label = "ball"});
  World w = b.build();
  const Real dt = 1e-6;
  Real most_spring = 0;
  bool touched = false;
  for (int i = 0; i < 100000 && !(touched && w.bodies[0].position.z > r); ++i) {  // through the contact
    ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
    if (w.stats.contacts == 1) {
      touched = true;
      ASSERT_EQ(w.pairs.size(), 1u);
      most_spring = std::max(most_spring, length(w.pairs[0].history.spring));
    }
  }
  ASSERT_TRUE(touched);
  ASSERT_GT(w.bodies[0].position.z, r) << "it bounced";
  EXPECT_GT(w.bodies[0].velocity.z, 0);
  EXPECT_GT(most_spring, 1e-7) << "friction loaded the spring";
  EXPECT_EQ(w.stats.contacts, 0);
  ASSERT_EQ(w.pairs.size(), 1u) << "still listed";
  EXPECT_EQ(w.pairs[0].history.spring, Vec3{});
  EXPECT_EQ(w.pairs[0].history.roll, Vec3{});
  EXPECT_EQ(w.pairs[0].history.twist, 0);
  for (int k = 0; k < 100000 && !w.pairs.empty(); ++k) ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
  EXPECT_TRUE(w.pairs.empty()) << "dropped once the box left the wall";
  EXPECT_GT(w.bodies[0].position.z, r * (1 + settings.box_skin));
}

// Two spheres of radius 5 mm in a cube periodic on every axis, 6 cm wide,
// squeezed along y at a strain rate of -5/s: the cell's width shrinks by
// (1 - 5 dt) per step (deform_cell's H += dt L H), and the step that takes
// it to 4 reaches with the skin, 4 r (1 + box_skin), or less stops with
// CellTooShort on axis y (1).
TEST(StepTest, ACellShrunkBelowShortestPeriodReportsCellTooShort) {
  const Real r = 0.005, side = 0.06, rate = -5, dt = 1e-4;
  WorldSettings s;
  s.model = ContactModel::Hertz;
  s.gravity = {};
  for (int a = 0; a < 3; ++a) s.periodic.axes[a] = true;
  s.periodic.lo = {0, 0, 0};
  s.periodic.hi = {side, side, side};
  s.cell_control.mode[1] = CellMode::StrainRate;
  s.cell_control.value[1] = rate;
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"m", kRho, kE, kNu, 0.5, 0.3});
  b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {0.015, 0.03, 0.015}, .label = "one"});
  b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {0.045, 0.01, 0.045}, .label = "two"});
  World w = b.build();
  const Real shortest = 4 * r * (1 + s.box_skin);
  // The first n with side (1 + rate dt)^n <= shortest.
  const int expected = static_cast<int>(std::ceil(std::log(shortest / side) / std::log1p(rate * dt)));
  StepReport report;
  int steps = 0;
  while (steps < 10 * expected) {
    ++steps;
    report = step(w, dt);
    if (report.status != StepStatus::Ok) break;
    ASSERT_GT(cell_width(w.cell.now, 1), shortest) << "an Ok step leaves the cell wider than allowed";
  }
  ASSERT_EQ(report.status, StepStatus::CellTooShort);
  EXPECT_EQ(report.id_a, 1u) << "axis y";
  EXPECT_NEAR(report.shortest, shortest, 1e-15);
  EXPECT_LE(cell_width(w.cell.now, 1), shortest);
  EXPECT_NEAR(cell_width(w.cell.now, 0), side, 1e-15);
  EXPECT_NEAR(cell_width(w.cell.now, 2), side, 1e-15);
  EXPECT_NEAR(steps, expected, 1);
}

}  // namespace
}  // namespace gjkdem::dem
