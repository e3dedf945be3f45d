// Planar GJK and EPA. The boolean test follows the seed text's Algorithm 14 and
// its plane checks literally; the distance loop uses the same closest-point
// logic as 3D (signed areas instead of volumes); the planar EPA grows a convex
// polygon inside A - B, splitting its closest edge at the support point along
// the edge normal until that point adds nothing.
#include "gjkdem/collide/gjk2d.hpp"

#include <limits>

#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {

struct Point2 {
  Vec2 w, a, b;  // w = a - b
};

Point2 support_diff(const ConvexPolygon& a, const ConvexPolygon& b, const Vec2& d) noexcept {
  const Vec2 pa = support(a, d), pb = support(b, -d);
  return {pa - pb, pa, pb};
}

Real polygon_size(const ConvexPolygon& a, const ConvexPolygon& b) noexcept {
  Real r = 0;
  for (const ConvexPolygon* p : {&a, &b})
    for (const Vec2& v : p->points) r = std::fmax(r, std::fmax(std::fabs(v.x), std::fabs(v.y)));
  return r;
}

// Closest point of the simplex (1 to 3 points) to the origin; keeps only the
// points of the feature that holds it and their barycentric weights.
Vec2 reduce(Point2* s, Real* lambda, int& n) noexcept {
  if (n == 1) { lambda[0] = 1; return s[0].w; }
  auto segment = [&](int i, int j, Real& li, Real& lj) {
    const Vec2 t = s[j].w - s[i].w;
    const Real tt = dot(t, t);
    Real u = tt > 0 ? -dot(s[i].w, t) / tt : 0;
    u = u < 0 ? 0 : (u > 1 ? 1 : u);
    li = 1 - u;
    lj = u;
    return s[i].w + t * u;
  };
  if (n == 2) {
    Real l0, l1;
    const Vec2 v = segment(0, 1, l0, l1);
    if (l1 == 0) { n = 1; lambda[0] = 1; }
    else if (l0 == 0) { s[0] = s[1]; n = 1; lambda[0] = 1; }
    else { lambda[0] = l0; lambda[1] = l1; }
    return v;
  }
  // Triangle: barycentric weights from signed areas with the origin.
  const Real area = cross(s[1].w - s[0].w, s[2].w - s[0].w);
  const Real c0 = cross(s[1].w, s[2].w), c1 = cross(s[2].w, s[0].w), c2 = cross(s[0].w, s[1].w);
  if (area != 0 && c0 * area > 0 && c1 * area > 0 && c2 * area > 0) {
    lambda[0] = c0 / area; lambda[1] = c1 / area; lambda[2] = c2 / area;
    return {0, 0};
  }
  // Outside: the best edge.
  Real best = std::numeric_limits<Real>::infinity();
  Point2 keep[2];
  Real keep_l[2];
  int keep_n = 0;
  Vec2 v{};
  for (int e = 0; e < 3; ++e) {
    const int i = e, j = (e + 1) % 3;
    Real li, lj;
    const Vec2 q = segment(i, j, li, lj);
    if (dot(q, q) < best) {
      best = dot(q, q);
      v = q;
      keep_n = 0;
      if (li > 0) { keep[keep_n] = s[i]; keep_l[keep_n++] = li; }
      if (lj > 0) { keep[keep_n] = s[j]; keep_l[keep_n++] = lj; }
    }
  }
  n = keep_n;
  for (int k = 0; k < n; ++k) { s[k] = keep[k]; lambda[k] = keep_l[k]; }
  return v;
}

}  // namespace

Vec2 support(const ConvexPolygon& p, const Vec2& d) noexcept {
  const Vec2* best = &p.points[0];
  Real best_dot = dot(*best, d);
  for (const Vec2& v : p.points) {
    const Real t = dot(v, d);
    if (t > best_dot) { best_dot = t; best = &v; }
  }
  return *best;
}

bool intersect2d(const ConvexPolygon& a, const ConvexPolygon& b, Vec2 d, std::vector<Gjk2dStep>* trace) {
  if (!(dot(d, d) > 0)) d = {1, 0};
  Vec2 s[3];
  int n = 0;
  auto record = [&](const Vec2& dir, const Vec2& p, bool enclosed) {
    if (trace) trace->push_back({dir, p, std::vector<Vec2>(s, s + n), enclosed});
  };
  for (int it = 0; it < kMaxGjkIterations; ++it) {
    const Vec2 p = support_diff(a, b, d).w;                 // line 4: simplex.append(support(d))
    if (dot(p, d) < 0) { record(d, p, false); return false; } // line 5: it does not pass the origin
    for (int k = 0; k < n; ++k)
      if (s[k] == p) { record(d, p, true); return true; }   // no new point: the origin is on the boundary
    const Vec2 dir = d;
    s[n++] = p;
    const Vec2 A = s[n - 1], ao = -A;
    if (n == 1) {
      d = ao;
    } else if (n == 2) {
      const Vec2 ab = s[0] - A;
      if (dot(ab, ao) > 0) d = triple_product(ab, ao, ab);  // perpendicular of AB towards O
      else { s[0] = A; n = 1; d = ao; }
    } else {
      const Vec2 B = s[1], C = s[0];
      const Vec2 ab = B - A, ac = C - A;
      const Vec2 ab_perp = triple_product(ac, ab, ab), ac_perp = triple_product(ab, ac, ac);
      if (dot(ab_perp, ao) > 0) { s[0] = B; s[1] = A; n = 2; d = ab_perp; }       // backtrack: drop C
      else if (dot(ac_perp, ao) > 0) { s[0] = C; s[1] = A; n = 2; d = ac_perp; }  // backtrack: drop B
      else { record(dir, p, true); return true; }                                // line 8: origin enclosed
    }
    if (!(dot(d, d) > 0)) { record(dir, p, true); return true; }  // origin on the simplex: touching
    record(dir, p, false);
  }
  return true;  // not reached for polygons: each iteration adds a new vertex of A - B
}

Penetration2dResult penetration2d(const ConvexPolygon& a, const ConvexPolygon& b) noexcept {
  Penetration2dResult r;
  const Real size = polygon_size(a, b);
  Point2 s[3];
  Real lambda[3] = {1, 0, 0};
  int n = 0;
  Vec2 v = a.points[0] - b.points[0];
  if (!(dot(v, v) > 0)) v = {1, 0};
  s[n++] = support_diff(a, b, -v);
  v = s[0].w;
  bool inside = false;
  for (int it = 1; it <= kMaxGjkIterations; ++it) {
    r.iterations = it;
    const Real vv = dot(v, v);
    if (vv <= (kGjkTouchTol * size) * (kGjkTouchTol * size)) { inside = true; break; }
    const Point2 w = support_diff(a, b, -v);
    const Real gap = vv - dot(v, w.w);
    if (gap <= kGjkRelTol * vv) break;
    bool repeated = false;
    for (int k = 0; k < n; ++k) repeated |= s[k].w == w.w;
    if (repeated) break;
    s[n++] = w;
    const Vec2 v_new = reduce(s, lambda, n);
    if (n == 3) { inside = true; break; }
    if (!(dot(v_new, v_new) < vv)) break;
    v = v_new;
  }
  if (!inside) {
    Vec2 wa{}, wb{};
    for (int k = 0; k < n; ++k) { wa = wa + s[k].a * lambda[k]; wb = wb + s[k].b * lambda[k]; }
    const Real dist = length(v);
    r.distance = dist;
    r.normal = -v * (1 / dist);
    r.witness_a = wa;
    r.witness_b = wb;
    return r;
  }
  // Planar EPA on a counter-clockwise polygon that holds the origin.
  r.intersect = true;
  constexpr int kMax = kEpaMaxVertices;
  Point2 poly[kMax];
  int m = 0;
  if (n < 3) {  // origin on a point or edge of the simplex: grow it across
    const Vec2 base = n == 2 ? s[1].w - s[0].w : Vec2{1, 0};
    const Vec2 perp{-base.y, base.x};
    for (int k = 0; k < n; ++k) poly[m++] = s[k];
    for (const Vec2& dir : {perp, -perp}) {
      const Point2 p = support_diff(a, b, dir);
      if (dot(p.w - s[0].w, dir) > kEpaAbsTol * size) poly[m++] = p;
    }
    if (n == 1 && m < 3) {
      for (const Vec2& dir : {base, -base}) {
        const Point2 p = support_diff(a, b, dir);
        if (dot(p.w - s[0].w, dir) > kEpaAbsTol * size) poly[m++] = p;
      }
    }
    if (m < 3) {  // A - B has no area: depth 0
      r.normal = length(perp) > 0 ? perp * (1 / length(perp)) : Vec2{0, 1};
      r.witness_a = s[0].a;
      r.witness_b = s[0].b;
      return r;
    }
    m = 3;
  } else {
    for (int k = 0; k < 3; ++k) poly[m++] = s[k];
  }
  if (cross(poly[1].w - poly[0].w, poly[2].w - poly[0].w) < 0) std::swap(poly[1], poly[2]);
  int best = 0;
  for (;;) {  // ends: each pass adds a vertex, and a full buffer returns
    ++r.iterations;
    Real best_dist = std::numeric_limits<Real>::infinity();
    Vec2 best_n{};
    for (int e = 0; e < m; ++e) {
      const Vec2 edge = poly[(e + 1) % m].w - poly[e].w;
      const Real len = length(edge);
      if (!(len > 0)) continue;
      const Vec2 nrm{edge.y / len, -edge.x / len};  // outward for a counter-clockwise polygon
      const Real dist = dot(nrm, poly[e].w);
      if (dist < best_dist) { best_dist = dist; best = e; best_n = nrm; }
    }
    const Point2 p = support_diff(a, b, best_n);
    if (dot(p.w, best_n) - best_dist <= kEpaRelTol * std::fabs(best_dist) + kEpaAbsTol * size || m == kMax) {
      const Point2& p0 = poly[best];
      const Point2& p1 = poly[(best + 1) % m];
      const Vec2 t = p1.w - p0.w;
      const Real tt = dot(t, t);
      Real u = tt > 0 ? -dot(p0.w, t) / tt : 0;
      u = u < 0 ? 0 : (u > 1 ? 1 : u);
      r.depth = std::fmax(best_dist, Real(0));
      r.normal = best_n;
      r.witness_a = p0.a * (1 - u) + p1.a * u;
      r.witness_b = p0.b * (1 - u) + p1.b * u;
      return r;
    }
    for (int k = m; k > best + 1; --k) poly[k] = poly[k - 1];  // insert after edge start
    poly[best + 1] = p;
    ++m;
  }
}

}  // namespace gjkdem
