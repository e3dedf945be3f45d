// The run loop (dem::run): observers see every output, a stop request stops
// between steps, and the physics guards of issue 11 catch what users call a
// blow-up (a time step above the stability limit, a body crossing its own
// size in a step, energy from nowhere, a non-finite state) and stop the run
// with a message, or warn and go on, as asked. Each case fails on the engine
// before the guards: those runs said "completed".
#include "gjkdem/dem/run.hpp"

#include <gtest/gtest.h>

#include <random>

#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "thrown_pair.hpp"

namespace gjkdem::dem {
namespace {

// A cube of the given half size dropped from just above a plane floor.
World cube_over_floor(Real half, const Vec3& velocity = {}, const Vec3& gravity = {0, 0, -9.81}) {
  WorldSettings s;
  s.gravity = gravity;
  WorldBuilder b(s);
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  b.add_plane({}, {0, 0, 1}, rock, "floor");
  b.add_body({.shape = {Shape{Box{{half, half, half}}}, {}}, .material = rock, .position = {0, 0, 1.5 * half},
              .velocity = velocity, .label = "cube"});
  return b.build();
}

struct Recorder : RunObserver {
  int outputs = 0, steps = 0;
  std::vector<std::string> warnings;
  void on_output(const World&, const RunState&) override { ++outputs; }
  void on_step(const World&, const RunState&) override { ++steps; }
  void on_warning(const World&, const RunState&, const std::string& m) override { warnings.push_back(m); }
};

TEST(Run, ObserversSeeEveryOutputAndStopRequestsStop) {
  World w = cube_over_floor(0.01);
  RunState run = plan_run(0.01, critical_time_step(w), 0.001);
  Recorder r;
  RunObserver* observers[] = {&r};
  EXPECT_EQ(dem::run(w, run, observers, [&] { return run.step == 7; }).status, RunStatus::Stopped);
  EXPECT_EQ(r.steps, 7);
  EXPECT_EQ(dem::run(w, run, observers).status, RunStatus::Completed);
  EXPECT_EQ(run.step, run.steps_total);
  EXPECT_EQ(static_cast<std::uint64_t>(r.outputs), run.outputs);
  EXPECT_GE(run.outputs, 11u);  // step 0, every 0.001 s, the end
}

// 1e-9 m flakes at a fixed dt of 2e-5 s (issue 11: 2.5e-9 J became 6.5e44 J).
TEST(Run, GuardStopsATimeStepAboveTheStabilityLimit) {
  World w = cube_over_floor(1e-9);
  RunState run = plan_run(0.01, 2e-5, 0.001);
  const RunOutcome o = dem::run(w, run, {});
  ASSERT_EQ(o.status, RunStatus::Failed);
  EXPECT_NE(o.error.find("above the stability limit"), std::string::npos) << o.error;
  EXPECT_EQ(run.step, 0u);  // refused before the first step
}

// A cube at 1,000 m/s with dt = "auto" tunnels through a floor (issue 11).
TEST(Run, GuardStopsABodyCrossingItsSizeInAStep) {
  World w = cube_over_floor(0.01, {0, 0, -1000});
  RunState run = plan_run(0.01, critical_time_step(w), 0.001);
  const RunOutcome o = dem::run(w, run, {});
  ASSERT_EQ(o.status, RunStatus::Failed);
  EXPECT_NE(o.error.find("of its size in one step"), std::string::npos) << o.error;
}

// Issue 32: a soft fast cube under the volume law sinks wholly below the
// floor between two outputs (no cut face: no force), which once completed
// the run silently; now the step fails, naming the body and the wall. The
// same cube on a stiff floor bounces (the guard does not fire on contact).
TEST(Run, ABodyWhollyBeyondAPlaneWallFailsTheRunNamingBoth) {
  const auto dropped = [](Real youngs, Real speed) {
    WorldBuilder b;
    const std::uint32_t m = b.add_material({"soft", 2500, youngs, 0.25, 0.5, 0.5});
    b.add_plane({}, {0, 0, 1}, m, "floor");
    b.add_body({.shape = {Shape{Box{{0.005, 0.005, 0.005}}}, {}}, .material = m, .position = {0, 0, 0.006},
                .velocity = {0, 0, -speed}, .label = "cube"});
    return b.build();
  };
  World soft = dropped(3e5, 20);
  RunState run = plan_run(0.01, 2e-5, 0.01);  // a stable step for the contact, long enough to pass through
  RunGuards no_travel;
  no_travel.max_travel = 1e9;  // the travel guard would stop it first: let the wall's own check see it
  const RunOutcome o = dem::run(soft, run, {}, {}, no_travel);
  ASSERT_EQ(o.status, RunStatus::Failed);
  EXPECT_NE(o.error.find("body 0 passed wholly through plane wall 0"), std::string::npos) << o.error;
  World stiff = dropped(1e9, 1);
  RunState bounce = plan_run(0.01, critical_time_step(stiff), 0.01);
  EXPECT_EQ(dem::run(stiff, bounce, {}).status, RunStatus::Completed);
}

// Issue 32: a tile thrown at a thin mesh floor passes its middle, where the
// contact turns and pushes it on through (the run once completed with the
// tile far below the floor). Now the step fails naming the tile and the
// piece, under both kinds of mesh piece (prism: volume law; triangle with a
// margin: Hertz). Thrown slowly, or sliding fast along the floor across the
// seam of its two triangles, the tile stays above and the run completes.
TEST(Run, ABodyThroughAMeshWallFailsTheRunNamingThePiece) {
  const auto thrown = [](ContactModel model, Real youngs, const Vec3& velocity, Real height) {
    WorldSettings settings;
    settings.model = model;
    WorldBuilder b(settings);
    const std::uint32_t m = b.add_material({"rock", 2500, youngs, 0.25, 0.5, 0.5});
    const Vec3 corners[4] = {{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}};
    const std::array<std::uint32_t, 3> triangles[2] = {{0, 1, 2}, {0, 2, 3}};
    b.add_mesh_walls(corners, triangles, 0.004, m, "floor");
    b.add_body({.shape = {Shape{Box{{0.001, 0.001, 0.0005}}}, {}}, .material = m, .position = {-0.02, 0.01, height},
                .velocity = velocity, .label = "tile"});
    return b.build();
  };
  // Volume law, 40 m/s on a soft floor: within the travel guard's bound.
  // Hertz holds faster tiles: at 300 m/s the travel guard must be lifted.
  struct Case {
    ContactModel model;
    Real youngs, speed, max_travel;
  };
  for (const Case& k : {Case{ContactModel::Volume, 1e6, 40, 0.5}, Case{ContactModel::Hertz, 1e7, 300, 1e9}}) {
    World fast = thrown(k.model, k.youngs, {0, 0, -k.speed}, 0.003);
    RunState run = plan_run(0.002, critical_time_step(fast), 0.002);
    RunGuards guards;
    guards.max_travel = k.max_travel;
    const RunOutcome o = dem::run(fast, run, {}, {}, guards);
    ASSERT_EQ(o.status, RunStatus::Failed) << name_of(k.model);
    EXPECT_NE(o.error.find("body 2 went through the mesh wall piece body"), std::string::npos) << o.error;
    for (const Vec3& v : {Vec3{0, 0, -1}, Vec3{30, 30, -0.1}}) {  // bouncing; sliding over the diagonal seam
      World slow = thrown(k.model, k.youngs, v, 0.0026);
      RunState calm = plan_run(0.002, critical_time_step(slow), 0.002);
      EXPECT_EQ(dem::run(slow, calm, {}).status, RunStatus::Completed) << name_of(k.model) << " " << v.x;
      EXPECT_GT(slow.bodies[2].position.z, 0.002) << name_of(k.model) << " " << v.x;  // still above the floor
    }
  }
}

// Issue 32: a plate driven at 500 m/s crosses a grain's size in one step;
// the travel guard, which skipped driven walls, now stops it.
TEST(Run, GuardStopsADrivenWallCrossingABodysSizeInAStep) {
  WorldBuilder b;
  const std::uint32_t m = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  PrescribedMotion push;
  push.velocity = {0, 0, 500};
  b.add_plane({0, 0, -0.5}, {0, 0, 1}, m, "piston", b.add_motion(push, "piston"));
  b.add_body({.shape = {Shape{Box{{0.005, 0.005, 0.005}}}, {}}, .material = m, .position = {0, 0, 0.5},
              .label = "cube"});
  World w = b.build();
  RunState run = plan_run(0.01, critical_time_step(w), 0.001);
  const RunOutcome o = dem::run(w, run, {});
  ASSERT_EQ(o.status, RunStatus::Failed);
  EXPECT_NE(o.error.find("driven plane wall 0 moves"), std::string::npos) << o.error;
  EXPECT_EQ(run.step, 0u);  // refused before the first step
}

TEST(Run, GuardSeesEnergyFromNowhere) {
  World w = cube_over_floor(0.01);
  RunState run = plan_run(0.01, critical_time_step(w), 0.001);
  run.outputs = 1;
  run.initial_energy = kinetic_energy(w) + potential_energy(w);
  EXPECT_EQ(check_guards(w, run, {}), "");
  w.bodies[0].velocity = {0.5, 0, 0};  // kinetic energy nothing supplied
  EXPECT_NE(check_guards(w, run, {}).find("energy grew from nowhere"), std::string::npos);
  // The advice says where it found the energy (issue 54): the fastest body.
  EXPECT_NE(check_guards(w, run, {}).find("body 0 moves fastest, at 0.5 m/s"), std::string::npos)
      << check_guards(w, run, {});
  RunGuards off;
  off.action = GuardAction::Off;
  EXPECT_EQ(check_guards(w, run, off), "");
}

// (Sideways, along the floor: a cube driven through the floor fails the
// step whatever the guards, ABodyWhollyBeyondAPlaneWallFailsTheRun.)
TEST(Run, WarnModeGoesOnAndWarnsOnce) {
  World w = cube_over_floor(0.01, {1000, 0, 0});
  RunState run = plan_run(0.001, critical_time_step(w), 0.0001);
  Recorder r;
  RunObserver* observers[] = {&r};
  RunGuards warn;
  warn.action = GuardAction::Warn;
  const RunOutcome o = dem::run(w, run, observers, {}, warn);
  EXPECT_NE(o.status, RunStatus::Stopped);
  EXPECT_GT(r.steps, 0);
  ASSERT_GE(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("of its size in one step"), std::string::npos);
}

// Issue 54, point 3: a press crushing soft fragments had one 0.7 mm into the
// floor without a word. A run warns, once, of a contact deeper than
// kLawRangeRel of its bodies' radius, under every law: a 2 cm cube settling
// on a floor of E = 3e3 Pa sinks 12% to 16% of its radius (warned, once,
// naming the pair), on E = 1e7 Pa far less (nothing said).
TEST(Run, ADeepContactIsWarnedOfOnce) {
  for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear, ContactModel::Volume})
    for (const Real youngs : {3e3, 1e7}) {
      WorldSettings s;
      s.model = model;
      WorldBuilder b(s);
      const std::uint32_t m = b.add_material({"soft", 2500, youngs, 0.25, 0.3, 0.5});
      b.add_plane({}, {0, 0, 1}, m, "floor");
      b.add_body({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .material = m, .position = {0, 0, 0.0101}});
      World w = b.build();
      RunState run = plan_run(0.3, critical_time_step(w), 0.01);
      Recorder r;
      RunObserver* observers[] = {&r};
      ASSERT_EQ(dem::run(w, run, observers).status, RunStatus::Completed) << name_of(model);
      if (youngs < 1e5) {
        EXPECT_EQ(r.warnings.size(), 1u) << name_of(model);
        if (r.warnings.empty()) continue;
        EXPECT_NE(r.warnings[0].find("contacts overlap deeply: plane wall 0 and body 0 by"), std::string::npos)
            << r.warnings[0];
      } else {
        EXPECT_TRUE(r.warnings.empty()) << name_of(model) << ": " << r.warnings[0];
      }
    }
}

// Gravity of 1e308 m/s^2 (issue 11: inf and nan were written to energy.csv).
TEST(Run, NonFiniteStateFailsTheRun) {
  World w = cube_over_floor(0.01, {}, {1e308, 0, 0});  // along the floor, not through it
  RunState run = plan_run(0.01, 1e-5, 0.001);
  RunGuards off;
  off.action = GuardAction::Off;  // only the finiteness check is left
  const RunOutcome o = dem::run(w, run, {}, {}, off);
  ASSERT_EQ(o.status, RunStatus::Failed);
  EXPECT_NE(o.error.find("not finite"), std::string::npos) << o.error;
}

// Issue 54, point 3: two rocks at +-50 m/s (volume law), two 1 cm boxes at
// +-40 m/s, a grain 1e4 times denser than the one it lands on: each went
// through the other and flew on, with nothing said. The class: pairs of
// convex bodies (spheres, boxes, rocks; alike, or one 1e4 times denser)
// thrown at each other at growing speeds under every law (the energy guard
// lifted) either bounce (each stays on its side) or stop the run naming the
// pair (or, faster, the travel guard names the body); never end on each
// other's side silently.
TEST(Run, NoTwoConvexBodiesPassThroughEachOtherSilently) {
  std::mt19937_64 rng(54);
  const Shape rock = random_polyhedron(20, 0.01, rng);
  for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear, ContactModel::Volume})
    for (const Shape& shape : {make_sphere(0.005), Shape{Box{{0.005, 0.005, 0.005}}}, rock})
      for (const Real density_ratio : {1.0, 1e4})
        for (const Real speed : {3.0, 30.0, 200.0}) {
          const ThrownPair pair{.model = model, .shape = {shape, {}}, .density_ratio = density_ratio, .speed = speed};
          EXPECT_EQ(thrown_pair_verdict(pair), "") << name_of(model) << " " << shape.core.index() << " ratio "
                                                          << density_ratio << " at " << speed << " m/s";
        }
}

}  // namespace
}  // namespace gjkdem::dem
