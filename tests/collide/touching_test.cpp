// Touching to round-off: intersect() must say what penetration() and
// distance() say. The boolean test took any separating plane, however thin,
// while the distance loop counts cores closer than kGjkTouchTol x size as
// touching, so FCL's kissing boxes 1e-16 apart (face against face) were
// "apart" for one and "intersecting" for the others. Here boxes, and the same
// boxes as polytopes, turned alike, face against face with gaps from 0 to
// 1e-9 of their size, at sizes 1e-3 to 1e3, in both orders.
#include <gtest/gtest.h>

#include <random>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem {
namespace {

std::vector<Vec3> corners(const Vec3& h) {
  std::vector<Vec3> c;
  for (int k = 0; k < 8; ++k) c.push_back({k & 1 ? h.x : -h.x, k & 2 ? h.y : -h.y, k & 4 ? h.z : -h.z});
  return c;
}

TEST(Touching, EveryQueryAgreesOnContactAtTheRoundOffFloor) {
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<Real> u(0, 1);
  int mismatches = 0, touching = 0, apart = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Real size = std::pow(10.0, -3 + 6 * u(rng));
    const Vec3 ha = Vec3{0.2 + u(rng), 0.2 + u(rng), 0.2 + u(rng)} * size;
    const Vec3 hb = Vec3{0.2 + u(rng), 0.2 + u(rng), 0.2 + u(rng)} * size;
    const Quat q = random_rotation(rng);
    const Real gap = trial % 5 == 0 ? 0 : size * std::pow(10.0, -17 + 8 * u(rng));
    // B beside A along A's local x, sliding within the overlap of the faces.
    const Vec3 local{ha.x + hb.x + gap, (u(rng) - 0.5) * ha.y, (u(rng) - 0.5) * ha.z};
    const Vec3 centre = Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5} * size;
    const Transform pa = Transform::from(centre, q), pb = Transform::from(centre + rotate(q, local), q);
    const Shape pairs[2][2] = {{Shape{Box{ha}}, Shape{Box{hb}}},
                               {Shape{make_polytope(corners(ha))}, Shape{make_polytope(corners(hb))}}};
    for (const auto& [a, b] : pairs) {
      const bool hit = intersect(a, pa, b, pb), hit_ba = intersect(b, pb, a, pa);
      const bool pen = penetration(a, pa, b, pb).intersect, dist = distance(a, pa, b, pb).intersect;
      touching += pen;
      apart += !pen;
      if ((hit != pen || hit_ba != pen || dist != pen) && ++mismatches <= 5)
        ADD_FAILURE() << "trial " << trial << " gap " << gap / size << " x size: intersect " << hit << "/" << hit_ba
                      << ", penetration " << pen << ", distance " << dist;
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(touching, 1000);  // the zero gaps and those below the touch tolerance
  EXPECT_GT(apart, 1000);     // gaps well above it
}

}  // namespace
}  // namespace gjkdem
