// Nearly parallel faces a hair apart (issue 12, FCL's issue 388 setting): a
// small box tilted by 1e-9 to 1e-5 rad hovers 1e-9 to 1e-6 above the top face
// of a large one. The exact distance is the height of the small box's lowest
// corner above that face (the box lies over the face's interior). GJK's
// closest point on a triangle used to be the weighted sum of its vertices,
// whose direction was off by eps * size / |v|; the next support point then
// came back already in the simplex and GJK stopped up to 8x too far, in
// either argument order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem {
namespace {

TEST(ParallelFaces, DistanceIsTheLowestCornersHeightInBothOrders) {
  std::mt19937_64 rng(388);
  std::uniform_real_distribution<Real> u(0, 1);
  int checked = 0;
  Real worst = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 hb{0.3 + u(rng), 0.3 + u(rng), 0.01 + u(rng)};
    const Vec3 ha{0.005 + 0.045 * u(rng), 0.005 + 0.045 * u(rng), 0.005 + 0.045 * u(rng)};
    const Real tilt = std::pow(10.0, -9 + 4 * u(rng)), gap = std::pow(10.0, -9 + 3 * u(rng));
    const Real turn = 2 * kPi * u(rng);
    const Quat q = quat_from_axis_angle({std::cos(turn), std::sin(turn), 0}, tilt);
    Real lowest = 1;
    for (int c = 0; c < 8; ++c)
      lowest = std::min(lowest, rotate(q, {c & 1 ? ha.x : -ha.x, c & 2 ? ha.y : -ha.y, c & 4 ? ha.z : -ha.z}).z);
    const Vec3 centre{(2 * u(rng) - 1) * (hb.x - 0.2), (2 * u(rng) - 1) * (hb.y - 0.2), hb.z + gap - lowest};
    const Transform pose_a = Transform::from(centre, q);
    const Real exact = centre.z + lowest - hb.z;  // as the pose places it, to round-off
    // Boxes, and the same boxes as polytopes (another support function).
    std::vector<Vec3> ca, cb;
    for (int c = 0; c < 8; ++c) {
      ca.push_back({c & 1 ? ha.x : -ha.x, c & 2 ? ha.y : -ha.y, c & 4 ? ha.z : -ha.z});
      cb.push_back({c & 1 ? hb.x : -hb.x, c & 2 ? hb.y : -hb.y, c & 4 ? hb.z : -hb.z});
    }
    const Shape shapes[2][2] = {{Shape{Box{ha}}, Shape{Box{hb}}}, {Shape{make_polytope(ca)}, Shape{make_polytope(cb)}}};
    for (const auto& [a, b] : shapes) {
      const Real ab = distance(a, pose_a, b, {}).distance, ba = distance(b, {}, a, pose_a).distance;
      // Round-off: the corner heights carry about eps * size.
      const Real tol = 1e-5 * exact + 1e-14;
      EXPECT_NEAR(ab, exact, tol) << "trial " << trial << " A first, tilt " << tilt << " gap " << gap;
      EXPECT_NEAR(ba, exact, tol) << "trial " << trial << " B first, tilt " << tilt << " gap " << gap;
      worst = std::max({worst, std::fabs(ab - exact) / exact, std::fabs(ba - exact) / exact});
      ++checked;
    }
  }
  EXPECT_EQ(checked, 4000);
  RecordProperty("worst_relative_error", std::to_string(worst));
}

}  // namespace
}  // namespace gjkdem
