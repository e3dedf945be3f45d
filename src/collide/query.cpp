// Pair-level dispatch of the narrow-phase queries: one std::visit per query picks
// the concrete core types, below which every support call is inlined.
#include "gjkdem/collide/query.hpp"

#include "epa_impl.hpp"
#include "gjk_impl.hpp"

namespace gjkdem {
namespace {

using detail::GjkMode;

Real pair_size(const Shape& a, const Shape& b) noexcept { return 2 * std::fmax(bounding_radius(a), bounding_radius(b)); }

Vec3 start_direction(const GjkCache* cache, const Transform& b_in_a) noexcept {
  if (cache && cache->valid && dot(cache->direction, cache->direction) > 0) return cache->direction;
  return -b_in_a.translation;  // A's origin minus B's: a point of A - B for centred shapes
}

template <class MD>
void save_cache(GjkCache* cache, const MD& md, const Vec3& v) noexcept {
  if (!cache) return;
  cache->direction = v;
  cache->hint_a = md.hint_a;
  cache->hint_b = md.hint_b;
  cache->valid = true;
}

template <class F>
auto with_diff(const Shape& a, const Shape& b, const Transform& b_in_a, const GjkCache* cache, F&& f) noexcept {
  return std::visit(
      [&](const auto& ca, const auto& cb) {
        detail::MinkowskiDiff<std::decay_t<decltype(ca)>, std::decay_t<decltype(cb)>> md{ca, cb, b_in_a};
        if (cache && cache->valid) { md.hint_a = cache->hint_a; md.hint_b = cache->hint_b; }
        return f(md);
      },
      a.core, b.core);
}

}  // namespace

bool intersect(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b, GjkCache* cache,
               const QuerySettings& st) noexcept {
  const Transform b_in_a = relative(pose_a, pose_b);
  return with_diff(a, b, b_in_a, cache, [&](auto& md) {
    const auto g = detail::gjk(md, start_direction(cache, b_in_a), pair_size(a, b), a.margin + b.margin,
                               GjkMode::Boolean, st);
    save_cache(cache, md, g.v);
    if (g.status == GjkStatus::Intersecting) return true;
    const Real margin = a.margin + b.margin;
    return dot(g.v, g.v) <= margin * margin;
  });
}

DistanceResult distance(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                        GjkCache* cache, const QuerySettings& st) noexcept {
  const Transform b_in_a = relative(pose_a, pose_b);
  return with_diff(a, b, b_in_a, cache, [&](auto& md) {
    const auto g = detail::gjk(md, start_direction(cache, b_in_a), pair_size(a, b), 0, GjkMode::Distance, st);
    save_cache(cache, md, g.v);
    DistanceResult r;
    r.status = g.status;
    r.iterations = g.iterations;
    const Real core_dist = length(g.v);
    const Real margin = a.margin + b.margin;
    if (g.status == GjkStatus::Intersecting || core_dist <= margin) {
      r.intersect = true;
      return r;
    }
    const Vec3 n = -g.v / core_dist;
    Vec3 wa, wb;
    simplex_witnesses(g.simplex, wa, wb);
    r.distance = core_dist - margin;
    r.normal = apply_rotation(pose_a, n);
    r.witness_a = apply(pose_a, wa + n * a.margin);
    r.witness_b = apply(pose_a, wb - n * b.margin);
    return r;
  });
}

PenetrationResult penetration(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                              GjkCache* cache, const QuerySettings& st) noexcept {
  const Transform b_in_a = relative(pose_a, pose_b);
  const Real size = pair_size(a, b);
  return with_diff(a, b, b_in_a, cache, [&](auto& md) {
    const auto g = detail::gjk(md, start_direction(cache, b_in_a), size, 0, GjkMode::Distance, st);
    PenetrationResult r;
    r.gjk_status = g.status;
    r.iterations = g.iterations;
    const Real margin = a.margin + b.margin;
    Vec3 n, wa, wb;
    if (g.status != GjkStatus::Intersecting) {
      const Real core_dist = length(g.v);
      n = -g.v / core_dist;
      simplex_witnesses(g.simplex, wa, wb);
      r.intersect = core_dist <= margin;
      r.distance = r.intersect ? 0 : core_dist - margin;
      r.depth = r.intersect ? margin - core_dist : 0;
    } else {
      detail::EpaPolytope poly;
      auto e = detail::epa(md, g.simplex, size, st, poly);
      r.epa_status = e.status;
      r.epa_iterations = e.iterations;
      n = e.normal;
      wa = e.witness_a;
      wb = e.witness_b;
      r.intersect = true;
      r.depth = e.depth + margin;
    }
    save_cache(cache, md, g.v);
    r.normal = apply_rotation(pose_a, n);
    r.witness_a = apply(pose_a, wa + n * a.margin);
    r.witness_b = apply(pose_a, wb - n * b.margin);
    return r;
  });
}

}  // namespace gjkdem
