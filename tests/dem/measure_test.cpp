// Measurements (measure.hpp) against independent answers:
// - solid fraction: a lattice of cubes (exact fractions, the region cutting
//   cubes in halves), spheres cut by the region's faces (a half, a quarter,
//   an eighth), and a bed of random polyhedra in a random box against Monte
//   Carlo sampling with GJK point tests;
//   the images of grains across a periodic cell's faces counted;
// - stress: two grains pushed apart (worked by hand), and a bed at rest on a
//   floor, periodic across, whose vertical stress times the volume is
//   g sum m z (the virial theorem: the floor carries the weight);
// - coordination: contacts counted directly.
#include "gjkdem/dem/measure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dem/beds.hpp"
#include "shape/surface_shapes.hpp"
#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {
namespace {

Material rock() { return {"rock", 2500, 1e7, 0.25, 0.3, 0.5}; }

// Hertz: the templates keep the shapes as given (the volume law's are
// tessellated for the contact model).
World with_bodies(const std::vector<std::pair<Shape, Vec3>>& bodies) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder b(settings);
  const std::uint32_t m = b.add_material(rock());
  b.accept_initial_overlaps();
  for (const auto& [shape, at] : bodies) b.add_body({.shape = {shape, {}}, .material = m, .position = at});
  return b.build();
}

TEST(Measure, CubesOnALatticeFillExactlyTheirShare) {
  // Cubes of side 0.6 at spacing 1: a fraction of 0.216 in any box of whole cells.
  std::vector<std::pair<Shape, Vec3>> cubes;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) cubes.push_back({Shape{Box{{0.3, 0.3, 0.3}}}, Vec3{i + 0.5, j + 0.5, k + 0.5}});
  const World w = with_bodies(cubes);
  MeasureWorkspace work;
  EXPECT_NEAR(measure(w, {}, {{0, 0, 0}, {4, 4, 4}}, work).solid_fraction, 0.216, 1e-12);
  EXPECT_NEAR(measure(w, {}, {{1, 1, 1}, {3, 2, 4}}, work).solid_fraction, 0.216, 1e-12);
  // A box from the middle of a layer of cubes to 0.1 past the middle of the
  // next: the parts inside count (0.3 and 0.4 of each cube's height).
  const Measures cut = measure(w, {}, {{0, 0, 0.5}, {4, 4, 1.6}}, work);
  EXPECT_NEAR(cut.solid_volume, 16 * 0.36 * (0.3 + 0.4), 1e-12);
  EXPECT_EQ(cut.grains, 32u) << "the grains whose centres are inside, faces included";
  // One cube cut at 0.1 from its centre on x, and at its centre on y.
  EXPECT_NEAR(measure(w, {}, {{0.6, 0.5, 0.2}, {1.0, 1.0, 0.8}}, work).solid_volume, 0.2 * 0.3 * 0.6, 1e-12);
}

// A U-shaped surface grain (u_prism, in cm) is clipped as its own surface: a
// region over its left arm and its hollow holds the arm alone (its hull
// would hold 1.25 arms), and in any pose and region (boxes, and balls as
// their tessellation) it holds what the U made of its three boxes holds (a
// compound of convex parts, clipped exactly), the workspace kept from region
// to region.
TEST(Measure, ASurfaceGrainIsClippedAsItsOwnSurface) {
  gjkdem::test::Mesh u = gjkdem::test::u_prism(1);
  for (Vec3& v : u.vertices) v = v * 0.01;
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder builder(settings);
  const std::uint32_t m = builder.add_material(rock());
  builder.accept_initial_overlaps();
  builder.add_body({.shape = {.surface = std::make_shared<const Surface>(gjkdem::test::surface_of(u))}, .material = m});
  const auto box = [](const Vec3& lo, const Vec3& hi) {  // cm
    return PlacedShape{Shape{Box{(hi - lo) * 0.005}}, Transform::from((lo + hi) * 0.005, Quat{})};
  };
  builder.add_body({.shape = {.parts = {box({0, 0, 0}, {3, 1, 1}), box({0, 1, 0}, {1, 2, 1}), box({2, 1, 0}, {3, 2, 1})}},
                    .material = m,
                    .position = {0.1, 0, 0}});
  World w = builder.build();
  const auto place = [&](Body& body, const Quat& turn, const Vec3& at) {  // its shape frame at `at`, turned
    const ShapeTemplate& t = w.templates[body.shape];
    body.orientation = normalized(turn * t.principal.rotation);
    body.position = at + rotate(turn, t.unit_mass.centroid);
  };
  MeasureWorkspace work;
  for (Body& body : w.bodies) place(body, Quat{}, {0, 0, 0});
  const MeasureRegion arm_and_hollow{{-0.01, 0.01, -0.01}, {0.015, 0.03, 0.02}};
  EXPECT_NEAR(volume_inside(w, w.bodies[0], arm_and_hollow, work), 1e-6, 1e-18);
  EXPECT_NEAR(volume_inside(w, w.bodies[1], arm_and_hollow, work), 1e-6, 1e-18);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> unit(-1, 1);
  int cut = 0;  // regions holding part of the U
  for (int trial = 0; trial < 20; ++trial) {
    const Quat turn = normalized(Quat{unit(rng), unit(rng), unit(rng), unit(rng)});
    const Vec3 at{0.01 * unit(rng), 0.01 * unit(rng), 0.01 * unit(rng)};
    for (Body& body : w.bodies) place(body, turn, at);
    const Vec3 centre = w.bodies[0].position + 0.01 * Vec3{unit(rng), unit(rng), unit(rng)};
    const Vec3 half = 0.01 * Vec3{1.2 + unit(rng), 1.2 + unit(rng), 1.2 + unit(rng)};
    MeasureRegion region{centre - half, centre + half};
    if (trial % 4 == 3) region.round = RoundRegion{.kind = RoundRegion::Kind::Ball, .base = centre, .radius = half.x};
    const Real surface = volume_inside(w, w.bodies[0], region, work), boxes = volume_inside(w, w.bodies[1], region, work);
    EXPECT_NEAR(surface, boxes, 1e-12 * 5e-6) << trial;
    cut += boxes > 0 && boxes < 5e-6 * (1 - 1e-9);
  }
  EXPECT_GE(cut, 10);
}

// A thin shell counts as its plates: a square plate 10 cm wide, 2 mm thick,
// tilted, with 0.3 of its width inside a box region holds 0.3 of its volume,
// and flat across a cylinder of radius 3 cm the disc's area times its
// thickness (the cylinder's tessellation inscribed: 2e-3).
TEST(Measure, AShellCountsTheAreaOfItsPlatesInsideTimesItsThickness) {
  WorldSettings settings;
  settings.model = ContactModel::Hertz;
  WorldBuilder builder(settings);
  const std::uint32_t m = builder.add_material(rock());
  const Real h = 0.05, thickness = 0.002;
  builder.add_body({.shape = {.shell = std::make_shared<const Shell>(make_shell(
                                  {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}}, {{{0, 1, 2}}, {{0, 2, 3}}}, thickness))},
                    .material = m});
  World w = builder.build();
  Body& plate = w.bodies[0];
  const ShapeTemplate& t = w.templates[plate.shape];
  const Real full = 2 * h * 2 * h * thickness;
  EXPECT_NEAR(t.unit_mass.volume, full, 1e-18);
  MeasureWorkspace work;
  plate.orientation = normalized(quat_from_axis_angle({1, 0, 0}, 0.5) * t.principal.rotation);
  plate.position = rotate(quat_from_axis_angle({1, 0, 0}, 0.5), t.unit_mass.centroid);
  EXPECT_NEAR(volume_inside(w, plate, {{0.02, -1, -1}, {1, 1, 1}}, work), 0.3 * full, 1e-15);
  EXPECT_EQ(volume_inside(w, plate, {{0.06, -1, -1}, {1, 1, 1}}, work), 0);
  plate.orientation = t.principal.rotation;
  plate.position = t.unit_mass.centroid;
  MeasureRegion disc;
  disc.round = RoundRegion{.base = {0, 0, -0.01}, .axis = {0, 0, 1}, .radius = 0.03, .height = 0.02};
  EXPECT_NEAR(volume_inside(w, plate, disc, work) / (kPi * 0.03 * 0.03 * thickness), 1, 2e-3);
}

TEST(Measure, SpheresCutByTheRegionKeepTheirPartInside) {
  const Real r = 0.5, full = 4.0 / 3.0 * kPi * r * r * r;
  const World w = with_bodies({{Shape{Point{}, r}, Vec3{0, 0, 0}}});
  MeasureWorkspace work;
  // Curved shapes are clipped as tessellations scaled to the true volume.
  EXPECT_NEAR(volume_inside(w, w.bodies[0], {{-1, -1, -1}, {1, 1, 1}}, work), full, 1e-12);
  EXPECT_NEAR(volume_inside(w, w.bodies[0], {{0, -1, -1}, {1, 1, 1}}, work) / full, 0.5, 2e-3);
  EXPECT_NEAR(volume_inside(w, w.bodies[0], {{0, 0, -1}, {1, 1, 1}}, work) / full, 0.25, 2e-3);
  EXPECT_NEAR(volume_inside(w, w.bodies[0], {{0, 0, 0}, {1, 1, 1}}, work) / full, 0.125, 2e-3);
  EXPECT_EQ(volume_inside(w, w.bodies[0], {{0.5, -1, -1}, {1, 1, 1}}, work), 0);
  // A cap of height h = r/2: pi h^2 (3r - h) / 3.
  const Real h = r / 2, cap = kPi * h * h * (3 * r - h) / 3;
  EXPECT_NEAR(volume_inside(w, w.bodies[0], {{-1, -1, r - h}, {1, 1, 1}}, work) / cap, 1, 5e-3);
}

// Whether a template is clipped exactly or as a tessellation depends on its
// shape, not on the first body met: an ellipsoid near the region but not in
// it (overlap() says empty before it says unsupported) must not make the next
// one, cut in half by the region's face, count nothing.
TEST(Measure, ACurvedGrainNearTheRegionDoesNotHideTheNextOnesVolume) {
  const Shape ellipsoid{Ellipsoid{{0.5, 0.1, 0.1}}};
  // The first lies along x beside the region (its reach, 0.5, reaches in; the
  // ellipsoid, 0.1 thick in y, does not); the second straddles x = 0.
  const World w = with_bodies({{ellipsoid, Vec3{0.2, 1.35, 0}}, {ellipsoid, Vec3{0, 0, 0}}});
  MeasureWorkspace work;
  const MeasureRegion region{{0, -1, -1}, {2, 1, 1}};
  EXPECT_EQ(volume_inside(w, w.bodies[0], region, work), 0);
  const Real full = 4.0 / 3.0 * kPi * 0.5 * 0.1 * 0.1;
  EXPECT_NEAR(volume_inside(w, w.bodies[1], region, work) / full, 0.5, 2e-3);
}

// A bed of random polyhedra (placed without overlap) in a box that cuts many
// of them, against the fraction of random points that fall in a grain.
// The fraction of 200,000 points drawn by `draw` that lie in a body, and its
// standard error.
template <class Draw>
std::pair<Real, Real> monte_carlo_fraction(const World& w, Draw draw) {
  const Shape point{Point{}};
  const int samples = 200000;
  int hits = 0;
  for (int k = 0; k < samples; ++k) {
    const Vec3 p = draw();
    for (const Body& body : w.bodies)
      if (length(p - body.position) < w.templates[body.shape].reach &&
          intersect(point, Transform::from(p, Quat{}), w.templates[body.shape].shape, shape_pose(w, body))) {
        ++hits;
        break;
      }
  }
  const Real fraction = static_cast<Real>(hits) / samples;
  return {fraction, std::sqrt(fraction * (1 - fraction) / samples)};
}

TEST(Measure, ABedsSolidFractionMatchesMonteCarlo) {
  WorldBuilder b;
  const std::uint32_t m = b.add_material(rock());
  std::mt19937_64 rng(11);
  test::fill_polyhedra(b, {.count = 120, .variants = 6, .vertices = 9, .size = 0.2, .lo = {0, 0, 0}, .hi = {1.2, 1.2, 1.2}, .material = m},
                       rng);
  const World w = b.build();
  const MeasureRegion region{{0.17, 0.23, 0.11}, {0.93, 0.71, 1.0}};
  MeasureWorkspace work;
  const Measures measured = measure(w, {}, region, work);
  std::uniform_real_distribution<Real> u(0, 1);
  const auto [fraction, sigma] = monte_carlo_fraction(w, [&] {
    return Vec3{region.lo.x + u(rng) * (region.hi.x - region.lo.x), region.lo.y + u(rng) * (region.hi.y - region.lo.y),
                region.lo.z + u(rng) * (region.hi.z - region.lo.z)};
  });
  EXPECT_GT(measured.solid_fraction, 0.04);
  EXPECT_NEAR(measured.solid_fraction, fraction, 4 * sigma) << "Monte Carlo: " << fraction << " +- " << sigma;
}

// A tilted cylinder and a ball (round_region.hpp) over the same bed: the
// solid fraction against Monte Carlo points drawn uniformly in them; a
// cylinder's flat caps clip a cube exactly, and a body deep inside counts
// whole.
TEST(Measure, CylindersAndBallsMatchMonteCarloAndCutCubesExactly) {
  WorldBuilder b;
  const std::uint32_t m = b.add_material(rock());
  std::mt19937_64 rng(12);
  test::fill_polyhedra(b, {.count = 120, .variants = 6, .vertices = 9, .size = 0.2, .lo = {0, 0, 0}, .hi = {1.2, 1.2, 1.2}, .material = m},
                       rng);
  const World w = b.build();
  for (const RoundRegion& g : {RoundRegion{.base = {0.3, 0.4, 0.2}, .axis = {0.3, 0.2, 1}, .radius = 0.35, .height = 0.7},
                               RoundRegion{.kind = RoundRegion::Kind::Ball, .base = {0.6, 0.6, 0.6}, .radius = 0.45}}) {
    SCOPED_TRACE(g.kind == RoundRegion::Kind::Ball ? "ball" : "cylinder");
    MeasureRegion region;
    region.round = g;
    MeasureWorkspace work;
    const Measures measured = measure(w, {}, region, work);
    EXPECT_DOUBLE_EQ(measured.region_volume, round_volume(g));
    std::uniform_real_distribution<Real> u(0, 1);
    const auto [fraction, sigma] = monte_carlo_fraction(w, [&] { return round_point(g, u(rng), u(rng), u(rng)); });
    EXPECT_GT(measured.solid_fraction, 0.04);
    EXPECT_NEAR(measured.solid_fraction, fraction, 4 * sigma + 2e-3) << "Monte Carlo: " << fraction << " +- " << sigma;
  }
  // A cube of side 0.2 cut by the caps of a wide cylinder 0.1 high through its middle: a slab of 0.2 x 0.2 x 0.1;
  // a ball of radius 2 holds the cube whole.
  const World cube = with_bodies({{Shape{Box{{0.1, 0.1, 0.1}}}, Vec3{}}});
  MeasureRegion slab, ball;
  slab.round = RoundRegion{.base = {0, 0, -0.05}, .axis = {0, 0, 1}, .radius = 1.0, .height = 0.1};
  ball.round = RoundRegion{.kind = RoundRegion::Kind::Ball, .base = {0.01, 0, 0}, .radius = 2.0};
  MeasureWorkspace work;
  EXPECT_NEAR(measure(cube, {}, slab, work).solid_volume, 0.004, 1e-15);
  EXPECT_DOUBLE_EQ(measure(cube, {}, ball, work).solid_volume, 0.008);
  EXPECT_EQ(measure(cube, {}, slab, work).grains, 1u);
  MeasureRegion flat;
  flat.round = RoundRegion{.radius = 1.0, .height = 0};
  EXPECT_THROW(measure(cube, {}, flat, work), std::invalid_argument);
}

// Two grains pushed apart by a force F along x at a contact halfway: the
// stress is 2 r F / V on xx (compression positive), zero elsewhere.
TEST(Measure, TwoGrainsPushedApartCompressAlongTheirLine) {
  const Real r = 0.1, force = 3;
  const World w = with_bodies({{Shape{Point{}, r}, Vec3{0, 0, 0}}, {Shape{Point{}, r}, Vec3{2 * r, 0, 0}}});
  const MeasuredContact c{0, false, 1, {r, 0, 0}, {1, 0, 0}, {force, 0, 0}};
  MeasureWorkspace work;
  const MeasureRegion region{{-1, -1, -1}, {1, 1, 1}};
  const Measures m = measure(w, {&c, 1}, region, work);
  EXPECT_NEAR(m.stress.row[0].x, 2 * r * force / 8, 1e-15);
  EXPECT_NEAR(m.pressure, 2 * r * force / 8 / 3, 1e-15);
  EXPECT_EQ(m.stress.row[1].y, 0);
  EXPECT_EQ(m.stress.row[0].y, 0);
  EXPECT_EQ(m.coordination, 1);
  EXPECT_EQ(m.contacts, 1u);
  EXPECT_EQ(m.mean_normal_force, force);
  // Only the second grain in the region: its half of the sum, and its contact.
  const Measures half = measure(w, {&c, 1}, {{0.15, -1, -1}, {1, 1, 1}}, work);
  EXPECT_EQ(half.grains, 1u);
  EXPECT_NEAR(half.stress.row[0].x * half.region_volume, r * force, 1e-15);
}

/// The weight's moment, g sum m z over the moving bodies (the Love-Weber
/// vertical stress times the volume of a bed at rest).
Real weight_moment_of(const World& w) {
  Real sum = 0;
  for (const Body& body : w.bodies)
    if (!body.fixed) sum += -w.settings.gravity.z * mass_of(w, body) * body.position.z;
  return sum;
}

/// Sums, over the outputs from `from` seconds on, the bed's measured
/// vertical stress times the region's volume and the weight's moment.
struct WeightAverager : RunObserver {
  MeasureRegion region;
  Real from = 0, stress_sum = 0, weight_sum = 0;
  int samples = 0;
  MeasureWorkspace work;
  void on_output(const World& w, const RunState& state) override {
    if (static_cast<Real>(state.step) * state.dt < from) return;
    const Measures m = measure(w, touching_contacts(w), region, work);
    stress_sum += m.stress.row[2].z * m.region_volume;
    weight_sum += weight_moment_of(w);
    ++samples;
  }
};

// 60 polyhedra settled on a floor in a cell periodic on x and y. At rest the
// floor carries the weight and the Love-Weber vertical stress of the whole
// bed is g sum m z / V; with the bodies' own forces it is exact at any time.
// The bed still rocks (kinetic energy about 4e-4 of the potential: flat
// faces on Hertz's single points), and its stress swings by +-3% about the
// weight (0.985, 1.026, 0.974 at 1.5, 2 and 2.5 s), so the weight is
// compared with the stress's mean over the last half second: bounded motion
// averages sum z m a_z = d/dt(sum z m v_z) - sum m v_z^2 to at most twice
// the kinetic energy.
TEST(Measure, ABedAtRestCarriesItsWeight) {
  WorldSettings s;
  s.model = ContactModel::Hertz;
  s.periodic.axes[0] = s.periodic.axes[1] = true;
  s.periodic.hi = {0.08, 0.08, 0};
  WorldBuilder b(s);
  const std::uint32_t m = b.add_material({"rock", 2500, 1e7, 0.25, 0.1, 0.5});
  b.add_plane({}, {0, 0, 1}, m, "floor");
  std::mt19937_64 rng(4);
  test::fill_polyhedra(b, {.count = 60, .size = 0.012, .lo = {0, 0, 0}, .hi = {0.08, 0.08, 0.05}, .material = m}, rng);
  World w = b.build();
  RunState run = plan_run(1.5, critical_time_step(w), 0.01);
  const MeasureRegion region{{0, 0, -0.01}, {0.08, 0.08, 0.1}};  // grains press a little into the floor
  WeightAverager average;
  average.region = region;
  average.from = 1.0;
  RunObserver* observers[] = {&average};
  ASSERT_EQ(dem::run(w, run, observers).status, RunStatus::Completed);
  ASSERT_LT(kinetic_energy(w), 1e-3 * potential_energy(w)) << "the bed should be at rest";

  const std::vector<MeasuredContact> contacts = touching_contacts(w);
  MeasureWorkspace work;
  const Measures measured = measure(w, contacts, region, work);
  ASSERT_EQ(measured.grains, 60u);
  Real exact = 0;
  std::size_t ends = 0;
  for (const Body& body : w.bodies) {
    if (body.fixed) continue;
    const Real mass = mass_of(w, body);
    // -(sum over contacts of z_c f_z) + z_p (F - m g)_z: the contacts between grains cancel.
    exact += body.position.z * (body.force.z - mass * w.settings.gravity.z);
  }
  for (const MeasuredContact& c : contacts) {
    ends += c.first_is_plane ? 1 : 2;
    if (c.first_is_plane) exact -= c.point.z * c.force.z;  // the floor's contacts, at about z = 0
  }
  const Real vertical = measured.stress.row[2].z * measured.region_volume;
  EXPECT_NEAR(vertical, exact, 1e-9 * std::fabs(exact));
  ASSERT_GE(average.samples, 50);
  EXPECT_NEAR(average.stress_sum / average.weight_sum, 1, 0.01);
  RecordProperty("mean_stress_over_weight", std::to_string(average.stress_sum / average.weight_sum));
  EXPECT_NEAR(measured.coordination, static_cast<Real>(ends) / 60, 1e-12);
  EXPECT_GT(measured.coordination, 2);
  // The region spans the cell: every grain counts whole, across the faces too.
  Real volume = 0, straddling = 0;
  for (const Body& body : w.bodies) {
    if (body.fixed) continue;
    volume += w.templates[body.shape].unit_mass.volume;
    const Real reach = w.templates[body.shape].reach;
    straddling += body.position.x < reach || body.position.x > 0.08 - reach;
  }
  EXPECT_GT(straddling, 5);
  EXPECT_NEAR(measured.solid_volume, volume, 1e-9 * volume);
}

}  // namespace
}  // namespace gjkdem::dem
