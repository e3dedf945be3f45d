// The engine's step on the benchmark impacts of Chung and Ooi (2011), with
// the sphere handled as a convex shape (a point with a margin) through GJK:
// test 1 (elastic normal impact of a glass sphere on a rigid wall: peak
// overlap, peak force and duration against Hertz theory, within 2%) and
// test 2 (restitution out = in for e = 0.2 to 1, within 2%).
#include "gjkdem/dem/world.hpp"
#include "gjkdem/dem/rigid_rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gjkdem::dem {
namespace {

struct ImpactResult {
  double peak_overlap = 0, peak_force = 0, duration = 0, rebound = 0;
};

ImpactResult drop_on_wall(double restitution, double speed, ContactModel model = ContactModel::Hertz) {
  World w;
  w.model = model;
  w.linear_stiffness = 1e4;
  w.gravity = {};
  w.materials.push_back({"glass", 2500, 4.8e10, 0.2, restitution, 0});
  w.templates.push_back(make_template(make_sphere(0.01)));
  w.templates.push_back(make_template(Shape{Box{{0.05, 0.05, 0.01}}}));
  Body wall;
  wall.id = 1;
  wall.shape = 1;
  wall.fixed = true;
  wall.position = {0, 0, -0.01};  // top face at z = 0
  Body ball;
  ball.id = 2;
  ball.shape = 0;
  ball.position = {0, 0, 0.01 + 1e-7};  // just above the wall
  ball.velocity = {0, 0, -speed};
  w.bodies = {wall, ball};
  ImpactResult r;
  const double dt = 5e-8;
  bool touched = false;
  double t_start = 0;
  for (int k = 0; k < 200000; ++k) {
    step(w, dt);
    const Body& b = w.bodies[1];
    const double overlap = 0.01 - b.position.z;
    if (overlap > 0 && !touched) { touched = true; t_start = w.time; }
    if (touched && overlap <= 0) {
      r.duration = w.time - t_start;
      r.rebound = b.velocity.z / speed;
      break;
    }
    r.peak_overlap = std::fmax(r.peak_overlap, overlap);
    r.peak_force = std::fmax(r.peak_force, b.force.z);
  }
  return r;
}

TEST(World, ChungOoiTest1ElasticImpactMatchesHertz) {
  const double v = 0.2;
  const ImpactResult r = drop_on_wall(1.0, v);
  const double mass = 2500 * 4.0 / 3 * 3.14159265358979323846 * 1e-6;
  const double e_star = 1 / (2 * (1 - 0.2 * 0.2) / 4.8e10), r_star = 0.01;
  const double d_max = std::pow(15 * mass * v * v / (16 * e_star * std::sqrt(r_star)), 0.4);
  const double f_max = 4.0 / 3 * e_star * std::sqrt(r_star) * std::pow(d_max, 1.5);
  const double t_c = 2.868265 * std::pow(mass * mass / (r_star * e_star * e_star * v), 0.2);
  EXPECT_NEAR(r.peak_overlap / d_max, 1.0, 0.02);
  EXPECT_NEAR(r.peak_force / f_max, 1.0, 0.02);
  EXPECT_NEAR(r.duration / t_c, 1.0, 0.02);
  EXPECT_NEAR(r.rebound, 1.0, 0.02);
}

TEST(World, ChungOoiTest2RestitutionOutEqualsIn) {
  for (double e : {0.2, 0.5, 0.8, 1.0}) {
    EXPECT_NEAR(drop_on_wall(e, 3.9).rebound, e, 0.02 * e) << "Hertz, e = " << e;
    EXPECT_NEAR(drop_on_wall(e, 0.1, ContactModel::Linear).rebound, e, 0.02 * e) << "linear, e = " << e;
  }
}

// A sphere launched sliding on a floor: friction slows the slip and spins the
// sphere up until it rolls, at 5/7 of the launch speed (solid sphere: the
// contact-point angular momentum m v R + I w is kept, I = 2/5 m R^2),
// whatever mu is; the slip lasts 2 v0 / (7 mu g).
TEST(World, SlidingSphereEndsRollingAtFiveSevenths) {
  World w;
  w.model = ContactModel::Hertz;
  w.materials.push_back({"soft", 2500, 1e7, 0.25, 0.5, 0.3});
  w.templates.push_back(make_template(make_sphere(0.01)));
  w.templates.push_back(make_template(Shape{Box{{1, 1, 0.01}}}));
  Body floor;
  floor.id = 1;
  floor.shape = 1;
  floor.fixed = true;
  floor.position = {0, 0, -0.01};
  Body ball;
  ball.id = 2;
  ball.shape = 0;
  ball.position = {0, 0, 0.01 - 2.7e-5};  // about the static overlap under gravity
  ball.velocity = {1, 0, 0};
  w.bodies = {floor, ball};
  const double dt = 1e-5;
  double slip_end = -1;
  for (int k = 0; k < 30000; ++k) {
    step(w, dt);
    const Body& b = w.bodies[1];
    const Vec3 omega = angular_velocity(b.orientation, b.angular_momentum,
                                        w.templates[0].principal.moments * w.materials[0].density);
    const double slip = b.velocity.x - omega.y * 0.01;
    if (slip_end < 0 && slip < 1e-3) slip_end = w.time;
  }
  const Body& b = w.bodies[1];
  const Vec3 omega = angular_velocity(b.orientation, b.angular_momentum, w.templates[0].principal.moments * w.materials[0].density);
  EXPECT_NEAR(b.velocity.x, 5.0 / 7, 0.01 * 5 / 7);
  EXPECT_NEAR(omega.y * 0.01, b.velocity.x, 1e-3);
  EXPECT_NEAR(slip_end, 2 / (7 * 0.3 * 9.81), 0.03 * 2 / (7 * 0.3 * 9.81));
  EXPECT_NEAR(b.position.z, 0.01, 1e-4);  // still on the floor
  EXPECT_EQ(w.bodies[0].history.size(), 1u);  // the persistent contact keeps its spring
}

}  // namespace
}  // namespace gjkdem::dem
