#pragma once
// The GJK simplex and its closest-point sub-algorithm.
//
// The sub-algorithm follows the signed-volumes method of Montanari, Petrinic and
// Barbieri (ACM TOG 36(3), 2017): barycentric coordinates of the origin's
// projection come from signed volumes (areas) of sub-simplices, and only the
// faces (edges) whose sign disagrees with the whole are searched further. Unlike
// Johnson's sub-algorithm it needs no nested determinant ratios, and it degrades
// gracefully on flat or duplicate simplices (those fall through to their edges).
// Departures: the triangle case uses the dominant axis of the triangle normal
// for its 2D projection; the segment case projects directly.
#include "gjkdem/math/vec3.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

/// One vertex of the Minkowski difference A - B with the points it came from.
struct SupportPoint {
  Vec3 w;  ///< a - b
  Vec3 a;  ///< on A
  Vec3 b;  ///< on B
  Vec3 d;  ///< the search direction that produced it (warm starts replay it)
};

struct Simplex {
  SupportPoint p[4];
  Real lambda[4] = {1, 0, 0, 0};  ///< barycentric weights of the closest point
  int size = 0;
};

namespace detail {

struct SubSimplex {
  unsigned mask = 0;          // bit i: vertex i kept
  Real lambda[4] = {0, 0, 0, 0};
  Vec3 v;                     // closest point
  Real dist_sq = 0;
};

inline bool same_sign(Real a, Real b) noexcept { return (a > 0 && b > 0) || (a < 0 && b < 0); }

/// A normal of triangle (a, b, c), oriented as cross(b - a, c - a), from its
/// two shortest edges. On a sliver (two support points a micron apart on a
/// rim, the third far off) an edge from the far vertex carries its round-off,
/// eps * size, across the short edge and tilts the plane by eps * size /
/// (short edge): 4e-11 rad on a cone's side, which ended GJK 1e-10 short.
/// Close points subtract exactly.
inline Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  const Vec3 ab = b - a, bc = c - b, ca = a - c;
  const Real lab = dot(ab, ab), lbc = dot(bc, bc), lca = dot(ca, ca);
  return lab >= lbc && lab >= lca ? cross(bc, ca) : lbc >= lca ? cross(ca, ab) : cross(ab, bc);
}

inline void closest_on_segment(const Vec3* w, int i, int j, SubSimplex& r) noexcept {
  const Vec3 t = w[j] - w[i];
  const Real tt = dot(t, t);
  const Real inv_tt = tt > 0 ? 1 / tt : 0;
  const Real s = -dot(w[i], t) * inv_tt;
  r = {};
  if (!(s > 0)) {
    r.mask = 1u << i; r.lambda[i] = 1; r.v = w[i];
  } else if (s >= 1) {
    r.mask = 1u << j; r.lambda[j] = 1; r.v = w[j];
  } else {
    r.mask = (1u << i) | (1u << j); r.lambda[i] = 1 - s; r.lambda[j] = s; r.v = w[i] + t * s;
    // The sum cancels to |v| with the round-off of the ends, eps * |w|, along
    // t as well: a point 1e-9 off a cone's side got a normal tilted 3e-8 rad
    // along the generator, which the flat generator turns into a 1e-8 error.
    // v is perpendicular to t; taking the along-t part out again is exact to
    // eps * |v|.
    r.v -= t * (dot(r.v, t) * inv_tt);
  }
  r.dist_sq = dot(r.v, r.v);
}

inline void closest_on_triangle(const Vec3* w, int i, int j, int k, SubSimplex& r) noexcept {
  const Vec3 n = triangle_normal(w[i], w[j], w[k]);
  const Real nn = dot(n, n);
  if (nn > 0) {
    const Vec3 p0 = n * (dot(w[i], n) / nn);  // origin projected on the plane
    const int ax = std::fabs(n.x) >= std::fabs(n.y) ? (std::fabs(n.x) >= std::fabs(n.z) ? 0 : 2)
                                                    : (std::fabs(n.y) >= std::fabs(n.z) ? 1 : 2);
    const int u = (ax + 1) % 3, v = (ax + 2) % 3;
    auto area = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
      return (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
    };
    const Real mu = area(w[i], w[j], w[k]);
    const Real ci = area(p0, w[j], w[k]), cj = area(w[i], p0, w[k]), ck = area(w[i], w[j], p0);
    if (same_sign(mu, ci) && same_sign(mu, cj) && same_sign(mu, ck)) {
      r = {};
      r.mask = (1u << i) | (1u << j) | (1u << k);
      r.lambda[i] = ci / mu; r.lambda[j] = cj / mu; r.lambda[k] = ck / mu;
      // The closest point is the origin's projection on the plane, not the
      // weighted sum of the vertices: that sum cancels to a point of size |v|
      // with the round-off of the vertices, eps * size, so near touching its
      // direction was off by eps * size / |v| (1e-8 rad for 1e-9 m on 1 m
      // boxes, FCL's issue 388 setting: GJK stopped 8x too far), and on a
      // sliver its weights are off too (a cone's side: the triangle came out
      // farther than its own edge). The projection is along the accurate
      // normal, exact to round-off.
      r.v = p0;
      r.dist_sq = dot(r.v, r.v);
      return;
    }
    // Outside: search the edges opposite the vertices whose sign disagrees.
    const Real c[3] = {ci, cj, ck};
    const int idx[3] = {i, j, k};
    bool found = false;
    for (int m = 0; m < 3; ++m) {
      if (same_sign(mu, c[m])) continue;
      SubSimplex e;
      closest_on_segment(w, idx[(m + 1) % 3], idx[(m + 2) % 3], e);
      if (!found || e.dist_sq < r.dist_sq) { r = e; found = true; }
    }
    if (found) return;
  }
  // Degenerate (zero-area) triangle: the closest point lies on one of its edges.
  SubSimplex e;
  closest_on_segment(w, i, j, r);
  closest_on_segment(w, j, k, e);
  if (e.dist_sq < r.dist_sq) r = e;
  closest_on_segment(w, k, i, e);
  if (e.dist_sq < r.dist_sq) r = e;
}

/// Whether any face of tetrahedron w sees the origin (from outside), by its
/// accurate normal; outside[m] is set for the face opposite vertex m. The
/// signed volumes that said "inside" are triple products from the origin,
/// with the round-off eps * |w|^3, which on a sliver face outweighs the
/// origin's distance to it: a corner 1e-12 x size off a cone's rim was
/// enclosed by a tetrahedron of three rim points. Out of line: it runs once
/// per enclosure, and inlined it kept the compiler from inlining the support
/// calls of the GJK loop (distance 14% slower).
[[gnu::noinline]] inline bool faces_see_origin(const Vec3* w, bool* outside) noexcept {
  bool any = false;
  for (int m = 0; m < 4; ++m) {
    const Vec3& a = w[(m + 1) % 4];
    const Vec3 n = triangle_normal(a, w[(m + 2) % 4], w[(m + 3) % 4]);
    const Real towards_m = dot(n, w[m] - a), towards_origin = -dot(n, a);
    outside[m] = (towards_m > 0 && towards_origin < 0) || (towards_m < 0 && towards_origin > 0);
    any |= outside[m];
  }
  return any;
}

inline void closest_on_tetrahedron(const Vec3* w, SubSimplex& r) noexcept {
  // c[m] = signed volume of the tetrahedron with the origin in place of vertex m;
  // they sum to the whole volume and are the barycentric weights times it.
  const Real c[4] = {dot(w[1], cross(w[2], w[3])), -dot(w[0], cross(w[2], w[3])), dot(w[0], cross(w[1], w[3])),
                     -dot(w[0], cross(w[1], w[2]))};
  const Real mu = c[0] + c[1] + c[2] + c[3];
  bool outside[4];
  for (int m = 0; m < 4; ++m) outside[m] = mu == 0 || !same_sign(mu, c[m]);
  if (!outside[0] && !outside[1] && !outside[2] && !outside[3]) {
    if (!faces_see_origin(w, outside)) {
      r = {};
      r.mask = 15;
      for (int m = 0; m < 4; ++m) r.lambda[m] = c[m] / mu;
      return;  // origin inside: v = 0
    }
  }
  bool found = false;
  for (int m = 0; m < 4; ++m) {
    if (!outside[m]) continue;
    SubSimplex f;
    closest_on_triangle(w, (m + 1) % 4, (m + 2) % 4, (m + 3) % 4, f);
    if (!found || f.dist_sq < r.dist_sq) { r = f; found = true; }
  }
}

}  // namespace detail

/// The smallest sub-simplex of `s` whose hull holds its point closest to the
/// origin, with its weights; `s` itself is left as it is, so a caller can
/// still drop the point it just added.
inline detail::SubSimplex closest_sub_simplex(const Simplex& s) noexcept {
  Vec3 w[4];
  for (int m = 0; m < s.size; ++m) w[m] = s.p[m].w;
  detail::SubSimplex r;
  switch (s.size) {
    case 1: r.mask = 1; r.lambda[0] = 1; r.v = w[0]; r.dist_sq = dot(w[0], w[0]); break;
    case 2: detail::closest_on_segment(w, 0, 1, r); break;
    case 3: detail::closest_on_triangle(w, 0, 1, 2, r); break;
    default: detail::closest_on_tetrahedron(w, r); break;
  }
  return r;
}

/// The same for a simplex too flat for the signs of its volumes: the nearest
/// of its facets (triangles of a tetrahedron, edges of a triangle), each
/// searched as usual. A support point within 1e-10 of the simplex's plane made
/// the tetrahedron's signs noise, the new point was dropped, and GJK stopped
/// 1e-10 short of its tolerance (an ellipsoid against a cone).
inline detail::SubSimplex nearest_facet(const Simplex& s) noexcept {
  if (s.size < 3) return closest_sub_simplex(s);
  Vec3 w[4];
  for (int m = 0; m < s.size; ++m) w[m] = s.p[m].w;
  detail::SubSimplex best, f;
  for (int skip = 0; skip < s.size; ++skip) {
    int idx[3], n = 0;
    for (int m = 0; m < s.size; ++m)
      if (m != skip) idx[n++] = m;
    if (s.size == 4) detail::closest_on_triangle(w, idx[0], idx[1], idx[2], f);
    else detail::closest_on_segment(w, idx[0], idx[1], f);
    if (skip == 0 || f.dist_sq < best.dist_sq) best = f;
  }
  return best;
}

/// Keeps the vertices of `r` in `s` with their weights; returns the closest
/// point (zero when a full tetrahedron encloses the origin).
inline Vec3 keep_sub_simplex(Simplex& s, const detail::SubSimplex& r) noexcept {
  int n = 0;
  for (int m = 0; m < s.size; ++m) {
    if (!(r.mask & (1u << m))) continue;
    s.p[n] = s.p[m];
    s.lambda[n] = r.lambda[m];
    ++n;
  }
  s.size = n;
  return n == 4 ? Vec3{} : r.v;
}

/// Reduces `s` to the smallest sub-simplex whose hull holds its point closest to
/// the origin, sets the barycentric weights, and returns that point (zero when
/// a full tetrahedron encloses the origin).
inline Vec3 reduce_to_closest(Simplex& s) noexcept { return keep_sub_simplex(s, closest_sub_simplex(s)); }

/// Witness points: the barycentric combination of the simplex's A and B points.
inline void simplex_witnesses(const Simplex& s, Vec3& on_a, Vec3& on_b) noexcept {
  on_a = {};
  on_b = {};
  for (int m = 0; m < s.size; ++m) {
    on_a += s.p[m].a * s.lambda[m];
    on_b += s.p[m].b * s.lambda[m];
  }
}

}  // namespace gjkdem
