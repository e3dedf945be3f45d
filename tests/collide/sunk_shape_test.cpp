// A small shape sunk into the side of a large cone (issue 12's first class:
// a cylinder of 0.14 sunk 0.026 into a cone of 4.5 came out "intersecting,
// depth 0, an unrelated normal"). EPA converged to 1e-11 on the curved
// boundary, then round-off turned a sliver face inside out, it took over as
// the closest face and EPA wandered to its iteration cap.
//
// The small shape's centre lies `sink` below the cone's side, far from its
// rim and apex, so any separating translation moves it at least `sink`, and
// one of sink + its bounding radius along the side's normal suffices.
#include <gtest/gtest.h>

#include <random>

#include "gjkdem/collide/query.hpp"

namespace gjkdem {
namespace {

TEST(SunkShape, DepthIsBoundedByTheSinkAtEverySizeRatio) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<Real> u(0, 1);
  int failures = 0, checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Real scale = std::pow(10.0, -2 + 2.5 * u(rng));  // the cone: 0.01 to 3 high
    const Real radius = 2 * scale, half_height = scale;
    const Shape cone{Cone{radius, half_height}};
    const Real small = scale * std::pow(10.0, -2.5 + 2 * u(rng));  // 1e-2.5 to 1e-0.5 of the cone
    Shape shape;
    switch (trial % 3) {
      case 0: shape = Shape{Cylinder{small * (0.5 + u(rng)), small * (0.5 + u(rng))}}; break;
      case 1: shape = Shape{Ellipsoid{{small * (0.5 + u(rng)), small * (0.5 + u(rng)), small * (0.5 + u(rng))}}}; break;
      default: shape = Shape{Box{{small * (0.5 + u(rng)), small * (0.5 + u(rng)), small * (0.5 + u(rng))}}}; break;
    }
    // A point of the side, away from rim and apex by more than the small shape.
    const Real reach = bounding_radius(shape);
    const Real z = -half_height + 2 * reach + (2 * half_height - 4 * reach) * (0.15 + 0.7 * u(rng));
    if (!(z > -half_height + 2 * reach && z < half_height - 2 * reach)) continue;
    const Real phi = 2 * kPi * u(rng);
    const Real r = radius * (half_height - z) / (2 * half_height);
    const Vec3 side{r * std::cos(phi), r * std::sin(phi), z};
    const Vec3 normal = normalized(Vec3{2 * half_height * std::cos(phi), 2 * half_height * std::sin(phi), radius});
    const Real sink = reach * (0.05 + 0.9 * u(rng));
    const Quat q = normalized(Quat{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
    const Transform pose = Transform::from(side - normal * sink, q);
    ++checked;
    const PenetrationResult ab = penetration(shape, pose, cone, {});
    const PenetrationResult ba = penetration(cone, {}, shape, pose);
    const Real tol = 1e-9 * scale;
    for (const PenetrationResult* p : {&ab, &ba}) {
      const bool ok = p->intersect && p->depth >= sink - tol && p->depth <= sink + reach + tol;
      if (!ok && ++failures <= 5)
        ADD_FAILURE() << "trial " << trial << (p == &ab ? " (small first)" : " (cone first)") << ": depth " << p->depth
                      << " for a sink of " << sink << " (reach " << reach << ", cone " << scale << ")";
    }
    EXPECT_NEAR(ab.depth, ba.depth, 1e-7 * ab.depth) << "trial " << trial << ": A and B swapped";
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(checked, 2500);
}

}  // namespace
}  // namespace gjkdem
