// Periodic boundaries (periodic.hpp): a body leaving the cell enters on the
// other side with its motion; two bodies colliding across the boundary come
// out as the same pair colliding in the middle of a world without
// boundaries (translation invariance); a bed on a floor, periodic across,
// keeps its grains in the cell, touches across the boundary, and continues
// from a checkpoint with the same bits; inflows see bodies across the
// boundary; cells too short are refused.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "dem/beds.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

WorldSettings periodic_x(Real lo, Real hi) {
  WorldSettings s;
  s.model = ContactModel::Hertz;
  s.gravity = {};
  s.periodic.axes[0] = true;
  s.periodic.lo = {lo, 0, 0};
  s.periodic.hi = {hi, 0, 0};
  return s;
}

TEST(Periodic, ABodyLeavingEntersOnTheOtherSide) {
  WorldBuilder b(periodic_x(0, 0.1));
  const std::uint32_t m = b.add_material({"glass", 2500, 1e7});
  b.add_body({.shape = {make_sphere(0.005), {}}, .material = m, .position = {0.09, 0, 0}, .velocity = {1, 0.2, 0},
              .label = "ball"});
  World w = b.build();
  for (int k = 0; k < 300; ++k) step(w, 1e-4);  // 3 cm: across x = 0.1
  const Body& ball = w.bodies[0];
  EXPECT_NEAR(ball.position.x, 0.09 + 0.03 - 0.1, 1e-12);
  EXPECT_NEAR(ball.position.y, 0.006, 1e-12);
  EXPECT_EQ(ball.velocity, (Vec3{1, 0.2, 0}));
}

// Two balls meeting head-on at `meet` (x), moving at +-v; returns their
// velocities after the collision.
std::pair<Vec3, Vec3> collide_at(Real meet, bool periodic) {
  WorldSettings s = periodic ? periodic_x(0, 0.1) : periodic_x(0, 0);
  if (!periodic) s.periodic = {};
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"glass", 2500, 1e7, 0.25, 0.6, 0.3});
  const Real r = 0.005, gap = 0.001;
  // Off-centre (y) so that friction and spin take part too.
  b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {meet - r - gap, 0.002, 0},
              .velocity = {0.5, 0, 0}, .label = "left"});
  b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = {meet + r + gap, -0.002, 0},
              .velocity = {-0.5, 0, 0}, .label = "right"});
  World w = b.build();
  for (int k = 0; k < 400; ++k) step(w, 1e-5);
  // Bodies are in id order; "left" was added first.
  return {w.bodies[0].velocity, w.bodies[1].velocity};
}

TEST(Periodic, ACollisionAcrossTheBoundaryIsACollisionInTheMiddle) {
  const auto [left_middle, right_middle] = collide_at(0.05, false);
  const auto [left_edge, right_edge] = collide_at(0.1, true);  // they meet at x = 0.1 = 0
  EXPECT_LT(left_middle.x, 0.4) << "no collision happened: no test";
  EXPECT_LT(length(left_edge - left_middle), 1e-9);
  EXPECT_LT(length(right_edge - right_middle), 1e-9);
}

// 150 polyhedra in a cell periodic on x and y, settling on a floor.
World periodic_bed() {
  WorldSettings s;
  s.periodic.axes[0] = s.periodic.axes[1] = true;
  s.periodic.lo = {0, 0, 0};
  s.periodic.hi = {0.08, 0.08, 0};
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"rock", 2500, 1e6, 0.25, 0.4, 0.5});
  b.add_plane({}, {0, 0, 1}, m, "floor");
  std::mt19937_64 rng(3);
  test::fill_polyhedra(b, {.count = 150, .size = 0.012, .lo = {0, 0, 0}, .hi = {0.08, 0.08, 0.12}, .material = m}, rng);
  return b.build();
}

TEST(Periodic, ABedTouchesAcrossTheBoundaryAndResumesWithTheSameBits) {
  World straight = periodic_bed();
  const RunState plan = plan_run(0.2, 1e-4, 0.05);
  struct Watch : RunObserver {
    int across = 0, outside = 0;
    void on_output(const World&, const RunState&) override {}
    void on_step(const World& w, const RunState&) override {
      for (const StepContact& c : w.results.contacts) across += c.active && c.image != kNoImage;
      for (const Body& b : w.bodies)
        if (!b.fixed && (b.position.x < 0 || b.position.x >= 0.08 || b.position.y < 0 || b.position.y >= 0.08))
          ++outside;
    }
  } watch;
  RunObserver* observers[] = {&watch};
  RunState run = plan;
  const RunOutcome outcome = dem::run(straight, run, observers);
  ASSERT_EQ(outcome.status, RunStatus::Completed) << outcome.error;
  EXPECT_GT(watch.across, 100) << "contacts across the boundary";
  EXPECT_EQ(watch.outside, 0);
  EXPECT_GT(straight.stats.contacts, 150);

  World first = periodic_bed();
  RunState part = plan;
  dem::run(first, part, {}, [&] { return part.step == 1000; });
  const std::string bytes = io::encode_checkpoint(first, {part, {}}, 7);
  World resumed = periodic_bed();
  const io::Checkpoint c = io::decode_checkpoint(bytes, resumed, 7, "memory");
  RunState rest = c.run;
  ASSERT_EQ(dem::run(resumed, rest, {}).status, RunStatus::Completed);
  ASSERT_EQ(resumed.bodies.size(), straight.bodies.size());
  for (std::size_t i = 0; i < straight.bodies.size(); ++i)
    ASSERT_EQ(std::memcmp(&straight.bodies[i], &resumed.bodies[i], sizeof(Body)), 0) << "body " << i;
}

TEST(Periodic, InflowsSeeBodiesAcrossTheBoundary) {
  // A ball at x = 0.001 of a cell [0, 0.05): its image at x = 0.051 fills an
  // inflow region just inside the far face, which a test of the ball itself
  // would take for empty. Away from the face, the inflow inserts.
  for (const bool at_face : {true, false}) {
    WorldBuilder b(periodic_x(0, 0.05));
    const std::uint32_t m = b.add_material({"glass", 2500, 1e7});
    b.add_body({.shape = {make_sphere(0.008), {}}, .material = m, .position = {0.001, 0, 0}, .label = "ball"});
    InflowDef d;
    d.variants = {{make_sphere(0.002), {}}};
    d.lo = {at_face ? 0.044 : 0.02, -0.004, -0.004};
    d.hi = {at_face ? 0.0499 : 0.03, 0.004, 0.004};
    d.material = m;
    d.rate = 1000;
    d.count = 5;
    b.add_inflow(d);
    World w = b.build();
    for (int k = 0; k < 200; ++k) step(w, 1e-4);
    EXPECT_EQ(w.inflow_states[0].inserted, at_face ? 0u : 5u) << (at_face ? "at the face" : "inside");
    if (at_face) {
      EXPECT_GT(w.inflow_states[0].behind, 0u);
    }
  }
}

TEST(Periodic, ACellShorterThanFourReachesIsRefused) {
  WorldBuilder b(periodic_x(0, 0.03));
  const std::uint32_t m = b.add_material({"glass", 2500, 1e7});
  b.add_body({.shape = {make_sphere(0.005), {}}, .material = m, .label = "ball"});
  EXPECT_NO_THROW(b.build()) << "0.03 m is more than four reaches and skins (0.021 m)";
  WorldBuilder small(periodic_x(0, 0.02));
  const std::uint32_t m2 = small.add_material({"glass", 2500, 1e7});
  small.add_body({.shape = {make_sphere(0.005), {}}, .material = m2, .label = "ball"});
  EXPECT_THROW(small.build(), BuildError);
}

}  // namespace
}  // namespace gjkdem::dem
