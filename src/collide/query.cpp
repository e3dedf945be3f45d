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

// The distance loop's test of cores `margins` (their sum) apart at most,
// warm from `cache` and saved to it: whether they meet. `reach` receives
// the length of the point of the cores' difference it stopped at (also
// where it stopped as intersecting: within the margins, or enclosing 0), a
// bound on their distance.
template <class MD>
bool meet_within(MD& md, const Vec3& v0, GjkCache* cache, Real size, Real margins, const QuerySettings& st,
                 Real* reach = nullptr) noexcept {
  const auto g = detail::gjk(md, v0, warm_dirs(cache), warm_size(cache), size, margins, GjkMode::Boolean, st);
  save_cache(cache, md, g.simplex);
  if (reach) *reach = length(g.v);
  return g.status == GjkStatus::Intersecting || dot(g.v, g.v) <= margins * margins;
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
    return meet_within(md, v0, cache, pair_size(a, b), a.margin + b.margin, st);
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

DepthClass classify_depth(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b, Real depth,
                          const QuerySettings& st) noexcept {
  // Cheap proofs first, EPA only where they fail (shapes that barely touch).
  if (const Real margins = a.margin + b.margin; margins > 0) {
    // With margins the depth is the margins plus the cores' depth where the
    // cores overlap, the margins less the cores' distance where they do not.
    // The test of the whole shapes, as intersect() runs it, stops at a point
    // v of the cores' difference within the margins: the cores lie at most
    // |v| apart, so margins - |v| beyond `depth` and the test's touching
    // band proves the depth, and an overlap costs that one test.
    const Real size = pair_size(a, b);
    const Real shrink = depth + 2 * st.touch_tol * size;
    const Transform b_in_a = relative(pose_a, pose_b);
    GjkCache cores;
    Real reach = 0;  // |v|
    const bool meet = with_diff(a, b, b_in_a, nullptr, [&](auto& md) {
      return meet_within(md, cold_start(b_in_a), &cores, size, margins, st, &reach);
    });
    if (!meet) return DepthClass::Apart;
    if (margins - reach > shrink) return DepthClass::Beyond;
    // Else the margins shrunk by that much, from the test's last simplex.
    if (margins > shrink) {
      const Real keep = (margins - shrink) / margins;
      Shape inner_a = a, inner_b = b;
      inner_a.margin *= keep;
      inner_b.margin *= keep;
      if (intersect(inner_a, pose_a, inner_b, pose_b, &cores, st)) return DepthClass::Beyond;
    }
  } else {
    // The overlap test (as intersect() runs it); its last simplex, when it
    // encloses the origin, lies in A - B, and each face farther than
    // `depth` from the origin proves the depth larger.
    const Transform b_in_a = relative(pose_a, pose_b);
    const detail::Overlap o = with_diff(a, b, b_in_a, nullptr, [&](auto& md) {
      int iterations = 0;
      Vec3 last_d;
      detail::Enclosure e;
      const detail::Overlap test = detail::gjk_boolean(md, -cold_start(b_in_a), st.max_gjk_iterations,
                                                       st.touch_tol * pair_size(a, b), iterations, last_d, &e);
      // Intersecting without a tetrahedron: the origin lies on the simplex (touching).
      if (!e.found) return test == detail::Overlap::Separated ? test : detail::Overlap::Undecided;
      static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};  // and the corner opposite
      for (const auto& f : kFaces) {
        const Vec3& p = e.p[f[0]];
        Vec3 n = cross(e.p[f[1]] - p, e.p[f[2]] - p);
        if (dot(n, e.p[f[3]] - p) > 0) n = -n;  // outward
        // The origin lies inside, farther than `depth` from the face's plane: n . p > depth |n|.
        const Real h = dot(n, p);
        if (!(h > 0 && h * h > depth * depth * dot(n, n))) return detail::Overlap::Undecided;
      }
      return detail::Overlap::Intersecting;
    });
    if (o == detail::Overlap::Separated) return DepthClass::Apart;
    if (o == detail::Overlap::Intersecting) return DepthClass::Beyond;
  }
  const PenetrationResult p = penetration(a, pose_a, b, pose_b, nullptr, st);
  return !p.intersect ? DepthClass::Apart : p.depth > depth ? DepthClass::Beyond : DepthClass::Within;
}

}  // namespace gjkdem
