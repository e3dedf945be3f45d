// Loads from outside the engine (issue 53): Body::applied_force and
// applied_torque, set by a step listener (run.hpp) before the forces.
// - a constant applied force on a free body is uniform acceleration (the
//   integrator is exact for it), and its work is the kinetic energy gained;
//   a constant applied torque on a sphere spins it up as tau t, its work the
//   energy of the spin; the energy balance dissipates nothing in either;
// - a drag listener (F = -beta v, every step) brings a falling grain to its
//   terminal velocity m g / beta to 1e-6; drag's work is what the grain lost;
//   the energy guard stays quiet where the listener pushes energy in;
// - a bed with drag on 1 and 2 threads, and stopped and resumed, gives the
//   same bits; a listener called every 5 steps is called at steps 0, 5, 10;
// - a listener's exception fails the run with its message; loads a listener
//   sets at the start of a world run again act in its first kick;
// - loads given to the builder (BodyDef::given) are placed as given and turn
//   the world's applied loads on; a channel that is not given, one given
//   twice, a value that is not finite or a load on a fixed body is refused;
// - a world without applied loads (World::applied_loads off) has no
//   applied work, whatever its bodies' fields hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>

#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

// F = -beta v on every moving body it owns.
struct Drag : StepListener {
  explicit Drag(Real drag, std::uint64_t steps = 1) : beta(drag), each(steps) {}
  std::uint64_t every() const override { return each; }
  void before_forces(OwnedBodies bodies, const RunState& state) override {
    calls.push_back(state.step);
    for (std::size_t i = 0; i < bodies.world.bodies.size(); ++i)
      if (bodies.owns(i)) bodies.world.bodies[i].applied_force = bodies.world.bodies[i].velocity * -beta;
  }
  Real beta;
  std::uint64_t each;
  std::vector<std::uint64_t> calls;
};

// One body of `shape` alone, gravity `g`.
World lone(const Shape& shape, Vec3 g = {}) {
  WorldSettings s;
  s.gravity = g;
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"m", 2000, 1e7, 0.3, 0.5, 0.4});
  b.add_body({.shape = {shape, {}}, .material = m, .position = {0, 0, 1}, .label = "grain"});
  World w = b.build();
  w.applied_loads = true;
  return w;
}

TEST(AppliedLoads, AConstantForceIsUniformAccelerationAndItsWorkTheEnergyGained) {
  World w = lone(Shape{Box{{0.01, 0.02, 0.03}}});
  Body& b = w.bodies[0];
  b.applied_force = {0.3, -0.2, 0.1};
  const Real m = mass_of(w, b), dt = 1e-3;
  const int steps = 1000;
  for (int k = 0; k < steps; ++k) ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
  const Real t = steps * dt;
  const Vec3 a = w.bodies[0].applied_force / m;
  EXPECT_NEAR(length(w.bodies[0].velocity - a * t), 0, 1e-12 * length(a * t));
  EXPECT_NEAR(length(w.bodies[0].position - Vec3{0, 0, 1} - a * (t * t / 2)), 0, 1e-10 * length(a) * t * t);
  const Real ke = kinetic_energy(w);
  EXPECT_NEAR(w.bodies[0].applied_work, ke, 1e-12 * ke);
  EXPECT_NEAR(energy_balance(w, 0).dissipated, 0, 1e-12 * ke);
  EXPECT_NEAR(energy_balance(w, 0).applied_work, ke, 1e-12 * ke);
}

TEST(AppliedLoads, AConstantTorqueSpinsASphereUpAndItsWorkIsTheSpinsEnergy) {
  World w = lone(make_sphere(0.02));
  w.bodies[0].applied_torque = {0, 0, 2e-4};
  const Real dt = 1e-3;
  for (int k = 0; k < 500; ++k) ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
  EXPECT_NEAR(w.bodies[0].angular_momentum.z, 2e-4 * 0.5, 1e-15);
  const Real ke = kinetic_energy(w);
  ASSERT_GT(ke, 0);
  EXPECT_NEAR(w.bodies[0].applied_work, ke, 1e-12 * ke);
  EXPECT_NEAR(energy_balance(w, 0).dissipated, 0, 1e-12 * ke);
}

TEST(AppliedLoads, ADragListenerGivesTheTerminalVelocityAndItsWorkIsWhatTheGrainLost) {
  World w = lone(Shape{Box{{0.01, 0.01, 0.01}}}, {0, 0, -9.81});
  w.applied_loads = false;  // a run with a listener turns them on
  const Real m = mass_of(w, w.bodies[0]);
  const Real beta = m / 0.01;  // 10 ms to relax; 0.3 s is 30 of them
  RunState state = plan_run(0.3, 1e-4, 0.1);
  Drag drag(beta);
  StepListener* listeners[] = {&drag};
  ASSERT_EQ(run(w, state, {}, {}, {}, listeners).status, RunStatus::Completed);
  EXPECT_TRUE(w.applied_loads);
  const Real terminal = m * 9.81 / beta;
  EXPECT_NEAR(w.bodies[0].velocity.z, -terminal, 1e-6 * terminal);
  // Falling h at constant speed, drag took m g h; all it took is the work.
  const EnergyBalance e = energy_balance(w, state.initial_energy);
  EXPECT_LT(e.applied_work, 0);
  EXPECT_NEAR(e.dissipated, 0, 1e-5 * -e.applied_work);  // the integrator's O(dt^2)
  EXPECT_EQ(drag.calls.size(), state.steps_total + 1);  // step 0, then before every step's forces
}

TEST(AppliedLoads, ALoadThatPushesEnergyInIsNotEnergyFromNowhere) {
  // Lifted at 3 g: its kinetic and potential energy grow far past the start's.
  World w = lone(make_sphere(0.01), {0, 0, -9.81});
  struct Lift : StepListener {
    void before_forces(OwnedBodies bodies, const RunState&) override {
      Body& b = bodies.world.bodies[0];
      b.applied_force = Vec3{0, 0, 3 * 9.81} * mass_of(bodies.world, b);
    }
  } lift;
  StepListener* listeners[] = {&lift};
  RunState state = plan_run(0.5, 1e-4, 0.01);
  const RunOutcome out = run(w, state, {}, {}, {}, listeners);
  EXPECT_EQ(out.status, RunStatus::Completed) << out.error;
  EXPECT_GT(w.bodies[0].velocity.z, 9);
}

// A bed of polyhedra settling under drag on a floor.
World dragged_bed(int threads) {
  WorldSettings s;
  s.gravity = {0, 0, -9.81};
  s.threads = threads;
  WorldBuilder b(s);
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e6, 0.25, 0.5, 0.6});
  b.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor");
  std::mt19937_64 rng(53);
  for (int i = 0; i < 40; ++i) {
    const Vec3 p{0.025 * (i % 4), 0.025 * ((i / 4) % 4), 0.02 + 0.025 * (i / 16)};
    b.add_body({.shape = {random_polyhedron(10, 0.01, rng), {}}, .material = rock, .position = p,
                .velocity = {0.1 * std::sin(i), 0.1 * std::cos(i), 0}});
  }
  return b.build();
}

bool same_bodies(const World& x, const World& y) {
  return x.bodies.size() == y.bodies.size() &&
         std::memcmp(x.bodies.data(), y.bodies.data(), x.bodies.size() * sizeof(Body)) == 0;
}

TEST(AppliedLoads, DragGivesTheSameBitsOnAnyThreadCountAndAcrossAResume) {
  const RunState plan = plan_run(0.05, 2e-5, 0.01);
  World one = dragged_bed(1), two = dragged_bed(2), first = dragged_bed(1);
  Drag drag(0.05, 3);
  StepListener* listeners[] = {&drag};
  RunState a = plan, b = plan, c = plan;
  ASSERT_EQ(run(one, a, {}, {}, {}, listeners).status, RunStatus::Completed);
  ASSERT_EQ(run(two, b, {}, {}, {}, listeners).status, RunStatus::Completed);
  EXPECT_TRUE(same_bodies(one, two));
  // Stopped at a step the listener is not due, then again where it is.
  ASSERT_EQ(run(first, c, {}, [&] { return c.step == 1001; }, {}, listeners).status, RunStatus::Stopped);
  ASSERT_EQ(run(first, c, {}, [&] { return c.step == 1500; }, {}, listeners).status, RunStatus::Stopped);
  ASSERT_EQ(run(first, c, {}, {}, {}, listeners).status, RunStatus::Completed);
  EXPECT_TRUE(same_bodies(one, first));
  Real work = 0;
  for (const Body& body : one.bodies) work += body.applied_work;
  EXPECT_LT(work, 0);  // drag took energy out
}

TEST(AppliedLoads, ALoadSetAtTheStartActsInTheFirstKickOfAWorldRunAgain) {
  World w = lone(make_sphere(0.01));
  RunState before = plan_run(1e-3, 1e-4, 1e-4);
  ASSERT_EQ(run(w, before, {}).status, RunStatus::Completed);  // its forces are current now
  ASSERT_TRUE(w.forces_current);
  struct Push : StepListener {
    void before_forces(OwnedBodies bodies, const RunState&) override { bodies.world.bodies[0].applied_force = {0.01, 0, 0}; }
  } push;
  StepListener* listeners[] = {&push};
  RunState again = plan_run(1e-2, 1e-4, 1e-3);
  ASSERT_EQ(run(w, again, {}, {}, {}, listeners).status, RunStatus::Completed);
  const Real m = mass_of(w, w.bodies[0]), v = 0.01 / m * 1e-2;  // every kick of the 100 steps pushed
  EXPECT_NEAR(w.bodies[0].velocity.x, v, 1e-12 * v);
  EXPECT_NEAR(w.bodies[0].applied_work, 0.5 * m * v * v, 1e-12 * m * v * v);
}

TEST(AppliedLoads, AListenerIsCalledEveryItsSteps) {
  World w = lone(make_sphere(0.01));
  Drag drag(0.1, 5);
  StepListener* listeners[] = {&drag};
  RunState state = plan_run(12e-4, 1e-4, 1e-4);
  ASSERT_EQ(run(w, state, {}, {}, {}, listeners).status, RunStatus::Completed);
  EXPECT_EQ(drag.calls, (std::vector<std::uint64_t>{0, 4, 9}));  // before the forces at steps 0, 5, 10
}

TEST(AppliedLoads, AListenersExceptionFailsTheRunWithItsMessage) {
  World w = lone(make_sphere(0.01));
  struct Broken : StepListener {
    void before_forces(OwnedBodies, const RunState& state) override {
      if (state.step == 3) throw std::runtime_error("the coupling lost its peer");
    }
  } broken;
  StepListener* listeners[] = {&broken};
  RunState state = plan_run(1e-3, 1e-4, 1e-4);
  const RunOutcome out = run(w, state, {}, {}, {}, listeners);
  EXPECT_EQ(out.status, RunStatus::Failed);
  EXPECT_EQ(out.error, "the coupling lost its peer");
  EXPECT_EQ(state.step, 3u);
}

TEST(AppliedLoads, AWorldWithoutAppliedLoadsIgnoresTheFields) {
  World w = lone(make_sphere(0.01));
  w.applied_loads = false;
  w.bodies[0].applied_force = {1, 0, 0};
  for (int k = 0; k < 10; ++k) ASSERT_EQ(step(w, 1e-3).status, StepStatus::Ok);
  EXPECT_EQ(w.bodies[0].velocity, Vec3{});
  EXPECT_EQ(w.bodies[0].applied_work, 0);
  EXPECT_EQ(energy_balance(w, 0).applied_work, 0);
}

TEST(AppliedLoads, GivenLoadsArePlacedAsGivenAndBadOnesRefused) {
  const BodyChannel* force = find_body_channel("applied_force");
  const BodyChannel* torque = find_body_channel("applied_torque");
  ASSERT_TRUE(force && torque);
  const auto build = [&](std::vector<GivenChannel> given, bool fixed = false) {
    WorldBuilder b{WorldSettings{}};
    const std::uint32_t m = b.add_material({"m", 2000, 1e7, 0.3, 0.5, 0.4});
    b.add_body({.shape = {make_sphere(0.1), {}}, .material = m, .given = std::move(given), .fixed = fixed,
                .label = "grain"});
    return b.build();
  };
  const World w = build({{force, {1, -2, 3}}, {torque, {0, 0, 0.5}}});
  EXPECT_TRUE(w.applied_loads);
  EXPECT_EQ(w.bodies[0].applied_force, (Vec3{1, -2, 3}));
  EXPECT_EQ(w.bodies[0].applied_torque, (Vec3{0, 0, 0.5}));
  EXPECT_FALSE(build({{force, {0, 0, 0}}}).applied_loads);  // a zero load is none
  EXPECT_FALSE(build({{force, {0, 0, 0}}}, true).applied_loads);  // nor on a fixed body
  const auto refused = [&](std::vector<GivenChannel> given, bool fixed, const std::string& says) {
    try {
      build(std::move(given), fixed);
      ADD_FAILURE() << "accepted; should say " << says;
    } catch (const BuildError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused({{find_body_channel("position"), {1, 2, 3}}}, false, "'position' is not one a body is given");
  refused({{nullptr, {}}}, false, "a null channel");
  refused({{force, {1, 0, 0}}, {force, {2, 0, 0}}}, false, "applied_force is given twice");
  refused({{torque, {0, std::nan(""), 0}}}, false, "applied_torque must be finite");
  refused({{torque, {0, 1, 0}}}, true, "a fixed body takes no applied load (applied_torque");
}

}  // namespace
}  // namespace gjkdem::dem
