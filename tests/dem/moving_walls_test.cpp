// Walls and fixed bodies with a prescribed motion (motion.hpp): the motion's
// velocities are the derivatives of its positions; bodies resting on a
// moving support follow it through friction (a conveyor, a turntable); a
// vibrating plate lifts a resting grain exactly when its peak acceleration
// A (2 pi f)^2 exceeds g; and the energy balance counts the walls' work, so
// that without damping or friction nothing shows as dissipated.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kGravity = 9.81;

TEST(MovingWalls, VelocitiesAreTheDerivativesOfThePositions) {
  PrescribedMotion m;
  m.center = {0.3, -0.2, 0.1};
  m.velocity = {0.05, 0, -0.02};
  m.angular_velocity = {0.4, -1.1, 2.0};
  m.amplitude = {0.001, 0.002, -0.003};
  m.frequency = 7;
  m.phase = 0.4;
  m.table_times = {0.1, 0.3, 0.35};
  m.table_displacements = {{0, 0, 0}, {0.01, -0.02, 0.005}, {0.012, -0.02, 0.0}};
  check_motion(m);
  const Vec3 given{0.5, 0.4, -0.3};
  const Real h = 1e-6;
  for (const Real t : {0.0, 0.05, 0.2, 0.32, 0.5, 2.0}) {  // before, inside and after the table
    const MotionFrame f = motion_frame(m, t);
    const Vec3 x = moved_point(f, m, given);
    const Vec3 numeric =
        (moved_point(motion_frame(m, t + h), m, given) - moved_point(motion_frame(m, t - h), m, given)) / (2 * h);
    EXPECT_LT(length(point_velocity(f, x) - numeric), 1e-6 * length(numeric)) << "t = " << t;
    // Rigid: distances from the moving centre are kept.
    EXPECT_NEAR(length(x - f.center), length(given - m.center), 1e-12) << "t = " << t;
  }
  // The table is held at its ends.
  PrescribedMotion table;
  table.table_times = m.table_times;
  table.table_displacements = m.table_displacements;
  EXPECT_EQ(motion_frame(table, -1.0).displacement, table.table_displacements.front());
  EXPECT_EQ(motion_frame(table, 5.0).displacement, table.table_displacements.back());
  EXPECT_EQ(motion_frame(table, 5.0).velocity, Vec3{});
}

TEST(MovingWalls, BadMotionsAreRefused) {
  const auto refused = [](const PrescribedMotion& m, const std::string& message) {
    WorldBuilder b;
    try {
      b.add_motion(m, "wall[0].motion");
    } catch (const BuildError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted a motion that should fail with: " << message;
  };
  refused({.velocity = {std::nan(""), 0, 0}}, "must be finite");
  refused({.frequency = -1}, "frequency must be >= 0");
  refused({.table_times = {0, 0}, .table_displacements = {{}, {}}}, "times must increase");
  refused({.table_times = {0, 1}, .table_displacements = {{}}}, "one displacement per time");

  WorldBuilder b;
  const std::uint32_t m = b.add_material({"steel", 7800, 2e11});
  EXPECT_THROW(b.add_plane({}, {0, 0, 1}, m, "floor", 1), BuildError);  // no motion 1 yet
  const std::uint32_t spin = b.add_motion({.angular_velocity = {0, 0, 1}}, "spin");
  EXPECT_THROW(b.add_body({.shape = {make_sphere(0.01), {}}, .material = m, .motion = spin, .label = "ball"}),
               BuildError);  // a moving body's motion comes from forces
}

// A cube resting on a support that moves: a belt along x (a plane sliding
// in itself, or a driven slab), or a turntable about z. Returns the world
// after `time`.
// (Rolling friction stops a cube rocking on its corners under the Hertz and
// linear laws, which see one contact point.)
World on_moving_support(ContactModel model, bool plane, const PrescribedMotion& motion, Vec3 at, Real time,
                        Vec3 velocity = {}) {
  WorldSettings settings;
  settings.model = model;
  settings.gravity = {0, 0, -kGravity};
  WorldBuilder b(settings);
  const std::uint32_t m = b.add_material({"grain", 2500, 1e7, 0.25, 0.3, 0.5, 0.1});
  const std::uint32_t belt = b.add_motion(motion, "belt");
  if (plane) {
    b.add_plane({}, {0, 0, 1}, m, "floor", belt);
  } else {
    b.add_body({.shape = {Shape{Box{{0.5, 0.5, 0.01}}}, {}}, .material = m, .position = {0, 0, -0.01},
                .fixed = true, .motion = belt, .label = "slab"});
  }
  const Real half = 0.005;
  b.add_body({.shape = {Shape{Box{{half, half, half}}}, {}}, .material = m, .position = at + Vec3{0, 0, half},
              .velocity = velocity, .label = "cube"});
  World w = b.build();
  RunState run = plan_run(time, critical_time_step(w), time);
  const RunOutcome outcome = dem::run(w, run, {});
  EXPECT_EQ(outcome.status, RunStatus::Completed) << outcome.error;
  return w;
}

TEST(MovingWalls, AGrainOnABeltTakesTheBeltsSpeed) {
  // Reached after speed / (mu g) = 0.04 s; under Hertz the cube, on one
  // contact point, then rocks about the belt's speed (3% at 0.1 s) until 0.2 s.
  const Real speed = 0.2;
  for (const ContactModel model : {ContactModel::Volume, ContactModel::Linear, ContactModel::Hertz})
    for (const bool plane : {true, false}) {
      const World w = on_moving_support(model, plane, {.velocity = {speed, 0, 0}}, {}, 0.3);
      const Body& cube = w.bodies.back();
      const std::string what = std::string(plane ? "plane" : "slab") + ", model " + std::to_string(int(model));
      EXPECT_NEAR(cube.velocity.x, speed, 0.01 * speed) << what;
      EXPECT_NEAR(cube.velocity.y, 0, 1e-3 * speed) << what;
      EXPECT_NEAR(cube.position.z, 0.005, 2e-4) << what << ": left the belt";
      if (!plane) {
        EXPECT_NEAR(w.bodies[0].position.x, speed * w.time, 1e-12) << "the slab is where its motion says";
      }
    }
}

TEST(MovingWalls, ABeltIsAFixedFloorSeenFromAMovingFrame) {
  // Galilean invariance: a cube dropped on a belt moving at v moves, at
  // every moment, as a cube thrown at -v onto a fixed floor, plus v.
  const Real speed = 0.2;
  for (const ContactModel model : {ContactModel::Volume, ContactModel::Linear, ContactModel::Hertz})
    for (const bool plane : {true, false})
      for (const Real time : {0.01, 0.03, 0.1}) {
        const World on_belt = on_moving_support(model, plane, {.velocity = {speed, 0, 0}}, {}, time);
        const World thrown = on_moving_support(model, plane, {}, {}, time, {-speed, 0, 0});
        const Body &a = on_belt.bodies.back(), &b = thrown.bodies.back();
        const std::string what = std::string(plane ? "plane" : "slab") + ", model " + std::to_string(int(model)) +
                                 ", t " + std::to_string(time);
        EXPECT_LT(length(a.velocity - b.velocity - Vec3{speed, 0, 0}), 1e-6 * speed) << what;  // round-off, grown by rocking
        EXPECT_LT(length(a.position - b.position - Vec3{speed * on_belt.time, 0, 0}), 1e-8) << what;
        EXPECT_LT(length(angular_velocity_of(on_belt, a) - angular_velocity_of(thrown, b)), 1e-6) << what;
      }
}

TEST(MovingWalls, AGrainOnATurntableTurnsWithIt) {
  // omega^2 r = 0.2 m/s^2, far below mu g: the cube is carried round.
  const Real omega = 2, r = 0.05;
  const World w = on_moving_support(ContactModel::Volume, false, {.angular_velocity = {0, 0, omega}}, {r, 0, 0}, 1.0);
  const Body& cube = w.bodies.back();
  const Vec3 radial{cube.position.x, cube.position.y, 0};
  EXPECT_NEAR(length(radial), r, 0.02 * r) << "slid off its circle";
  EXPECT_NEAR(std::atan2(cube.position.y, cube.position.x), omega * w.time, 0.05) << "lags the table";
  EXPECT_NEAR(length(cube.velocity - cross(Vec3{0, 0, omega}, radial)), 0, 0.02 * omega * r);
  const Quat turned = w.bodies[0].orientation;  // the table's slab turned by omega t about z
  EXPECT_NEAR(2 * std::atan2(turned.z, turned.w), omega * w.time, 1e-9);
}

// A ball resting on a plate that vibrates vertically at 10 Hz with peak
// acceleration gamma g, from the bottom of its stroke. The contact is stiff
// (natural frequency 620 Hz), so the ball leaves the plate where the plate's
// downward acceleration first exceeds g. Returns whether it ever left.
// Stiff linear contacts (2e4 N/m) under gravity, for balls on shaken plates.
WorldSettings shaker_settings() {
  WorldSettings settings;
  settings.model = ContactModel::Linear;
  settings.linear_stiffness = 2e4;
  settings.gravity = {0, 0, -kGravity};
  return settings;
}

bool ball_leaves_plate(Real gamma, bool plane) {
  WorldBuilder b(shaker_settings());
  const std::uint32_t m = b.add_material({"glass", 2500, 1e9, 0.25, 0.3, 0.5});
  const Real f = 10, w = 2 * kPi * f;
  const std::uint32_t shake =
      b.add_motion({.amplitude = {0, 0, gamma * kGravity / (w * w)}, .frequency = f, .phase = -kPi / 2}, "shake");
  if (plane) {
    b.add_plane({}, {0, 0, 1}, m, "plate", shake);
  } else {
    b.add_body({.shape = {Shape{Box{{0.05, 0.05, 0.01}}}, {}}, .material = m, .position = {0, 0, -0.01},
                .fixed = true, .motion = shake, .label = "plate"});
  }
  const Real radius = 0.005, mass = 2500 * 4.0 / 3.0 * kPi * radius * radius * radius;
  // At rest on the plate at its lowest point (resting overlap m g / k).
  b.accept_initial_overlaps();
  b.add_body({.shape = {make_sphere(radius), {}}, .material = m,
              .position = {0, 0, radius - gamma * kGravity / (w * w) - mass * kGravity / 2e4}, .label = "ball"});
  World world = b.build();
  struct Watch : RunObserver {
    bool left = false;
    void on_output(const World&, const RunState&) override {}
    void on_step(const World& w, const RunState&) override { left = left || w.stats.contacts == 0; }
  } watch;
  RunObserver* observers[] = {&watch};
  RunState run = plan_run(0.5, 2e-5, 0.5);
  const RunOutcome outcome = dem::run(world, run, observers);
  EXPECT_EQ(outcome.status, RunStatus::Completed) << outcome.error;
  return watch.left;
}

TEST(MovingWalls, AVibratingPlateLiftsAGrainWhenItsAccelerationExceedsG) {
  for (const bool plane : {true, false}) {
    EXPECT_FALSE(ball_leaves_plate(0.995, plane)) << (plane ? "plane" : "slab") << ": left below the threshold";
    EXPECT_TRUE(ball_leaves_plate(1.005, plane)) << (plane ? "plane" : "slab") << ": stayed above the threshold";
  }
}

TEST(MovingWalls, TheEnergyBalanceCountsTheWallsWork) {
  // An elastic ball (restitution 1, no friction) bouncing on a plate shaken
  // at 2.5 g: the plate pumps energy in and out; nothing is dissipated.
  WorldBuilder b(shaker_settings());
  const std::uint32_t m = b.add_material({"elastic", 2500, 1e9, 0.25, 1.0, 0.0});
  const Real f = 10, w = 2 * kPi * f, amplitude = 2.5 * kGravity / (w * w);
  b.add_plane({}, {0, 0, 1}, m, "plate", b.add_motion({.amplitude = {0, 0, amplitude}, .frequency = f}, "shake"));
  b.add_body({.shape = {make_sphere(0.005), {}}, .material = m, .position = {0, 0, 0.005 + amplitude + 1e-4},
              .label = "ball"});
  World world = b.build();
  struct Watch : RunObserver {
    Real most_work = 0, worst_dissipated = 0;
    Real initial = 0;
    void on_output(const World&, const RunState&) override {}
    void on_step(const World& w, const RunState& s) override {
      const EnergyBalance e = energy_balance(w, s.initial_energy);
      most_work = std::fmax(most_work, std::fabs(e.wall_work));
      worst_dissipated = std::fmax(worst_dissipated, std::fabs(e.dissipated));
      initial = s.initial_energy;
    }
  } watch;
  RunObserver* observers[] = {&watch};
  RunState run = plan_run(1.0, 1e-5, 1.0);
  const RunOutcome outcome = dem::run(world, run, observers);
  ASSERT_EQ(outcome.status, RunStatus::Completed) << outcome.error;
  EXPECT_GT(watch.most_work, 0.5 * std::fabs(watch.initial)) << "the plate did little work: no test";
  EXPECT_LT(watch.worst_dissipated, 1e-3 * watch.most_work);  // measured 2e-4: the O(dt^2) error
}

}  // namespace
}  // namespace gjkdem::dem
