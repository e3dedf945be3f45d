// Pair-level dispatch of the narrow-phase queries: one std::visit per query picks
// the concrete core types, below which every support call is inlined.
#include "gjkdem/collide/query.hpp"

#include "epa_impl.hpp"
#include "gjk_boolean_impl.hpp"
#include "gjk_impl.hpp"
#include "polish_impl.hpp"

namespace gjkdem {
namespace {

using detail::GjkMode;

Real pair_size(const Shape& a, const Shape& b) noexcept { return 2 * std::fmax(bounding_radius(a), bounding_radius(b)); }

// Cold start: A's origin minus B's, a point of A - B for centred shapes.
Vec3 cold_start(const Transform& b_in_a) noexcept { return -b_in_a.translation; }

int warm_size(const GjkCache* cache) noexcept { return cache ? cache->size : 0; }
const Vec3* warm_dirs(const GjkCache* cache) noexcept { return cache ? cache->dirs : nullptr; }

// The warm start for next time: the given search directions and support hints.
template <class MD>
void save_cache(GjkCache* cache, const MD& md, const Vec3* dirs, int size) noexcept {
  if (!cache) return;
  for (int k = 0; k < size; ++k) cache->dirs[k] = dirs[k];
  cache->size = size;
  cache->hint_a = md.hint_a;
  cache->hint_b = md.hint_b;
}

template <class MD>
void save_cache(GjkCache* cache, const MD& md, const Simplex& s) noexcept {
  Vec3 dirs[4];
  for (int k = 0; k < s.size; ++k) dirs[k] = s.p[k].d;
  save_cache(cache, md, dirs, s.size);
}

// Core results (frame A, normal n from A to B) to world witnesses with the
// margins: A's witness moves along n by its margin, B's against it.
template <class Result>
void place_witnesses(Result& r, const Transform& pose_a, const Vec3& n, const Vec3& wa, const Vec3& wb, Real margin_a,
                     Real margin_b) noexcept {
  r.normal = apply_rotation(pose_a, n);
  r.witness_a = apply(pose_a, wa + n * margin_a);
  r.witness_b = apply(pose_a, wb - n * margin_b);
}

template <class F>
auto with_diff(const Shape& a, const Shape& b, const Transform& b_in_a, const GjkCache* cache, F&& f) noexcept {
  return std::visit(
      [&](const auto& ca, const auto& cb) {
        detail::MinkowskiDiff<std::decay_t<decltype(ca)>, std::decay_t<decltype(cb)>> md{ca, cb, b_in_a};
        if (cache && cache->size > 0) { md.hint_a = cache->hint_a; md.hint_b = cache->hint_b; }
        return f(md);
      },
      a.core, b.core);
}

}  // namespace

bool intersect(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b, GjkCache* cache,
               const QuerySettings& st) noexcept {
  const Transform b_in_a = relative(pose_a, pose_b);
  return with_diff(a, b, b_in_a, cache, [&](auto& md) {
    const Vec3 v0 = cold_start(b_in_a);
    if (a.margin == 0 && b.margin == 0) {  // the seed's Algorithm 14; the distance loop settles ties
      int iterations = 0;
      Vec3 last_d;
      const Vec3 d0 = warm_size(cache) > 0 ? cache->dirs[0] : -v0;
      const auto o = detail::gjk_boolean(md, d0, st.max_gjk_iterations, st.touch_tol * pair_size(a, b), iterations,
                                         last_d);
      if (o != detail::Overlap::Undecided) {
        save_cache(cache, md, &last_d, 1);  // a separating direction, or the last search direction
        return o == detail::Overlap::Intersecting;
      }
    }
    const auto g = detail::gjk(md, v0, warm_dirs(cache), warm_size(cache), pair_size(a, b), a.margin + b.margin,
                               GjkMode::Boolean, st);
    save_cache(cache, md, g.simplex);
    if (g.status == GjkStatus::Intersecting) return true;
    const Real margin = a.margin + b.margin;
    return dot(g.v, g.v) <= margin * margin;
  });
}

DistanceResult distance(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                        GjkCache* cache, const QuerySettings& st) noexcept {
  const Transform b_in_a = relative(pose_a, pose_b);
  return with_diff(a, b, b_in_a, cache, [&](auto& md) {
    const auto g = detail::gjk(md, cold_start(b_in_a), warm_dirs(cache), warm_size(cache), pair_size(a, b), 0,
                               GjkMode::Distance, st);
    save_cache(cache, md, g.simplex);
    DistanceResult r;
    r.status = g.status;
    r.iterations = g.iterations;
    Real core_dist = length(g.v);
    const Real margin = a.margin + b.margin;
    Vec3 n, wa, wb;
    if (g.status != GjkStatus::Intersecting && core_dist > 0) {
      n = -g.v / core_dist;
      simplex_witnesses(g.simplex, wa, wb);
      // Before the margin test, as penetration(): the polish can lower the gap.
      if (g.stalled) detail::polish_separation(md, n, core_dist, wa, wb, pair_size(a, b));
    }
    if (g.status == GjkStatus::Intersecting || core_dist <= margin) {
      r.intersect = true;
      return r;
    }
    r.distance = core_dist - margin;
    place_witnesses(r, pose_a, n, wa, wb, a.margin, b.margin);
    return r;
  });
}

PenetrationResult penetration(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                              GjkCache* cache, const QuerySettings& st) noexcept {
  const Transform b_in_a = relative(pose_a, pose_b);
  const Real size = pair_size(a, b);
  return with_diff(a, b, b_in_a, cache, [&](auto& md) {
    const auto g = detail::gjk(md, cold_start(b_in_a), warm_dirs(cache), warm_size(cache), size, 0,
                               GjkMode::Distance, st);
    PenetrationResult r;
    r.gjk_status = g.status;
    r.iterations = g.iterations;
    const Real margin = a.margin + b.margin;
    Vec3 n, wa, wb;
    if (g.status != GjkStatus::Intersecting) {
      Real core_dist = length(g.v);
      n = -g.v / core_dist;
      simplex_witnesses(g.simplex, wa, wb);
      if (g.stalled) detail::polish_separation(md, n, core_dist, wa, wb, size);
      r.intersect = core_dist <= margin;
      r.distance = r.intersect ? 0 : core_dist - margin;
      r.depth = r.intersect ? margin - core_dist : 0;
    } else {
      detail::EpaPolytope poly;
      auto e = detail::epa(md, g.simplex, size, st, poly);
      detail::polish_penetration(md, e, poly, size);
      r.epa_status = e.status;
      r.epa_iterations = e.iterations;
      n = e.normal;
      wa = e.witness_a;
      wb = e.witness_b;
      r.intersect = true;
      r.depth = e.depth + margin;
    }
    save_cache(cache, md, g.simplex);
    place_witnesses(r, pose_a, n, wa, wb, a.margin, b.margin);
    return r;
  });
}

}  // namespace gjkdem
