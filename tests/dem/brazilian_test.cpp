// The Brazilian test of a bonded assembly (issue 31, docs/breakage.md): a
// disc of 50 mm across and 20 mm thick, cut into 100 glued Voronoi pieces,
// pressed between two platens along its diameter (z) until it splits.
#include <gtest/gtest.h>

#include <cmath>

#include "gjkdem/dem/bonds.hpp"
#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kRadius = 0.025, kHalfThick = 0.01;

struct Brazilian {
  Real peak = 0;          // N, on the top platen
  int broken = 0, bonds = 0;
  Real broken_x = 0;      // mean |x| of the broken bonds' faces (m): the loaded diameter is x = 0
  Real all_x = 0;
};

Brazilian brazilian(Real tensile, Real shear, std::uint64_t seed, std::uint32_t pieces, Real speed) {
  WorldSettings s;
  s.gravity = {};
  WorldBuilder b(s);
  Material m{.name = "rock", .density = 2500, .youngs_modulus = 1e8, .poisson_ratio = 0.2, .friction = 0.5};
  m.glue = {.tensile_strength = tensile, .shear_strength = shear};
  const std::uint32_t rock = b.add_material(m);
  const std::uint32_t down = b.add_motion({.velocity = {0, 0, -speed}}, "press");
  b.add_plane({0, 0, -kRadius}, {0, 0, 1}, rock, "floor");
  b.add_plane({0, 0, kRadius}, {0, 0, -1}, rock, "plate", down);
  const Quat axis_y = quat_from_axis_angle({1, 0, 0}, kPi / 2);
  b.add_bonded({.shape = {Shape{Cylinder{kRadius, kHalfThick}}, {}}, .pieces = pieces, .seed = seed,
                .material = rock, .rotation = axis_y, .label = "disc"});
  World w = b.build();
  const Real dt = critical_time_step(w);
  Brazilian out;
  out.bonds = static_cast<int>(w.bonds.size());
  // Until the force falls to half its peak once bonds have broken.
  for (int k = 0; k < 40000; ++k) {
    if (step(w, dt).status != StepStatus::Ok) {
      ADD_FAILURE() << "the step failed at t = " << w.time;
      break;
    }
    Real f = 0;
    for (const StepContact& c : w.results.contacts)
      if (c.active && c.a_is_plane && c.a == 1) f -= c.force.z;  // the plate's push on the disc is -z
    out.peak = std::fmax(out.peak, f);
    if (f < 0.5 * out.peak && broken_bonds(w.bonds) > 0) break;
  }
  for (const Bond& bond : w.bonds) {
    const Body* a = nullptr;
    for (const Body& body : w.bodies) if (body.id == bond.a) a = &body;
    const Real x = std::fabs((a->position + rotate(a->orientation, bond.point_a)).x);
    out.all_x += x;
    if (!bond.intact) ++out.broken, out.broken_x += x;
  }
  out.all_x /= out.bonds;
  if (out.broken) out.broken_x /= out.broken;
  return out;
}

// The relation, as docs/breakage.md derives and states it: the splitting
// tensile strength 2 F / (pi D t) at the peak force F is c times the bonds'
// tensile strength, c = 0.466 for discs of 100 pieces (7 across); the
// affine estimate from the bonds' stiffnesses is 0.527, above it by the
// disorder of the pieces. Checked at three strengths over three discs each:
// the mean within 10% of c sigma_t (the relation is a proportion), every
// disc's crack along the loaded diameter (x = 0).
constexpr Real kSplitRatio = 0.466;

void expect_splitting_strength(Real tensile) {
  Real mean = 0;
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Brazilian r = brazilian(tensile, 4 * tensile, seed, 100, 0.02);
    const Real split = 2 * r.peak / (kPi * 2 * kRadius * 2 * kHalfThick);
    mean += split / 3;
    EXPECT_GT(r.broken, 0);
    EXPECT_LT(r.broken_x, 0.65 * r.all_x) << "seed " << seed << ": the crack is not along the loaded diameter";
    EXPECT_GT(split, 0.8 * kSplitRatio * tensile) << "seed " << seed;
    EXPECT_LT(split, 1.2 * kSplitRatio * tensile) << "seed " << seed;
  }
  EXPECT_NEAR(mean, kSplitRatio * tensile, 0.1 * kSplitRatio * tensile);
}

TEST(Brazilian, SplittingStrengthIsTheStatedShareOfABondStrengthOf50kPa) { expect_splitting_strength(5e4); }
TEST(Brazilian, SplittingStrengthIsTheStatedShareOfABondStrengthOf100kPa) { expect_splitting_strength(1e5); }
TEST(Brazilian, SplittingStrengthIsTheStatedShareOfABondStrengthOf200kPa) { expect_splitting_strength(2e5); }

}  // namespace
}  // namespace gjkdem::dem
