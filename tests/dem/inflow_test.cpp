// Inflows (inflow.hpp): a region inserting bodies during a run delivers its
// rate in bodies or kilograms per second within 1% over a second, never
// places a body where it touches another or a wall, follows the number
// probabilities of its variants within sampling error, and stops at its
// count and stop time; bad inflows are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <span>
#include <string>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

// Cubes of three sizes pouring down from a region.
InflowDef cube_inflow() {
  InflowDef d;
  for (const Real half : {0.002, 0.003, 0.004}) d.variants.push_back({Shape{Box{{half, half, half}}}, {}});
  d.weights = {0.5, 0.3, 0.2};
  d.lo = {-0.03, -0.03, 0.1};
  d.hi = {0.03, 0.03, 0.12};
  d.velocity = {0, 0, -0.5};
  d.label = "inflow";
  return d;
}

// (Without the box the bodies fall freely: cheap runs of a second.)
World pour_world(const InflowDef& d, bool with_box = false) {
  WorldBuilder b;
  const std::uint32_t m = b.add_material({"grain", 2500, 1e6, 0.25, 0.3, 0.5});
  if (with_box) b.add_box_walls({-0.05, -0.05, 0}, {0.05, 0.05, 0.3}, true, 0.01, m, "box");
  InflowDef def = d;
  def.material = m;
  b.add_inflow(def);
  return b.build();
}

Real run_initial_energy = 0;  // of the last run_for

void run_for(World& w, Real duration, std::span<RunObserver* const> observers = {}) {
  RunState run = plan_run(duration, 1e-4, duration);
  const RunOutcome outcome = dem::run(w, run, observers);
  ASSERT_EQ(outcome.status, RunStatus::Completed) << outcome.error;
  run_initial_energy = run.initial_energy;
}

// Checks at every step that the bodies inserted in it touch nothing.
struct InsertionWatch : RunObserver {
  int overlaps = 0, inserted = 0;
  void on_output(const World&, const RunState&) override {}
  void on_step(const World& w, const RunState&) override {
    const std::size_t n = w.bodies.size();
    for (std::size_t i = n - static_cast<std::size_t>(w.stats.inserted); i < n; ++i) {
      ++inserted;
      const ShapeTemplate& t = w.templates[w.bodies[i].shape];
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        const ShapeTemplate& o = w.templates[w.bodies[j].shape];
        if (intersect(t.shape, shape_pose(t, w.bodies[i]), o.shape, shape_pose(o, w.bodies[j]))) ++overlaps;
      }
    }
  }
};

TEST(Inflow, DeliversItsRateInBodiesWithoutOverlap) {
  InflowDef d = cube_inflow();
  d.rate = 400;
  d.stop = 10;
  World w = pour_world(d);
  const std::size_t walls = w.bodies.size();
  InsertionWatch watch;
  RunObserver* observers[] = {&watch};
  run_for(w, 1.0, observers);
  const Real inserted = static_cast<Real>(w.bodies.size() - walls);
  EXPECT_NEAR(inserted, 400, 4) << "the rate over one second";
  EXPECT_EQ(watch.inserted, static_cast<int>(inserted));
  EXPECT_EQ(watch.overlaps, 0);
  EXPECT_EQ(w.inflow_states[0].inserted, static_cast<std::uint64_t>(inserted));
  EXPECT_EQ(w.inflow_states[0].behind, 0u) << "the region had room all along";
  for (std::size_t i = 1; i < w.bodies.size(); ++i) ASSERT_LT(w.bodies[i - 1].id, w.bodies[i].id);
  // Falling freely, nothing is lost: the energy the bodies brought in is all there.
  const EnergyBalance e = energy_balance(w, run_initial_energy);
  EXPECT_GT(e.inflow, 0);
  EXPECT_LT(std::fabs(e.dissipated), 1e-6 * (e.kinetic + std::fabs(e.potential)));
}

// A disc, a cylinder and a ball (round_region.hpp): every body is placed
// inside, and the places are uniform in the volume (in the disc's area):
// the mean of (r/R)^2 about the axis, of the height along it, and of
// (r/R)^3 in a ball is 1/2, within five standard errors of 300 draws.
TEST(Inflow, RoundRegionsPlaceBodiesUniformlyInside) {
  for (const RoundRegion& g : {RoundRegion{.base = {0.01, 0.0, 0.2}, .axis = {1, 0, 1}, .radius = 0.05, .height = 0},
                               RoundRegion{.base = {0.0, 0.01, 0.1}, .axis = {0, 0, 1}, .radius = 0.04, .height = 0.05},
                               RoundRegion{.kind = RoundRegion::Kind::Ball, .base = {0, 0, 0.3}, .radius = 0.04}}) {
    const bool ball = g.kind == RoundRegion::Kind::Ball, disc = !ball && g.height == 0;
    SCOPED_TRACE(ball ? "ball" : disc ? "disc" : "cylinder");
    WorldSettings settings;
    settings.gravity = {};
    WorldBuilder b(settings);
    InflowDef d;
    d.variants = {{make_sphere(0.001), {}}};
    d.round = g;
    d.rate = 3000;
    d.count = 300;
    d.material = b.add_material({"grain", 2500, 1e6, 0.25, 0.3, 0.5});
    b.add_inflow(d);
    World w = b.build();
    run_for(w, 0.11);
    ASSERT_EQ(w.bodies.size(), 300u);
    const Vec3 a = normalized(g.axis);
    Real radial = 0, along = 0;
    for (const Body& body : w.bodies) {
      const Vec3 rel = body.position - g.base;
      const Real h = ball ? 0 : dot(rel, a), r = length(ball ? rel : rel - a * h);
      ASSERT_LE(r, g.radius * (1 + 1e-12));
      if (!ball) {
        ASSERT_TRUE(h >= -1e-12 && h <= g.height + 1e-12) << h;
      }
      radial += ball ? std::pow(r / g.radius, 3) : std::pow(r / g.radius, 2);
      along += disc || ball ? 0.5 : h / g.height;
    }
    const Real standard_error = 1 / std::sqrt(12.0 * 300);
    EXPECT_NEAR(radial / 300, 0.5, 5 * standard_error);
    EXPECT_NEAR(along / 300, 0.5, 5 * standard_error);
  }
  // A round region's bad numbers are refused by name.
  WorldBuilder b;
  InflowDef d;
  d.variants = {{make_sphere(0.001), {}}};
  d.rate = 10, d.count = 5, d.label = "inflow[0]";
  d.material = b.add_material({"grain", 2500, 1e6, 0.25, 0.3, 0.5});
  d.round = RoundRegion{.radius = 0.01, .height = -1};
  try {
    b.add_inflow(d);
    ADD_FAILURE() << "a negative height was taken";
  } catch (const BuildError& e) {
    EXPECT_NE(std::string(e.what()).find("inflow[0]: the region's radius"), std::string::npos) << e.what();
  }
}

TEST(Inflow, DeliversItsMassRate) {
  InflowDef d = cube_inflow();
  d.mass_rate = 0.2;  // kg/s: about 350 cubes a second
  d.stop = 10;
  World w = pour_world(d);
  run_for(w, 1.0);
  Real mass = 0;
  for (const Body& b : w.bodies)
    if (!b.fixed) mass += mass_of(w, b);
  EXPECT_NEAR(mass, 0.2, 0.002) << "the mass rate over one second";
  EXPECT_NEAR(mass, w.inflow_states[0].mass, 1e-12);
}

TEST(Inflow, VariantsFollowTheirNumberProbabilities) {
  // 100,000 draws of the counter-based generator: each count within 4
  // standard deviations of its expectation.
  Inflow f;
  f.cumulative = {0.5, 0.8, 1.0};
  f.seed = 7;
  const int n = 100000;
  int counts[3] = {};
  for (int k = 0; k < n; ++k) ++counts[inflow_variant(f, static_cast<std::uint64_t>(k))];
  const Real p[3] = {0.5, 0.3, 0.2};
  for (int v = 0; v < 3; ++v)
    EXPECT_NEAR(counts[v], n * p[v], 4 * std::sqrt(n * p[v] * (1 - p[v]))) << "variant " << v;
  // And in a run: the inserted bodies' templates.
  InflowDef d = cube_inflow();
  d.rate = 600;
  d.stop = 10;
  World w = pour_world(d);
  run_for(w, 1.0);
  int seen[3] = {}, total = 0;
  for (const Body& b : w.bodies)
    if (!b.fixed) ++seen[b.shape - w.inflows[0].templates[0]], ++total;
  ASSERT_GT(total, 590);
  for (int v = 0; v < 3; ++v)
    EXPECT_NEAR(seen[v], total * p[v], 4 * std::sqrt(total * p[v] * (1 - p[v]))) << "variant " << v;
}

TEST(Inflow, StopsAtItsCountAndStopTime) {
  InflowDef d = cube_inflow();
  d.rate = 1000;
  d.count = 50;
  World by_count = pour_world(d, true);
  run_for(by_count, 0.2);
  EXPECT_EQ(by_count.inflow_states[0].inserted, 50u);
  d.count = 0;
  d.start = 0.05;
  d.stop = 0.1;
  World by_time = pour_world(d);
  run_for(by_time, 0.2);
  EXPECT_NEAR(static_cast<Real>(by_time.inflow_states[0].inserted), 51, 1);  // bodies 0..50 due in [0.05, 0.1]
}

TEST(Inflow, AFullRegionFallsBehindAndSaysSo) {
  // No gravity, no velocity: the bodies stay where they were put, the
  // region fills up, and the inflow counts the steps it could not keep up.
  InflowDef d = cube_inflow();
  d.velocity = {};
  d.rate = 5000;
  d.stop = 10;
  WorldSettings no_gravity;
  no_gravity.gravity = {0, 0, 0};
  WorldBuilder b(no_gravity);
  const std::uint32_t m = b.add_material({"grain", 2500, 1e6});
  d.material = m;
  b.add_inflow(d);
  World w = b.build();
  InsertionWatch watch;
  RunObserver* observers[] = {&watch};
  run_for(w, 0.2, observers);
  EXPECT_GT(w.inflow_states[0].behind, 0u);
  EXPECT_LT(w.bodies.size(), 1000u);
  EXPECT_EQ(watch.overlaps, 0);
}

TEST(Inflow, BadInflowsAreRefused) {
  const auto refused = [](InflowDef d, const std::string& message) {
    WorldBuilder b;
    d.material = b.add_material({"grain", 2500, 1e6});
    try {
      b.add_inflow(d);
    } catch (const BuildError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted an inflow that should fail with: " << message;
  };
  // Each case changes a good inflow (10 bodies/s until t = 1 s) in one way.
  const std::pair<void (*)(InflowDef&), const char*> cases[] = {
      {[](InflowDef& d) { d.stop = std::numeric_limits<Real>::infinity(); }, "give a count or a stop time"},
      {[](InflowDef& d) { d.mass_rate = 1; }, "give one rate > 0"},
      {[](InflowDef& d) { d.weights = {1, 1}; }, "2 weights for 3 shapes"},
      {[](InflowDef& d) { d.weights = {0, 0, 0}; }, "the weights add up to 0"},
      {[](InflowDef& d) { d.start = 2; }, "the stop must come after the start"},
      {[](InflowDef& d) { d.rate = 1e9; }, "more than 10000000 bodies"},
      {[](InflowDef& d) { d.variants.clear(); }, "no shape to insert"},
  };
  for (const auto& [change, message] : cases) {
    InflowDef d = cube_inflow();
    d.rate = 10;
    d.stop = 1;
    change(d);
    refused(d, message);
  }
}

// A region no body could ever be inserted in (under the floor, inside a
// fixed plate) is refused when the world is built, naming the inflow and
// the wall (issue 32: it inserted nothing and said nothing); a region
// reaching past a wall, or beyond a wall that moves, is fine.
TEST(Inflow, ARegionNoBodyCouldEnterIsRefused) {
  const auto build = [](Vec3 lo, Vec3 hi, bool plate, bool shaken) {
    WorldBuilder b;
    const std::uint32_t m = b.add_material({"grain", 2500, 1e6, 0.25, 0.3, 0.5});
    PrescribedMotion shake;
    shake.amplitude = {0, 0, 0.001}, shake.frequency = 10;
    b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor", shaken ? b.add_motion(shake, "shake") : 0);
    if (plate)
      b.add_body({.shape = {Shape{Box{{0.1, 0.1, 0.01}}}, {}}, .material = m, .position = {0, 0, 0.5}, .fixed = true,
                  .label = "plate"});
    InflowDef d = cube_inflow();
    d.material = m, d.lo = lo, d.hi = hi, d.rate = 100, d.count = 10;
    b.add_inflow(d);
    return b.build();
  };
  const auto refused = [&](Vec3 lo, Vec3 hi, bool plate, const std::string& message) {
    try {
      build(lo, hi, plate, false);
      ADD_FAILURE() << "accepted: " << message;
    } catch (const BuildError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  refused({-0.03, -0.03, -0.2}, {0.03, 0.03, -0.1}, false, "inflow: its region lies wholly beyond the plane wall");
  refused({-0.03, -0.03, 0.495}, {0.03, 0.03, 0.505}, true, "inflow: its region lies wholly inside plate");
  EXPECT_NO_THROW(build({-0.03, -0.03, -0.1}, {0.03, 0.03, 0.1}, false, false));  // reaches above the floor
  EXPECT_NO_THROW(build({-0.03, -0.03, 0.45}, {0.03, 0.03, 0.505}, true, false));  // reaches out of the plate
  EXPECT_NO_THROW(build({-0.03, -0.03, -0.2}, {0.03, 0.03, -0.1}, false, true));   // the floor moves
}

}  // namespace
}  // namespace gjkdem::dem
