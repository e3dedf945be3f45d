// Rolling friction (Ai et al. 2011, type C): a ball rolling on a flat
// support stops where the analysis says. With a constant resisting moment
// M = mu_r R F_n and rolling without slip, m a = -F_t and I alpha = F_t R - M
// give a = -M / (R m (1 + I / (m R^2))) = -5/7 mu_r g for a solid sphere, so
// from v0 it rolls d = v0^2 / (2 |a|) = 7 v0^2 / (10 mu_r g). Without rolling
// friction nothing damps rolling without slip: the ball keeps its speed.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <tuple>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kRadius = 0.01, kSpeed = 0.1, kGravity = 9.81;

struct Rolled {
  Real distance = 0, speed = 0;
};

// A ball set rolling at kSpeed along x on a plane or on a fixed box, run for `time`.
Rolled roll_ball(ContactModel model, bool on_plane, Real rolling_friction, Real time) {
  WorldSettings settings;
  settings.model = model;
  settings.gravity = {0, 0, -kGravity};
  WorldBuilder b(settings);
  Material rubber{"ball", 1200, 1e7, 0.3, 0.5, 0.8};
  rubber.rolling_friction = rolling_friction;
  const std::uint32_t m = b.add_material(rubber);
  if (on_plane) {
    b.add_plane({}, {0, 0, 1}, m, "floor");
  } else {
    b.add_body({.shape = {Shape{Box{{0.2, 0.05, 0.01}}}, {}}, .material = m, .position = {0, 0, -0.01},
                .fixed = true, .label = "slab"});
  }
  b.add_body({.shape = {make_sphere(kRadius), {}}, .material = m, .position = {-0.1, 0, kRadius},
              .velocity = {kSpeed, 0, 0}, .angular_velocity = {0, kSpeed / kRadius, 0}, .label = "ball"});
  World w = b.build();
  RunState run = plan_run(time, critical_time_step(w), time);
  const RunOutcome outcome = dem::run(w, run, {});
  EXPECT_EQ(outcome.status, RunStatus::Completed) << outcome.error;
  const Body& ball = w.bodies.back();
  EXPECT_NEAR(ball.position.z, kRadius, 5e-3 * kRadius) << "left the support";  // resting overlap: 1.7e-3 R
  return {ball.position.x + 0.1, length(ball.velocity)};
}

TEST(RollingResistance, ABallStopsWhereTheAnalysisSays) {
  for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear})
    for (const bool on_plane : {true, false})
      for (const Real mu_r : {0.05, 0.2}) {
        const Real expected = 7 * kSpeed * kSpeed / (10 * mu_r * kGravity);  // 14.3 mm and 3.6 mm
        const Rolled r = roll_ball(model, on_plane, mu_r, 0.5);  // stops within 0.29 s
        const std::string what = std::string(model == ContactModel::Hertz ? "Hertz" : "linear") +
                                 (on_plane ? " on a plane" : " on a fixed box") + ", mu_r " + std::to_string(mu_r);
        EXPECT_NEAR(r.distance, expected, 0.015 * expected) << what;
        EXPECT_LT(r.speed, 1e-4) << what << ": still moving";
      }
}

// Issue 32: rolling_friction = 1000 created energy (the dissipation went
// negative) at the normal contact's time step: the rolling spring, 2.25 k
// (mu_r R)^2 on the ball's inertia, rings 2.37 mu_r times as fast. The
// critical step now counts it; the step that ignored it is refused by the
// stability guard, and the shorter one keeps the energy balance.
TEST(RollingResistance, AHugeRollingFrictionTakesAShorterStepNotEnergy) {
  for (const ContactModel model : {ContactModel::Hertz, ContactModel::Linear}) {
    const auto ball = [&](Real mu_r) {
      WorldSettings settings;
      settings.model = model;
      settings.gravity = {0, 0, -kGravity};
      WorldBuilder b(settings);
      Material rubber{"ball", 1200, 1e7, 0.3, 0.5, 0.8};
      rubber.rolling_friction = mu_r;
      const std::uint32_t m = b.add_material(rubber);
      b.add_plane({}, {0, 0, 1}, m, "floor");
      b.add_body({.shape = {make_sphere(kRadius), {}}, .material = m, .position = {-0.1, 0, kRadius * 0.999},
                  .velocity = {kSpeed, 0, 0}, .label = "ball"});  // sliding: the rolling spring winds up
      b.accept_initial_overlaps();
      return b.build();
    };
    const std::string what = model == ContactModel::Hertz ? "Hertz" : "linear";
    const Real plain = critical_time_step(ball(0));
    World w = ball(1000);
    const Real dt = critical_time_step(w);
    EXPECT_LT(dt, plain / 1000) << what;  // 2.37 mu_r against a wall
    RunState too_long = plan_run(2e-4, plain, 2e-4);
    const RunOutcome refused = dem::run(w, too_long, {});
    EXPECT_EQ(refused.status, RunStatus::Failed) << what;
    EXPECT_NE(refused.error.find("above the stability limit"), std::string::npos) << what << ": " << refused.error;
    World again = ball(1000);
    RunState run = plan_run(2e-4, dt, 2e-4);
    ASSERT_EQ(dem::run(again, run, {}).status, RunStatus::Completed) << what;
    const EnergyBalance e = energy_balance(again, run.initial_energy);
    EXPECT_GE(e.dissipated, -1e-9 * run.initial_energy) << what << ": energy from nowhere";
  }
}

TEST(RollingResistance, WithoutItABallRollsOn) {
  for (const bool on_plane : {true, false}) {
    const Rolled r = roll_ball(ContactModel::Hertz, on_plane, 0, 0.3);
    EXPECT_NEAR(r.speed, kSpeed, 0.01 * kSpeed) << (on_plane ? "plane" : "box");
    EXPECT_NEAR(r.distance, kSpeed * 0.3, 0.01 * kSpeed * 0.3) << (on_plane ? "plane" : "box");
  }
}

TEST(RollingResistance, MaterialsOutOfRangeAreRefused) {
  for (const auto& [mu_r, eta, message] :
       {std::tuple{-0.1, 0.3, "rolling_friction must be >= 0"},
        std::tuple{std::numeric_limits<Real>::infinity(), 0.3, "rolling_friction must be finite"},
        std::tuple{0.1, 1.5, "rolling_damping must lie in [0, 1]"}}) {
    WorldBuilder b;
    Material m{"sand", 2600, 1e7};
    m.rolling_friction = mu_r;
    m.rolling_damping = eta;
    try {
      b.add_material(m);
      ADD_FAILURE() << message << ": accepted";
    } catch (const BuildError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("material 'sand': ") + message);
    }
  }
}

}  // namespace
}  // namespace gjkdem::dem
