// Domain runs (issue 15): a pour run on 2, 3 and 4 domains gives, at every
// output, the same bits as the run of the whole world (bodies with their
// forces, box anchors, the pair store with warm starts and springs, the
// touching contacts, the stats), while bodies cross from one domain into
// another. Ranks are threads of this process here (ThreadRanks); the MPI
// transport runs the same code under mpirun (tests/mpi_run.sh).
#include "gjkdem/dem/domains.hpp"

#include <barrier>
#include <cmath>
#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "dem/beds.hpp"
#include "gjkdem/dem/bonds.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

// Ranks as threads: exchange() hands each message over through a shared
// table, between two barriers.
class ThreadRanks {
 public:
  explicit ThreadRanks(int n) : table_(n, std::vector<std::string>(n)), sync_(n) {
    for (int r = 0; r < n; ++r) ranks_.emplace_back(*this, r);
  }
  struct Rank : DomainTransport {
    Rank(ThreadRanks& shared, int index) : all(shared), me(index) {}
    int rank() const override { return me; }
    int size() const override { return static_cast<int>(all.ranks_.size()); }
    std::vector<std::string> exchange(std::vector<std::string> out) override {
      for (int r = 0; r < size(); ++r) all.table_[r][me] = std::move(out[r]);
      all.sync_.arrive_and_wait();
      std::vector<std::string> in = std::move(all.table_[me]);
      all.table_[me].assign(size(), {});
      all.sync_.arrive_and_wait();
      return in;
    }
    ThreadRanks& all;
    int me;
  };
  Rank& rank(int r) { return ranks_[r]; }

 private:
  std::vector<std::vector<std::string>> table_;  // [to][from]
  std::barrier<> sync_;
  std::vector<Rank> ranks_;
};

template <class T>
std::string bytes_of(const std::vector<T>& items) {
  return std::string(reinterpret_cast<const char*>(items.data()), items.size() * sizeof(T));
}

// What a run shows at each output, as bytes.
struct Snapshot {
  Real time;
  std::string bodies, anchors, turns, pairs, contacts, planes;
  StepStats stats;
  Real wall_work;
};

struct Recorder : RunObserver {
  std::vector<Snapshot> outputs;
  void on_output(const World& w, const RunState&) override {
    std::vector<StepContact> touching;
    for (const StepContact& c : w.results.contacts)
      if (c.active) touching.push_back(c);
    outputs.push_back({w.time, bytes_of(w.bodies), bytes_of(w.search.boxes.anchor_position),
                       bytes_of(w.search.boxes.anchor_orientation), bytes_of(w.pairs), bytes_of(touching),
                       bytes_of(w.planes), w.stats, w.wall_work});
  }
};

void expect_same(const std::vector<Snapshot>& serial, const std::vector<Snapshot>& domains, int ranks) {
  ASSERT_EQ(serial.size(), domains.size()) << ranks << " ranks";
  for (std::size_t k = 0; k < serial.size(); ++k) {
    const Snapshot &s = serial[k], &d = domains[k];
    SCOPED_TRACE(testing::Message() << ranks << " ranks, output " << k << " at t = " << s.time);
    EXPECT_EQ(s.time, d.time);
    EXPECT_TRUE(s.bodies == d.bodies);
    EXPECT_TRUE(s.anchors == d.anchors);
    EXPECT_TRUE(s.turns == d.turns);
    EXPECT_TRUE(s.pairs == d.pairs);
    EXPECT_TRUE(s.contacts == d.contacts);
    EXPECT_TRUE(s.planes == d.planes);
    EXPECT_EQ(s.stats.contacts, d.stats.contacts);
    EXPECT_EQ(s.stats.wall_contacts, d.stats.wall_contacts);
    EXPECT_EQ(std::memcmp(&s.stats.elastic_energy, &d.stats.elastic_energy, sizeof(Real)), 0);
    EXPECT_EQ(std::memcmp(&s.stats.wall_power, &d.stats.wall_power, sizeof(Real)), 0);
    EXPECT_EQ(std::memcmp(&s.wall_work, &d.wall_work, sizeof(Real)), 0);
  }
}

// A run and where it ended (rank 0's gathered world on domains).
struct Ended {
  RunOutcome outcome;
  RunState state;
  World world;
};

Ended run_whole(World world, RunState state, Recorder& recorder, std::span<StepListener* const> listeners = {}) {
  RunObserver* observers[] = {&recorder};
  const RunOutcome outcome = run(world, state, observers, {}, {}, listeners);
  return {outcome, state, std::move(world)};
}

// Runs `world` on `ranks` threads, stopping after `stop_at` steps (0: to
// the end); rank 0's recorder sees the outputs.
Ended run_on(int ranks, const World& world, const RunState& state, Recorder& recorder, std::uint64_t stop_at = 0,
             DomainReport* report = nullptr, std::span<StepListener* const> listeners = {}) {
  ThreadRanks all(ranks);
  std::vector<RunOutcome> outcomes(ranks);
  std::vector<World> wholes(ranks, world);
  std::vector<RunState> states(ranks, state);
  {
    std::vector<std::jthread> threads;
    for (int r = 0; r < ranks; ++r)
      threads.emplace_back([&, r] {
        RunObserver* observers[] = {&recorder};
        const auto seen = r == 0 ? std::span<RunObserver* const>(observers) : std::span<RunObserver* const>();
        outcomes[r] = run_domains(wholes[r], states[r], seen, all.rank(r),
                                  [&] { return stop_at > 0 && states[r].step == stop_at; }, {}, {}, report,
                                  listeners);
      });
  }
  for (int r = 1; r < ranks; ++r) EXPECT_EQ(outcomes[r].status, outcomes[0].status);
  return {outcomes[0], states[0], std::move(wholes[0])};
}

// Polyhedra with friction poured into a box of fixed slabs on a plane
// floor, past a fixed obstacle: a tall region, so the cuts are horizontal
// and the grains fall through them.
// `driven`: the floor shakes (2 g) and the obstacle turns about the vertical;
// `inflow`: 300 grains per second rain in across the top of the box.
World pour(ContactModel model, bool driven = false, bool inflow = false) {
  WorldSettings s;
  s.model = model;
  s.gravity = {0, 0, -9.81};
  WorldBuilder b(s);
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e6, 0.25, 0.5, 0.6});
  const std::uint32_t shake = driven ? b.add_motion({.amplitude = {0, 0, 0.002}, .frequency = 16}, "shake") : 0;
  const std::uint32_t turn =
      driven ? b.add_motion({.center = {0.01, 0, 0.05}, .angular_velocity = {0, 0, 4}}, "turn") : 0;
  b.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor", shake);
  b.add_box_walls({-0.03, -0.03, 0}, {0.03, 0.03, 0.3}, true, 0.01, rock, "box");
  b.add_body({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .material = rock, .position = {0.01, 0, 0.05},
              .fixed = true, .motion = turn, .label = "obstacle"});
  std::mt19937_64 rng(15);
  if (inflow)
    b.add_inflow({.variants = {{random_polyhedron(8, 0.008, rng), {}}, {Shape{Box{{0.004, 0.004, 0.004}}}, {}}},
                  .weights = {},
                  .lo = {-0.02, -0.02, 0.22},
                  .hi = {0.02, 0.02, 0.26},
                  .material = rock,
                  .velocity = {0, 0, -0.5},
                  .rate = 300,
                  .count = 100,
                  .label = "rain"});
  test::fill_polyhedra(b, {.count = 90, .variants = 4, .vertices = 10, .size = 0.012, .lo = {-0.025, -0.025, 0.07},
                           .hi = {0.025, 0.025, 0.2}, .material = rock},
                       rng);
  return b.build();
}

class Domains : public testing::TestWithParam<ContactModel> {};

TEST_P(Domains, APourGivesTheSerialBitsOnAnyNumberOfRanks) {
  const World world = pour(GetParam());
  const RunState plan = plan_run(0.2, critical_time_step(world), 0.02);
  Recorder serial;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed);
  ASSERT_GT(serial.outputs.back().stats.contacts, 50);  // the grains lie on each other and the walls

  // Grains cross the cuts: their owners at the start and at the end differ.
  // (The volume law's pour is the slower: 3 ranks are left to the Hertz one.)
  const std::vector<int> rank_counts = GetParam() == ContactModel::Volume ? std::vector<int>{2, 4} : std::vector<int>{2, 3, 4};
  for (const int ranks : rank_counts) {
    const DomainLayout layout = layout_domains(world, ranks);
    int crossed = 0;
    for (std::size_t i = 0; i < world.bodies.size(); ++i)
      crossed += layout.owner_of(world.bodies[i].position) != layout.owner_of(whole.world.bodies[i].position);
    EXPECT_GT(crossed, 10) << ranks << " ranks";
    Recorder domains;
    DomainReport report;
    ASSERT_EQ(run_on(ranks, world, plan, domains, 0, &report).outcome.status, RunStatus::Completed);
    expect_same(serial.outputs, domains.outputs, ranks);
    // The grains gathered at the bottom, where the first regions left the
    // top ones empty: the regions were drawn again, and share the pile.
    EXPECT_GE(report.rebalances, 1) << ranks << " ranks";
    std::vector<int> first(ranks, 0), last(ranks, 0);
    int moving = 0;
    for (const Body& b : whole.world.bodies)
      if (!b.fixed) ++first[layout.owner_of(b.position)], ++last[report.layout.owner_of(b.position)], ++moving;
    EXPECT_EQ(*std::min_element(first.begin(), first.end()), 0) << ranks << " ranks";
    EXPECT_GT(*std::min_element(last.begin(), last.end()), moving / (4 * ranks)) << ranks << " ranks";
    ASSERT_EQ(report.ranks.size(), static_cast<std::size_t>(ranks));
    double moved = 0;  // bodies handed over with their pairs' springs, which the outputs compared
    for (const DomainReport::Rank& r : report.ranks) {
      EXPECT_GT(r.ghosts, 0) << ranks << " ranks";
      moved += r.moved_out;
    }
    EXPECT_GT(moved * static_cast<double>(report.steps), 10) << ranks << " ranks";
  }
}

INSTANTIATE_TEST_SUITE_P(Laws, Domains, testing::Values(ContactModel::Volume, ContactModel::Hertz),
                         [](const testing::TestParamInfo<ContactModel>& p) { return p.param == ContactModel::Volume ? "Volume" : "Hertz"; });

// A shaken floor and a turning obstacle: their work on the grains, summed
// every step from every domain's contacts, has the serial run's bits.
TEST(Domains, DrivenWallsAndBodiesGiveTheSerialBits) {
  const World world = pour(ContactModel::Hertz, true);
  const RunState plan = plan_run(0.2, critical_time_step(world), 0.02);
  Recorder serial;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed);
  ASSERT_GT(std::fabs(whole.world.wall_work), 1e-6);  // the floor and the obstacle worked on the grains
  for (const int ranks : {2, 3}) {
    Recorder domains;
    ASSERT_EQ(run_on(ranks, world, plan, domains).outcome.status, RunStatus::Completed);
    expect_same(serial.outputs, domains.outputs, ranks);
  }
}

// Grains rain in through an inflow while others pour: every rank places the
// new bodies among those near the inflow, gathered from every domain, and
// the run keeps the serial bits.
TEST(Domains, AnInflowGivesTheSerialBits) {
  const World world = pour(ContactModel::Hertz, false, true);
  const RunState plan = plan_run(0.2, critical_time_step(world), 0.02);
  Recorder serial;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed);
  ASSERT_GT(whole.world.inflow_states[0].inserted, 40u);
  for (const int ranks : {2, 3}) {
    Recorder domains;
    const Ended split = run_on(ranks, world, plan, domains);
    ASSERT_EQ(split.outcome.status, RunStatus::Completed);
    expect_same(serial.outputs, domains.outputs, ranks);
    EXPECT_EQ(split.world.inflow_states[0].inserted, whole.world.inflow_states[0].inserted);
    EXPECT_EQ(std::memcmp(&split.world.inflow_states[0].energy, &whole.world.inflow_states[0].energy, sizeof(Real)), 0);
  }
}

// Grains that break as they land and pile up (docs/breakage.md): each
// domain breaks those it owns, every rank appends every fragment's template
// in id order, and the run keeps the serial bits.
TEST(Domains, GrainsThatBreakGiveTheSerialBits) {
  World world = pour(ContactModel::Volume);
  world.materials[0].strength = {.mean = 2e3, .weibull_modulus = 3, .reference_size = 0.01, .smallest = 0.005};
  world = WorldBuilder(std::move(world)).build();  // room for the fragments
  const RunState plan = plan_run(0.1, critical_time_step(world), 0.005);
  Recorder serial;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed) << whole.outcome.error;
  ASSERT_GT(whole.world.broken, 10u);
  RecordProperty("broken", std::to_string(whole.world.broken));
  for (const int ranks : {2, 3}) {
    Recorder domains;
    const Ended split = run_on(ranks, world, plan, domains);
    ASSERT_EQ(split.outcome.status, RunStatus::Completed);
    expect_same(serial.outputs, domains.outputs, ranks);
    EXPECT_EQ(split.world.broken, whole.world.broken);
    EXPECT_EQ(split.world.templates.size(), whole.world.templates.size());
  }
}

// Bonded assemblies thrown on a floor side by side, cut apart by the
// domains (docs/breakage.md): each domain holds the partners of its
// bodies' bonds, the bonds broken on one rank are told to every rank, and
// the bonds' energy is summed in bond order on rank 0.
TEST(Domains, BondedAssembliesThatCrackGiveTheSerialBits) {
  WorldSettings s;
  s.model = ContactModel::Volume;
  s.gravity = {0, 0, -9.81};
  WorldBuilder b(s);
  Material rock{.name = "rock", .density = 2500, .youngs_modulus = 1e7};
  rock.glue = {.tensile_strength = 3e4, .shear_strength = 3e4, .damping = 0.2};
  const std::uint32_t m = b.add_material(rock);
  b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor");
  for (int k = 0; k < 4; ++k)
    b.add_bonded({.shape = {Shape{Box{{0.01, 0.006, 0.008}}}, {}}, .pieces = 10, .seed = static_cast<std::uint64_t>(k + 1),
                  .material = m, .position = {0.025 * k - 0.0375, 0.002 * k, 0.0081}, .velocity = {0.1, 0, -1.0}});
  World world = b.build();
  const RunState plan = plan_run(0.012, critical_time_step(world), 0.001);
  Recorder serial;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed) << whole.outcome.error;
  const std::size_t broken = broken_bonds(whole.world.bonds);
  ASSERT_GT(broken, 5u);
  ASSERT_LT(broken, whole.world.bonds.size());
  for (const int ranks : {2, 3}) {
    Recorder domains;
    const Ended split = run_on(ranks, world, plan, domains);
    ASSERT_EQ(split.outcome.status, RunStatus::Completed) << split.outcome.error;
    expect_same(serial.outputs, domains.outputs, ranks);
    ASSERT_EQ(split.world.bonds.size(), whole.world.bonds.size());
    for (std::size_t k = 0; k < whole.world.bonds.size(); ++k) {
      EXPECT_EQ(split.world.bonds[k].intact, whole.world.bonds[k].intact) << ranks << " ranks, bond " << k;
      EXPECT_EQ(split.world.bonds[k].broken_time, whole.world.bonds[k].broken_time) << ranks << " ranks, bond " << k;
    }
  }
}

// Grains thrown sideways in a cell periodic across x and y, onto a floor:
// they wrap around while they fall through the cuts, touching across the
// cell's faces through their images; the cell's stress at the outputs is
// summed again on rank 0 in the order of the keys.
TEST(Domains, APeriodicCellGivesTheSerialBits) {
  WorldSettings s;
  s.model = ContactModel::Hertz;
  s.gravity = {0, 0, -9.81};
  s.periodic.axes[0] = s.periodic.axes[1] = true;
  s.periodic.lo = {-0.04, -0.04, 0};
  s.periodic.hi = {0.04, 0.04, 0};
  WorldBuilder b(s);
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e6, 0.25, 0.5, 0.6});
  b.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor");
  std::mt19937_64 rng(16);
  test::fill_polyhedra(b, {.count = 90, .variants = 4, .vertices = 10, .size = 0.012, .lo = {-0.035, -0.035, 0.01},
                           .hi = {0.035, 0.035, 0.12}, .material = rock},
                       rng);
  World world = b.build();
  for (Body& body : world.bodies) body.velocity = {0.4, 0.2, 0};
  const RunState plan = plan_run(0.15, critical_time_step(world), 0.015);
  Recorder serial;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed);
  ASSERT_GT(serial.outputs.back().stats.contacts, 50);
  for (const int ranks : {2, 3}) {
    Recorder domains;
    const Ended split = run_on(ranks, world, plan, domains);
    ASSERT_EQ(split.outcome.status, RunStatus::Completed);
    expect_same(serial.outputs, domains.outputs, ranks);
    for (int k = 0; k < 6; ++k)
      EXPECT_EQ(std::memcmp(&split.world.cell.stress[k], &whole.world.cell.stress[k], sizeof(Real)), 0) << k;
  }
}

// A run stopped on 3 ranks and continued on 2 from the whole world it left
// (what a checkpoint holds) ends with the serial run's bits.
TEST(Domains, AStoppedRunContinuesOnAnotherNumberOfRanks) {
  const World world = pour(ContactModel::Hertz);
  const RunState plan = plan_run(0.06, critical_time_step(world), 0.01);
  Recorder serial, domains;
  ASSERT_EQ(run_whole(world, plan, serial).outcome.status, RunStatus::Completed);
  const Ended first = run_on(3, world, plan, domains, plan.steps_total / 2);
  ASSERT_EQ(first.outcome.status, RunStatus::Stopped);
  ASSERT_EQ(first.state.step, plan.steps_total / 2);
  ASSERT_EQ(run_on(2, first.world, first.state, domains).outcome.status, RunStatus::Completed);
  expect_same(serial.outputs, domains.outputs, 3);
}

// A step listener (run.hpp) on every rank: a drag F = -beta v on the bodies
// each owns, every 2 steps, on 3 ranks and stopped on 3 and continued on 1,
// gives the serial bits, applied loads and their work included.
TEST(Domains, ADragListenerGivesTheSerialBitsOnAnyNumberOfRanks) {
  struct Drag : StepListener {
    std::uint64_t every() const override { return 2; }
    void before_forces(OwnedBodies bodies, const RunState&) override {
      for (std::size_t i = 0; i < bodies.world.bodies.size(); ++i)
        if (bodies.owns(i)) bodies.world.bodies[i].applied_force = bodies.world.bodies[i].velocity * -0.02;
    }
  } drag;
  StepListener* listeners[] = {&drag};
  const World world = pour(ContactModel::Volume);
  const RunState plan = plan_run(0.06, critical_time_step(world), 0.01);
  Recorder serial, domains, resumed;
  const Ended whole = run_whole(world, plan, serial, listeners);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed);
  Real work = 0;
  for (const Body& b : whole.world.bodies) work += b.applied_work;
  EXPECT_LT(work, 0);
  const Ended split = run_on(3, world, plan, domains, 0, nullptr, listeners);
  ASSERT_EQ(split.outcome.status, RunStatus::Completed);
  expect_same(serial.outputs, domains.outputs, 3);
  const Ended first = run_on(3, world, plan, resumed, plan.steps_total / 2 + 1, nullptr, listeners);
  ASSERT_EQ(first.outcome.status, RunStatus::Stopped);
  ASSERT_EQ(run_on(1, first.world, first.state, resumed, 0, nullptr, listeners).outcome.status, RunStatus::Completed);
  expect_same(serial.outputs, resumed.outputs, 3);
}

// The highest grain, owned by the top domain, becomes a sphere, which the
// volume law cannot clip: its domain fails, and the run stops on every
// rank with that domain's message, as the whole world's run does.
TEST(Domains, AFailingDomainStopsTheRunWithItsMessage) {
  World world = pour(ContactModel::Volume);
  std::size_t top = 0;
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (world.bodies[i].position.z > world.bodies[top].position.z) top = i;
  ShapeTemplate sphere = world.templates[world.bodies[top].shape];
  sphere.shape = make_sphere(sphere.reach);
  world.templates.push_back(sphere);
  world.bodies[top].shape = static_cast<std::uint32_t>(world.templates.size() - 1);
  const RunState plan = plan_run(0.2, critical_time_step(world), 0.02);
  ASSERT_EQ(layout_domains(world, 2).owner_of(world.bodies[top].position), 1);
  Recorder serial, domains;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Failed);
  ASSERT_NE(whole.outcome.error.find("body " + std::to_string(world.bodies[top].id)), std::string::npos)
      << whole.outcome.error;
  const Ended split = run_on(2, world, plan, domains);
  EXPECT_EQ(split.outcome.status, RunStatus::Failed);
  EXPECT_EQ(split.outcome.error, whole.outcome.error);
  EXPECT_EQ(split.state.step, whole.state.step);
}

// Grains in a cell periodic on every axis, squeezed by a servo towards a
// pressure while it shears fast enough that its tilt is taken back: every
// step the servo reads the whole stress (summed again from every domain's
// contacts), the cell's new field works on every domain's bodies, and the
// search cell is renewed when the whole world's would be, not when a
// domain's ghosts change.
TEST_P(Domains, AServoedShearingCellGivesTheSerialBits) {
  WorldSettings s;
  s.model = GetParam();
  s.gravity = {};
  s.periodic.axes[0] = s.periodic.axes[1] = s.periodic.axes[2] = true;
  s.periodic.lo = {0, 0, 0};
  s.periodic.hi = {0.06, 0.06, 0.06};
  for (int k = 0; k < 6; ++k) s.cell_control.mode[k] = CellMode::Stress, s.cell_control.value[k] = k < 3 ? 2e4 : 0;
  s.cell_control.mode[kXZ] = CellMode::StrainRate, s.cell_control.value[kXZ] = 8;
  s.cell_control.max_strain_rate = 5;
  WorldBuilder b(s);
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  std::mt19937_64 rng(17);
  test::fill_polyhedra(b, {.count = 150, .variants = 4, .vertices = 10, .size = 0.008, .lo = {0.003, 0.003, 0.003},
                           .hi = {0.057, 0.057, 0.057}, .material = rock},
                       rng);
  World world = b.build();
  std::uniform_real_distribution<Real> u(-0.2, 0.2);
  for (Body& body : world.bodies) body.velocity = {u(rng), u(rng), u(rng)};
  const RunState plan = plan_run(0.12, critical_time_step(world), 0.01);
  Recorder serial;
  const Ended whole = run_whole(world, plan, serial);
  ASSERT_EQ(whole.outcome.status, RunStatus::Completed) << whole.outcome.error;
  ASSERT_LT(whole.world.cell.now.tilt.y, 0) << "the tilt was taken back";
  ASSERT_LT(whole.world.cell.now.hi.x - whole.world.cell.now.lo.x, 0.045) << "the servo squeezed the cell";
  ASSERT_GT(serial.outputs.back().stats.contacts, 15);
  for (const int ranks : {2, 3}) {
    Recorder domains;
    DomainReport report;
    const Ended split = run_on(ranks, world, plan, domains, 0, &report);
    ASSERT_EQ(split.outcome.status, RunStatus::Completed);
    expect_same(serial.outputs, domains.outputs, ranks);
    EXPECT_EQ(std::memcmp(&split.world.cell.now, &whole.world.cell.now, sizeof(PeriodicCell)), 0) << ranks << " ranks";
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ(std::memcmp(&split.world.cell.rate[k], &whole.world.cell.rate[k], sizeof(Real)), 0) << k;
      EXPECT_EQ(std::memcmp(&split.world.cell.stress[k], &whole.world.cell.stress[k], sizeof(Real)), 0) << k;
    }
    double moved = 0;
    for (const DomainReport::Rank& r : report.ranks) moved += r.moved_out;
    EXPECT_GT(moved * static_cast<double>(report.steps), 5) << ranks << " ranks";
  }
}

}  // namespace
}  // namespace gjkdem::dem
