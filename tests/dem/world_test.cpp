// The engine's step on the benchmark impacts of Chung and Ooi (2011), with
// the sphere handled as a convex shape (a point with a margin) through GJK:
// test 1 (elastic normal impact of a glass sphere on a rigid wall: peak
// overlap, peak force and duration against Hertz theory, within 2%) and
// test 2 (restitution out = in for e = 0.2 to 1, within 2%).
#include "gjkdem/dem/world.hpp"
#include "gjkdem/dem/world_builder.hpp"

#include <algorithm>

#include <gtest/gtest.h>

#include <cmath>

namespace gjkdem::dem {
namespace {

struct ImpactResult {
  double peak_overlap = 0, peak_force = 0, duration = 0, rebound = 0;
};

ImpactResult drop_on_wall(double restitution, double speed, ContactModel model = ContactModel::Hertz) {
  WorldSettings settings;
  settings.model = model;
  settings.linear_stiffness = 1e4;
  settings.gravity = {};
  WorldBuilder builder(settings);
  const std::uint32_t glass = builder.add_material({"glass", 2500, 4.8e10, 0.2, restitution, 0});
  // Top face at z = 0; the ball just above it.
  builder.add_body({.shape = {Shape{Box{{0.05, 0.05, 0.01}}}, {}}, .material = glass, .position = {0, 0, -0.01},
                    .fixed = true, .label = "wall"});
  builder.add_body({.shape = {make_sphere(0.01), {}}, .material = glass, .position = {0, 0, 0.01 + 1e-7},
                    .velocity = {0, 0, -speed}, .label = "ball"});
  World w = builder.build();
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
  const double mass = 2500 * 4.0 / 3 * kPi * 1e-6;
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

// A cube of half-size 0.01 m on a large fixed floor under the volume law
// (k = 1e9 N/m^3 unless changed), resting at its static overlap.
World cube_on_floor(double restitution, double friction, const Vec3& gravity) {
  WorldSettings settings;
  settings.model = ContactModel::Volume;
  settings.gravity = gravity;
  settings.volume_stiffness = 1e9;
  WorldBuilder builder(settings);
  builder.accept_initial_overlaps();  // the cube starts at its resting overlap
  const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, restitution, friction});
  builder.add_body({.shape = {Shape{Box{{1, 1, 0.01}}}, {}}, .material = rock, .position = {0, 0, -0.01},
                    .fixed = true, .label = "floor"});
  builder.add_body({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .material = rock,
                    .position = {0, 0, 0.01 - 2500 * 8e-6 * -gravity.z / (1e9 * 4e-4)},  // resting overlap
                    .label = "cube"});
  return builder.build();
}

struct Landing {
  double peak = 0, duration = 0, rebound_speed = 0, spin = 0;
};

// Drops the cube of `w` (no gravity, undamped) at 0.5 m/s with the given
// orientation, its lowest point 1e-9 m above the floor (`height` = centre
// height at first touch), and records the first contact.
Landing land(World w, const Quat& orientation, const Vec3& offset, double height, double dt) {
  w.settings.gravity = {};
  Body& cube = w.bodies[1];
  cube.orientation = orientation;
  cube.position = offset + Vec3{0, 0, height + 1e-9};
  cube.velocity = {0, 0, -0.5};
  Landing r;
  double t_start = -1;
  for (int i = 0; i < 200000 && r.duration == 0; ++i) {
    step(w, dt);
    const double overlap = height - w.bodies[1].position.z;
    if (overlap > 0 && t_start < 0) t_start = w.time;
    if (t_start >= 0 && overlap <= 0) r.duration = w.time - t_start;
    r.peak = std::fmax(r.peak, overlap);
  }
  r.rebound_speed = w.bodies[1].velocity.z;
  r.spin = length(w.bodies[1].angular_momentum);
  return r;
}

// The volume law with a cube landing flat: V = A delta, so F = k A delta is a
// linear spring: contact time pi sqrt(m / (k A)), peak overlap v sqrt(m / (k A)),
// and the undamped law gives it back all its speed.
TEST(World, VolumeLawCubeLandingFlat) {
  const double m = 2500 * 8e-6, area = 4e-4, k = 1e9 * area;
  const double t_c = kPi * std::sqrt(m / k), d_max = 0.5 * std::sqrt(m / k);
  const Landing r = land(cube_on_floor(1.0, 0, {}), {}, {0.003, -0.002, 0}, 0.01, t_c / 2000);
  EXPECT_NEAR(r.duration / t_c, 1.0, 0.02);
  EXPECT_NEAR(r.peak / d_max, 1.0, 0.02);
  EXPECT_NEAR(r.rebound_speed, 0.5, 0.005);
  // Landing flat, the force acts through the face centre: no spin.
  EXPECT_LT(r.spin, 1e-12);
}

// Landing on an edge (the cube turned 45 degrees about x): the overlap is a
// prism of cross-section delta^2, V = L delta^2, so m x'' = -k L x^2. Energy
// gives delta_max = (3 m v^2 / (2 k L))^(1/3) and the contact lasts
// 2 delta_max / v * B(1/3, 1/2) / 3 = 2.80436 delta_max / v.
TEST(World, VolumeLawCubeLandingOnAnEdge) {
  const double m = 2500 * 8e-6, kl = 1e9 * 0.02, v = 0.5;
  const double d_max = std::cbrt(3 * m * v * v / (2 * kl)), t_c = 2.80436 * d_max / v;
  const Landing r = land(cube_on_floor(1.0, 0, {}), quat_from_axis_angle({1, 0, 0}, kPi / 4), {},
                         0.01 * std::sqrt(2.0), t_c / 4000);
  EXPECT_NEAR(r.duration / t_c, 1.0, 0.02);
  EXPECT_NEAR(r.peak / d_max, 1.0, 0.02);
  EXPECT_NEAR(r.rebound_speed, v, 0.01 * v);
}

// Landing on a vertex (the body diagonal vertical): the overlap is a corner
// tetrahedron with edges sqrt(3) delta, V = (sqrt(3)/2) delta^3, so
// m x'' = -c x^3 with c = k sqrt(3)/2: delta_max = (2 m v^2 / c)^(1/4) and the
// contact lasts 2 delta_max / v * 1.311029 (the integral of (1 - u^4)^(-1/2)).
TEST(World, VolumeLawCubeLandingOnAVertex) {
  World w = cube_on_floor(1.0, 0, {});
  w.settings.volume_stiffness = 1e11;
  const double m = 2500 * 8e-6, c = 1e11 * std::sqrt(3.0) / 2, v = 0.5;
  const double d_max = std::pow(2 * m * v * v / c, 0.25), t_c = 2 * 1.311029 * d_max / v;
  const Vec3 diag = normalized(Vec3{-1, -1, -1});  // the corner (-1,-1,-1) points down
  const Quat corner_down = quat_from_axis_angle(normalized(cross(diag, {0, 0, -1})), std::acos(dot(diag, {0, 0, -1})));
  const Landing r = land(w, corner_down, {}, 0.01 * std::sqrt(3.0), t_c / 4000);
  EXPECT_NEAR(r.duration / t_c, 1.0, 0.02);
  EXPECT_NEAR(r.peak / d_max, 1.0, 0.02);
  EXPECT_NEAR(r.rebound_speed, v, 0.01 * v);
}

TEST(World, VolumeLawDampingGivesTheRestitution) {
  for (double e : {0.3, 0.7}) {
    World w = cube_on_floor(e, 0, {});
    w.bodies[1].position.z = 0.01 + 1e-9;
    w.bodies[1].velocity = {0, 0, -0.5};
    for (int i = 0; i < 20000 && !(w.bodies[1].position.z > 0.01 + 1e-6); ++i) step(w, 1e-6);
    EXPECT_NEAR(w.bodies[1].velocity.z / 0.5, e, 0.02 * e) << "e = " << e;
  }
}

// A cube on a floor tilted by theta (gravity tilted instead): it stays put
// when tan(theta) < mu and slides with g (sin theta - mu cos theta) otherwise.
TEST(World, CubeOnInclineSticksOrSlides) {
  const double g = 9.81, theta = 20 * kPi / 180;
  const Vec3 gravity{g * std::sin(theta), 0, -g * std::cos(theta)};
  World stick = cube_on_floor(0.3, 0.5, gravity);
  for (int i = 0; i < 50000; ++i) step(stick, 2e-5);  // 1 s
  EXPECT_LT(std::fabs(stick.bodies[1].position.x), 1e-3 * 0.02);
  EXPECT_NEAR(stick.bodies[1].position.z, 0.01, 1e-5);  // resting on its face, not sunk or tipped
  EXPECT_NEAR(rotate(stick.bodies[1].orientation, {0, 0, 1}).z, 1.0, 1e-6);
  World slide = cube_on_floor(0.3, 0.2, gravity);
  for (int i = 0; i < 10000; ++i) step(slide, 2e-5);  // 0.2 s to settle into sliding
  const double x0 = slide.bodies[1].position.x, v0 = slide.bodies[1].velocity.x;
  for (int i = 0; i < 25000; ++i) step(slide, 2e-5);  // 0.5 s measured
  const double t = 0.5, a = 2 * (slide.bodies[1].position.x - x0 - v0 * t) / (t * t);
  EXPECT_NEAR(a / (g * (std::sin(theta) - 0.2 * std::cos(theta))), 1.0, 0.03);
  EXPECT_GT(slide.bodies[1].position.x, 0.1);  // it really slid (about 0.25 m)
  EXPECT_NEAR(slide.bodies[1].position.z, 0.01, 1e-5);
}

// A sphere launched sliding on a floor: friction slows the slip and spins the
// sphere up until it rolls, at 5/7 of the launch speed (solid sphere: the
// contact-point angular momentum m v R + I w is kept, I = 2/5 m R^2),
// whatever mu is; the slip lasts 2 v0 / (7 mu g).
TEST(World, SlidingSphereEndsRollingAtFiveSevenths) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder builder(settings);
  builder.accept_initial_overlaps();  // the ball starts at about its resting overlap
  const std::uint32_t soft = builder.add_material({"soft", 2500, 1e7, 0.25, 0.5, 0.3});
  builder.add_body({.shape = {Shape{Box{{1, 1, 0.01}}}, {}}, .material = soft, .position = {0, 0, -0.01},
                    .fixed = true, .label = "floor"});
  builder.add_body({.shape = {make_sphere(0.01), {}}, .material = soft,
                    .position = {0, 0, 0.01 - 2.7e-5},  // about the static overlap under gravity
                    .velocity = {1, 0, 0}, .label = "ball"});
  World w = builder.build();
  const double dt = 1e-5;
  double slip_end = -1;
  for (int k = 0; k < 30000; ++k) {
    step(w, dt);
    const Body& b = w.bodies[1];
    const Vec3 omega = angular_velocity_of(w, b);
    const double slip = b.velocity.x - omega.y * 0.01;
    if (slip_end < 0 && slip < 1e-3) slip_end = w.time;
  }
  const Body& b = w.bodies[1];
  const Vec3 omega = angular_velocity_of(w, b);
  EXPECT_NEAR(b.velocity.x, 5.0 / 7, 0.01 * 5 / 7);
  EXPECT_NEAR(omega.y * 0.01, b.velocity.x, 1e-3);
  EXPECT_NEAR(slip_end, 2 / (7 * 0.3 * 9.81), 0.03 * 2 / (7 * 0.3 * 9.81));
  EXPECT_NEAR(b.position.z, 0.01, 1e-4);  // still on the floor
  // The persistent contact keeps its spring.
  EXPECT_EQ(std::count_if(w.pairs.begin(), w.pairs.end(),
                          [](const PairState& p) { return length(p.history.spring) > 0; }),
            1);
}

}  // namespace
}  // namespace gjkdem::dem
