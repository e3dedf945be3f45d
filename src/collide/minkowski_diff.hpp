#pragma once
// Support mapping of A - B expressed in A's local frame: B's pose relative to A
// is computed once per pair, so support calls stay in small local coordinates
// (round-off follows the shapes' size, not their distance from the world origin).
#include "gjkdem/collide/simplex.hpp"
#include "gjkdem/math/transform.hpp"

namespace gjkdem::detail {

template <class CoreA, class CoreB>
struct MinkowskiDiff {
  using TypeA = CoreA;
  using TypeB = CoreB;
  const CoreA& a;
  const CoreB& b;
  Transform b_in_a;  ///< B's local frame as seen from A's
  int hint_a = 0;
  int hint_b = 0;

  /// Support point of A - B in direction d (frame A, need not be unit).
  SupportPoint support(const Vec3& d) noexcept {
    const Vec3 pa = gjkdem::support(a, d, hint_a);
    const Vec3 pb = apply(b_in_a, gjkdem::support(b, apply_inverse_rotation(b_in_a, -d), hint_b));
    return {pa - pb, pa, pb, d};
  }
};

}  // namespace gjkdem::detail
