#pragma once
// GJK on a Minkowski difference (Gilbert, Johnson and Keerthi 1988; the seed
// text's Algorithm 14; termination after van den Bergen, "Collision Detection in
// Interactive 3D Environments", 2003, section 4.3).
//
// One loop serves both queries. The boolean test returns as soon as a support
// point fails to pass the origin (a separating plane, Algorithm 14 line 5) or a
// tetrahedron encloses it. The distance query runs until the duality gap
// |v|^2 - v.w is within the tolerances, or until no support point improves v
// (round-off floor), keeping the best simplex seen.
#include "gjkdem/collide/settings.hpp"
#include "gjkdem/collide/status.hpp"
#include "minkowski_diff.hpp"

namespace gjkdem::detail {

struct GjkOutput {
  GjkStatus status = GjkStatus::Separated;
  Simplex simplex;  ///< its barycentric combination is v
  Vec3 v;           ///< closest point of A - B to the origin found (frame A)
  int iterations = 0;
  /// Separated, but stopped at the round-off floor before the duality gap
  /// met the tolerances (the next support point could not shorten v).
  bool stalled = false;
};

enum class GjkMode { Distance, Boolean };

/// `margin` (sum of both margins) only matters for Boolean: cores closer than it
/// intersect, and a separating plane must clear it.
/// `warm`/`warm_size`: search directions to replay first (a previous simplex),
/// or none; `v` is the cold start guess, a point of A - B.
template <class MD>
GjkOutput gjk(MD& md, Vec3 v, const Vec3* warm, int warm_size, Real size, Real margin, GjkMode mode,
              const QuerySettings& st) noexcept {
  GjkOutput out;
  Simplex& s = out.simplex;
  const Real touch_sq = (st.touch_tol * size) * (st.touch_tol * size);
  int it = 1;
  if (warm_size > 0) {
    for (int k = 0; k < warm_size; ++k) s.p[k] = md.support(warm[k]);
    s.size = warm_size;
    v = reduce_to_closest(s);
    it = warm_size;
    if (s.size == 4) {
      out.status = GjkStatus::Intersecting;
      out.iterations = it;
      out.v = {};
      return out;
    }
  } else {
    if (!(dot(v, v) > 0)) v = {1, 0, 0};
    s.p[0] = md.support(-v);
    s.size = 1;
    s.lambda[0] = 1;
    v = s.p[0].w;
  }
  for (;; ++it) {
    out.iterations = it;
    const Real dist_sq = dot(v, v);
    if (dist_sq <= touch_sq) { out.status = GjkStatus::Intersecting; break; }
    if (it > st.max_gjk_iterations) { out.status = GjkStatus::MaxIterations; break; }
    const SupportPoint w = md.support(-v);
    const Real vw = dot(v, w.w);
    if (mode == GjkMode::Boolean) {
      // v.w / |v| is a lower bound on the core distance; it must clear the
      // margins, or the touch tolerance of cores, as penetration()'s answer does.
      const Real clear = std::fmax(margin, st.touch_tol * size);
      if (vw > 0 && vw * vw > clear * clear * dist_sq) { out.status = GjkStatus::Separated; break; }
      if (dist_sq <= margin * margin) { out.status = GjkStatus::Intersecting; break; }
    }
    const Real gap = dist_sq - vw;
    if (gap <= st.gjk_rel_tol * dist_sq || gap * gap <= (st.gjk_abs_tol * size) * (st.gjk_abs_tol * size) * dist_sq) {
      out.status = GjkStatus::Separated;
      break;
    }
    bool repeated = false;
    for (int m = 0; m < s.size; ++m) repeated |= (s.p[m].w == w.w);
    if (repeated) { out.status = GjkStatus::Separated; out.stalled = true; break; }

    s.p[s.size++] = w;
    detail::SubSimplex r = closest_sub_simplex(s);
    // The new point was dropped although it lies beyond v (gap > 0): a
    // simplex too flat for its signs. Its nearest facet decides.
    if (r.mask != 15 && !(r.dist_sq < dist_sq)) r = nearest_facet(s);
    // No progress means the round-off floor is reached: drop the new point
    // and keep the best simplex seen (a nearly flat simplex can reduce to a
    // far worse point: a point 1e-12 off a cylinder came out 0.66 apart).
    if (r.mask != 15 && !(r.dist_sq < dist_sq)) {
      --s.size;
      out.status = GjkStatus::Separated;
      out.stalled = true;
      break;
    }
    v = keep_sub_simplex(s, r);
    if (s.size == 4) { out.status = GjkStatus::Intersecting; break; }
  }
  out.v = v;
  return out;
}

}  // namespace gjkdem::detail
