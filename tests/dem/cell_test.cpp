// A deforming periodic cell (periodic.hpp), without walls:
// - driven by the stress servo to an isotropic pressure, a box of grains
//   comes to rest with the contacts' stress tensor, measured independently
//   (dem::measure's sum over contact points), equal to the pressure within
//   1% on the diagonal and below 1% of it off the diagonal;
// - stretched at a strain rate, its faces and its grains' affine velocities
//   move as the rate says, and the kinetic energy the field gives them is
//   counted as work;
// - sheared at a rate (Lees-Edwards), its tilt grows as the rate says and
//   is taken back at half the edge, the grains stay in it, their mean
//   velocity follows the shear, and no energy is made;
// - a servoed, shearing cell continues from a checkpoint with the same bits,
//   also from the step before a grain wraps (the continued run renews its
//   search cell where the run that did not stop renews it);
// - a cell compressed below four reaches stops the run with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "gjkdem/dem/measure.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/io/view_format.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kPressure = 5e4;  // Pa

// `count` spheres of radii 4 to 6 mm, loose in a cube of side `side`
// periodic on every axis, no gravity.
World loose_box(int count, Real side, const CellControl& control, Real friction,
                ContactModel model = ContactModel::Hertz) {
  WorldSettings s;
  s.model = model;
  s.gravity = {};
  s.periodic.axes[0] = s.periodic.axes[1] = s.periodic.axes[2] = true;
  s.periodic.lo = {0, 0, 0};
  s.periodic.hi = {side, side, side};
  s.cell_control = control;
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"glass", 2500, 5e7, 0.25, 0.3, friction});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Real> u(0, 1);
  std::vector<std::pair<Vec3, Real>> placed;
  while (static_cast<int>(placed.size()) < count) {
    const Real r = 0.004 + 0.002 * u(rng);
    const Vec3 p{side * u(rng), side * u(rng), side * u(rng)};
    bool free = true;
    for (const auto& [q, rq] : placed) {
      Vec3 d = p - q;
      for (int a = 0; a < 3; ++a) d[a] -= side * std::round(d[a] / side);
      if (length(d) < r + rq + 1e-4) free = false;
    }
    if (!free) continue;
    placed.push_back({p, r});
    b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = p,
                .velocity = {0.05 * (u(rng) - 0.5), 0.05 * (u(rng) - 0.5), 0.05 * (u(rng) - 0.5)}});
  }
  return b.build();
}

CellControl isotropic(Real pressure, Real max_rate) {
  CellControl c;
  for (int k = 0; k < 6; ++k) c.mode[k] = CellMode::Stress, c.value[k] = k < 3 ? pressure : 0;
  c.max_strain_rate = max_rate;
  return c;
}

class ServoedBox : public ::testing::TestWithParam<std::pair<ContactModel, Real>> {};

// Frictionless and frictional Hertz spheres, and frictional ones under the
// linear law. (With a time step above the Mindlin limit, critical_time_step,
// the frictional Hertz box never came to rest at this pressure.)
INSTANTIATE_TEST_SUITE_P(DeformingCell, ServoedBox,
                         ::testing::Values(std::pair{ContactModel::Hertz, Real(0)},
                                           std::pair{ContactModel::Hertz, Real(0.3)},
                                           std::pair{ContactModel::Linear, Real(0.3)}));

TEST_P(ServoedBox, ComesToRestAtTheAppliedPressure) {
  const auto [model, friction] = GetParam();
  World w = loose_box(120, 0.06, isotropic(kPressure, 1.0), friction, model);
  RunState run = plan_run(2.0, critical_time_step(w), 0.5);
  ASSERT_EQ(dem::run(w, run, {}).status, RunStatus::Completed);
  EXPECT_LT(w.cell.now.hi.x - w.cell.now.lo.x, 0.05) << "compressed from 0.06";
  EXPECT_LT(kinetic_energy(w), 1e-4 * w.stats.elastic_energy) << "at rest";
  // The stress as dem::measure sums it (contact points, nearest images):
  // every grain is in a region larger than the cell, so scale its volume.
  const MeasureRegion region{w.cell.now.lo - Vec3{0.1, 0.1, 0.1}, w.cell.now.hi + Vec3{0.1, 0.1, 0.1}};
  MeasureWorkspace work;
  const Measures m = measure(w, touching_contacts(w), region, work);
  const Real scale = region.volume() / cell_volume(w.cell.now);
  EXPECT_EQ(m.grains, w.bodies.size());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Real s = m.stress.row[i][j] * scale;
      if (i == j) {
        EXPECT_NEAR(s, kPressure, 0.01 * kPressure) << "sigma " << i << i;
      } else {
        EXPECT_LT(std::fabs(s), 0.01 * kPressure) << "sigma " << i << j;
      }
      // The servo's own sum (branch vectors between centres) agrees.
      const int k = i == j ? i : i + j == 1 ? kXY : i + j == 2 ? kXZ : kYZ;
      EXPECT_NEAR(s, w.cell.stress[k], 1e-6 * kPressure);
    }
}

TEST(DeformingCell, AStretchedCellMovesItsFacesAndGivesTheGrainsItsField) {
  CellControl c;
  c.mode[0] = CellMode::StrainRate, c.value[0] = 0.5;
  World w = loose_box(4, 0.06, c, 0.3);
  std::vector<Body> before = w.bodies;
  const Real dt = 1e-4, start_energy = kinetic_energy(w);
  const Vec3 centre = cell_centre(w.cell.now);
  ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
  // The field's velocity 0.5 (x - centre) joins each grain's own.
  Real expected_work = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const Vec3 v = before[i].velocity + Vec3{0.5 * (before[i].position.x - centre.x), 0, 0};
    expected_work += 0.5 * mass_of(w, before[i]) * (dot(v, v) - dot(before[i].velocity, before[i].velocity));
    if (w.bodies[i].position.x >= before[i].position.x + v.x * dt - 1e-12) {  // not wrapped
      EXPECT_NEAR(w.bodies[i].velocity.x, v.x, 1e-12);
    }
  }
  EXPECT_NEAR(w.wall_work, expected_work, 1e-15);
  EXPECT_NEAR(kinetic_energy(w) - start_energy, expected_work, 1e-12);
  for (int k = 1; k < 2000; ++k) ASSERT_EQ(step(w, dt).status, StepStatus::Ok);
  EXPECT_NEAR(w.cell.now.hi.x - w.cell.now.lo.x, 0.06 * std::pow(1 + 0.5 * dt, 2000), 1e-12);
  EXPECT_NEAR(cell_centre(w.cell.now).x, 0.03, 1e-12);
  EXPECT_EQ(w.cell.now.hi.y - w.cell.now.lo.y, 0.06);
  // Frames carry the cell as it is now (the viewer and gjkdem analyze read it).
  const io::ViewFrame frame = io::decode_view_frame(io::encode(io::view_frame(w, 2000)));
  EXPECT_EQ(frame.cell_axes, 7u);
  EXPECT_EQ(frame.cell[3], static_cast<float>(w.cell.now.hi.x));
  EXPECT_EQ(frame.cell[0], static_cast<float>(w.cell.now.lo.x));
  // A grain crossing a face takes the field's difference with it: its
  // velocity stays the field's at its new place plus its own.
  for (const Body& b : w.bodies) {
    EXPECT_GE(b.position.x, w.cell.now.lo.x);
    EXPECT_LT(b.position.x, w.cell.now.hi.x);
  }
}

CellControl simple_shear(Real rate) {
  CellControl c;
  c.mode[kXZ] = CellMode::StrainRate, c.value[kXZ] = rate;
  return c;
}

TEST(DeformingCell, ASimpleShearWithoutWallsFollowsItsRate) {
  const Real rate = 4, side = 0.05;
  World w = loose_box(80, side, simple_shear(rate), 0.3);
  RunState run = plan_run(0.15, critical_time_step(w), 0.01);
  struct Watch : RunObserver {
    int outside = 0;
    Real least_dissipated = 0;
    Real initial = 0;
    void on_output(const World& w, const RunState& s) override {
      least_dissipated = std::fmin(least_dissipated, energy_balance(w, s.initial_energy).dissipated);
    }
    void on_step(const World& w, const RunState&) override {
      for (const Body& b : w.bodies) {
        // In the tilted cell: z in [lo, hi), x within the leaning faces.
        const Real f = (b.position.z - w.cell.now.lo.z) / (w.cell.now.hi.z - w.cell.now.lo.z);
        const Real x = b.position.x - w.cell.now.lo.x - f * w.cell.now.tilt.y;
        if (f < 0 || f >= 1 || x < -1e-12 || x >= w.cell.now.hi.x - w.cell.now.lo.x + 1e-12) ++outside;
      }
    }
  } watch;
  RunObserver* observers[] = {&watch};
  ASSERT_EQ(dem::run(w, run, observers).status, RunStatus::Completed);
  EXPECT_EQ(watch.outside, 0);
  // Tilt: rate * side * t, taken back by one edge past half of it.
  Real tilt = rate * side * w.time;
  while (tilt > side / 2) tilt -= side;
  EXPECT_NEAR(w.cell.now.tilt.y, tilt, 1e-3 * side);
  EXPECT_EQ(w.cell.now.tilt.x, 0);
  EXPECT_EQ(w.cell.now.tilt.z, 0);
  // The grains' mean velocity along x grows with z at the shear rate.
  Real sz = 0, szz = 0, sv = 0, svz = 0;
  for (const Body& b : w.bodies) {
    const Real z = b.position.z - cell_centre(w.cell.now).z;
    sz += z, szz += z * z, sv += b.velocity.x, svz += b.velocity.x * z;
  }
  const Real n = static_cast<Real>(w.bodies.size());
  const Real slope = (n * svz - sz * sv) / (n * szz - sz * sz);
  EXPECT_NEAR(slope, rate, 0.15 * rate);
  // The cell's work is counted: the contacts' damping and friction only
  // take energy out.
  EXPECT_GT(w.wall_work, 0);
  EXPECT_GT(watch.least_dissipated, -1e-6 * w.wall_work);
  EXPECT_GT(energy_balance(w, run.initial_energy).dissipated, 0);
}

// Two balls colliding across the bottom face of a cell sheared at `rate`
// (x along, z across): B near the top meets A near the bottom through its
// image one edge c = (tilt, 0, Lz) below, which moves with B's velocity
// minus rate * Lz along x. Without a cell, a ball placed where that image
// is and moving as it moves must come out the same. Returns A's and B's
// (or the stand-in's) velocities after; the periodic B's less rate * Lz.
std::pair<Vec3, Vec3> collide_across(Real rate, bool periodic) {
  const Real side = 0.06, r = 0.005;
  WorldSettings s;
  s.model = ContactModel::Hertz;
  s.gravity = {};
  if (periodic) {
    s.periodic.axes[0] = s.periodic.axes[2] = true;
    s.periodic.hi = {side, 0, side};
    s.cell_control.mode[kXZ] = CellMode::StrainRate, s.cell_control.value[kXZ] = rate;
  }
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"glass", 2500, 1e7, 0.25, 0.6, 0.4});
  // The cell's affine field, rate * (z - centre) along x, joins the balls'
  // velocities in the first step: the stand-in has it from the start.
  const Real centre = side / 2;
  const Vec3 a{0.030, 0.001, 0.006}, bp{0.032, -0.001, side - 0.0061};
  const Vec3 va{0.1, 0, -0.5}, vb{-0.1, 0.05, 0.5};
  const Vec3 field_a{rate * (a.z - centre), 0, 0};
  b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = a, .velocity = va + (periodic ? Vec3{} : field_a)});
  if (periodic) {
    b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = bp, .velocity = vb});
  } else {
    const Vec3 image = bp - Vec3{0, 0, side};
    b.add_body({.shape = {make_sphere(r), {}}, .material = m, .position = image,
                .velocity = vb + Vec3{rate * (image.z - centre), 0, 0}});
  }
  World w = b.build();
  Real most = 0;
  for (int k = 0; k < 400; ++k) {
    step(w, 1e-5);
    most = std::fmax(most, length(w.bodies[0].force));
  }
  EXPECT_GT(most, 0) << "they touched";
  Vec3 after_b = w.bodies[1].velocity;
  if (periodic) after_b.x -= rate * side;
  return {w.bodies[0].velocity, after_b};
}

TEST(DeformingCell, ACollisionAcrossAShearedFaceIsTheSameCollisionWithoutACell) {
  for (const Real rate : {0.0, 20.0}) {
    const auto [a, b] = collide_across(rate, true);
    const auto [a0, b0] = collide_across(rate, false);
    EXPECT_LT(length(a - a0), 1e-9) << "rate " << rate;
    EXPECT_LT(length(b - b0), 1e-9) << "rate " << rate;
  }
}

TEST(DeformingCell, AServoedShearingCellContinuesFromACheckpointBitForBit) {
  CellControl c = isotropic(kPressure, 1.0);
  c.mode[kXZ] = CellMode::StrainRate, c.value[kXZ] = 3;  // and a tilt taken back on the way
  const auto fresh = [&] { return loose_box(60, 0.045, c, 0.3); };
  World straight = fresh();
  const RunState plan = plan_run(0.25, critical_time_step(straight), 0.05);
  RunState run = plan;
  ASSERT_EQ(dem::run(straight, run, {}).status, RunStatus::Completed);
  EXPECT_LT(straight.cell.now.tilt.y, 0) << "the tilt was taken back";

  World first = fresh();
  RunState part = plan;
  dem::run(first, part, {}, [&] { return part.step == plan.steps_total / 2; });
  const std::string bytes = io::encode_checkpoint(first, {part, {}}, 7);
  World resumed = fresh();
  const io::Checkpoint saved = io::decode_checkpoint(bytes, resumed, 7, "memory");
  RunState rest = saved.run;
  ASSERT_EQ(dem::run(resumed, rest, {}).status, RunStatus::Completed);
  for (std::size_t i = 0; i < straight.bodies.size(); ++i)
    ASSERT_EQ(std::memcmp(&straight.bodies[i], &resumed.bodies[i], sizeof(Body)), 0) << "body " << i;
  EXPECT_EQ(std::memcmp(&straight.cell.now, &resumed.cell.now, sizeof(PeriodicCell)), 0);
  EXPECT_EQ(straight.cell.rate, resumed.cell.rate);
  EXPECT_EQ(straight.wall_work, resumed.wall_work);
}

// A grain that wraps across a face of a deforming cell takes the field's
// velocity difference with it (L times the lattice vector it moved by), so
// its kinetic energy jumps: that is work the cell does, and the balance
// counts it. The contacts' damping and friction then only take energy out,
// at every output, while grains wrap in a squeezed cell, and in a squeezed
// shearing one whose tilt is taken back (every grain in the part of the
// cell that changes sides wraps at once).
TEST(DeformingCell, TheEnergyOfGrainsWrappingInADeformingCellIsCounted) {
  for (const bool shear : {false, true}) {
    CellControl c = isotropic(kPressure, 1.0);
    if (shear) c.mode[kXZ] = CellMode::StrainRate, c.value[kXZ] = 3;
    World w = loose_box(60, 0.045, c, 0.3);
    RunState run = plan_run(0.25, critical_time_step(w), 0.005);
    struct Watch : RunObserver {
      Real least_dissipated = 0;
      void on_output(const World& w, const RunState& s) override {
        least_dissipated = std::fmin(least_dissipated, energy_balance(w, s.initial_energy).dissipated);
      }
    } watch;
    RunObserver* observers[] = {&watch};
    ASSERT_EQ(dem::run(w, run, observers).status, RunStatus::Completed);
    if (shear) {
      EXPECT_LT(w.cell.now.tilt.y, 0) << "the tilt was taken back";
    }
    EXPECT_GT(watch.least_dissipated, -1e-6 * w.wall_work) << (shear ? "shearing" : "squeezed");
    EXPECT_GT(energy_balance(w, run.initial_energy).dissipated, 0) << (shear ? "shearing" : "squeezed");
  }
}

// A checkpoint written the step before a grain wraps across a face: the
// continued run's first candidate search keeps the search cell it restored,
// but the wrap renews it, as in the run that did not stop.
TEST(DeformingCell, ARunContinuedJustBeforeAGrainWrapsGivesTheSameBits) {
  CellControl c = isotropic(kPressure, 1.0);
  c.mode[kXZ] = CellMode::StrainRate, c.value[kXZ] = 3;
  const auto fresh = [&] { return loose_box(60, 0.045, c, 0.3); };
  World probe = fresh();
  const RunState plan = plan_run(0.06, critical_time_step(probe), 0.02);
  // The steps at which some grain wraps (its centre jumps by most of a period).
  std::vector<std::uint64_t> wraps;
  for (std::uint64_t k = 1; k <= plan.steps_total; ++k) {
    const std::vector<Body> before = probe.bodies;
    ASSERT_EQ(step(probe, plan.dt).status, StepStatus::Ok);
    for (std::size_t i = 0; i < before.size(); ++i)
      if (length(probe.bodies[i].position - before[i].position) > 0.02) {
        wraps.push_back(k);
        break;
      }
  }
  ASSERT_GE(wraps.size(), 3u);
  World straight = fresh();
  RunState run = plan;
  ASSERT_EQ(dem::run(straight, run, {}).status, RunStatus::Completed);
  for (const std::uint64_t wrap : {wraps[0], wraps[wraps.size() / 2], wraps.back()}) {
    World first = fresh();
    RunState part = plan;
    dem::run(first, part, {}, [&] { return part.step == wrap - 1; });
    ASSERT_EQ(part.step, wrap - 1);
    World resumed = fresh();
    RunState rest = io::decode_checkpoint(io::encode_checkpoint(first, {part, {}}, 7), resumed, 7, "memory").run;
    ASSERT_EQ(dem::run(resumed, rest, {}).status, RunStatus::Completed);
    SCOPED_TRACE(testing::Message() << "continued before step " << wrap);
    for (std::size_t i = 0; i < straight.bodies.size(); ++i)
      ASSERT_EQ(std::memcmp(&straight.bodies[i], &resumed.bodies[i], sizeof(Body)), 0) << "body " << i;
    const BoxCache &s = straight.search.boxes, &r = resumed.search.boxes;
    EXPECT_EQ(std::memcmp(s.anchor_position.data(), r.anchor_position.data(), s.anchor_position.size() * sizeof(Vec3)), 0);
    EXPECT_EQ(std::memcmp(&straight.search.cell, &resumed.search.cell, sizeof(PeriodicCell)), 0);
    EXPECT_EQ(straight.wall_work, resumed.wall_work);
  }
}

TEST(DeformingCell, ACellCompressedBelowFourReachesStopsTheRun) {
  CellControl c;
  for (int a = 0; a < 3; ++a) c.mode[a] = CellMode::StrainRate, c.value[a] = -3;
  World w = loose_box(3, 0.04, c, 0.3);
  RunState run = plan_run(1, 5e-5, 0.1);
  const RunOutcome out = dem::run(w, run, {});
  ASSERT_EQ(out.status, RunStatus::Failed);
  EXPECT_NE(out.error.find("periodic cell's width across x shrank to"), std::string::npos) << out.error;
  EXPECT_NE(out.error.find("four times the largest body's reach"), std::string::npos) << out.error;
}

// Issue 32: a strain rate of 1e12 /s inverted the cell in one step and was
// reported as a width of -nan; the guard now names the rate before the
// first step, and 3 /s at the same dt passes it.
TEST(DeformingCell, AStrainRateTooFastForTheStepIsNamed) {
  for (const Real rate : {1e12, 3.0}) {
    CellControl c;
    for (int a = 0; a < 3; ++a) c.mode[a] = CellMode::StrainRate, c.value[a] = -rate;
    World w = loose_box(3, 0.04, c, 0.3);
    RunState run = plan_run(2e-4, 5e-5, 1e-4);
    const RunOutcome out = dem::run(w, run, {});
    if (rate > 1e6) {
      ASSERT_EQ(out.status, RunStatus::Failed);
      EXPECT_NE(out.error.find("the periodic cell's strain rate"), std::string::npos) << out.error;
      EXPECT_NE(out.error.find("moves the images"), std::string::npos) << out.error;
      EXPECT_EQ(run.step, 0u);
    } else {
      EXPECT_EQ(out.status, RunStatus::Completed) << out.error;
    }
  }
}

TEST(DeformingCell, TheBuilderRefusesControlsItCannotHonour) {
  // Refused by the builder's constructor (dem::check_settings) or, for
  // what depends on the bodies, by build().
  const auto refuses = [](WorldSettings s, const std::string& message) {
    try {
      WorldBuilder b(s);
      const std::uint32_t m = b.add_material({"glass", 2500, 1e7});
      b.add_body({.shape = {make_sphere(0.005), {}}, .material = m, .position = {0.05, 0.05, 0.05}});
      b.build();
      ADD_FAILURE() << "accepted: " << message;
    } catch (const BuildError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  WorldSettings s;
  s.periodic.axes[0] = true;
  s.periodic.hi = {0.1, 0, 0};
  s.cell_control.mode[kXZ] = CellMode::StrainRate;
  refuses(s, "not periodic on z");
  s.cell_control = {};
  s.cell_control.mode[0] = CellMode::Stress, s.cell_control.value[0] = 1e4, s.cell_control.max_strain_rate = 1;
  refuses(s, "periodic on x, y and z");
  s.periodic.axes[1] = s.periodic.axes[2] = true;
  s.periodic.hi = {0.1, 0.1, 0.1};
  s.cell_control.max_strain_rate = 0;
  refuses(s, "stress needs max_strain_rate too");
  s.cell_control.max_strain_rate = -1;
  refuses(s, "max_strain_rate must be finite and > 0");
  s.cell_control = {};
  s.cell_control.mode[kXY] = CellMode::Stress, s.cell_control.max_strain_rate = 1;
  refuses(s, "stress needs a normal stress");
  // A wall piece as long as the period: a body would touch it directly and
  // through its image at once (a drum slice periodic along its axis).
  WorldSettings slice;
  slice.periodic.axes[0] = true;
  slice.periodic.hi = {0.1, 0, 0};
  WorldBuilder b(slice);
  const std::uint32_t m = b.add_material({"glass", 2500, 1e7});
  b.add_body({.shape = {make_sphere(0.005), {}}, .material = m, .position = {0.05, 0, 0.02}});
  b.add_body({.shape = {Shape{Box{Vec3{0.05, 0.01, 0.01}}}, {}}, .material = m, .position = {0.05, 0, 0}, .fixed = true,
              .label = "floor"});
  try {
    b.build();
    ADD_FAILURE() << "a wall as long as the period was accepted";
  } catch (const BuildError& e) {
    EXPECT_NE(std::string(e.what()).find("floor spans 0.1 m along the periodic axis x"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Cut it along x"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gjkdem::dem
