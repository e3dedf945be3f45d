#pragma once
// Newton polish of the penetration direction for curved shapes.
//
// The depth is the minimum over unit u of f(u) = h_{A-B}(u), the support
// function of the Minkowski difference, and the minimiser is the normal. On
// smooth shapes EPA converges slowly: its faces approximate a curved surface,
// so after its fixed buffers fill, the depth is good but the normal is only as
// good as the square root of the depth error. f is smooth there, so a few
// trust-region Newton steps on the sphere (gradient = tangential part of the
// support point, Hessian by central differences of it) reach the minimiser to
// round-off. Every f(u) is an upper bound on the depth, so a step is kept only
// when it lowers f: the polish cannot make the answer worse. This follows the
// reference computation of ../shared/tools/curved.py in spirit (chart, Newton,
// trust region); the code is our own.
#include "epa_impl.hpp"
#include <algorithm>
#include <limits>

#include "gjkdem/math/vec2.hpp"
#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem::detail {

/// Cores whose support point is unique (strictly convex, smooth almost
/// everywhere): the witness on such a shape is its support point.
template <class T>
inline constexpr bool kUniqueSupport = std::is_same_v<T, Ellipsoid> || std::is_same_v<T, Superellipsoid>;

/// Cores for which EPA's polytope is only an approximation.
template <class T>
inline constexpr bool kCurvedCore = kUniqueSupport<T> || std::is_same_v<T, Cylinder> || std::is_same_v<T, Cone>;

template <class MD>
Vec3 tangential(MD& md, const Vec3& u, SupportPoint& sp) noexcept {
  sp = md.support(u);
  return sp.w - u * dot(sp.w, u);
}

/// Minimises f from the unit direction u; returns false when nothing improved.
/// On return u is the best direction, f its value and sp its support point.
template <class MD>
bool polish_direction(MD& md, Vec3& u, Real& f, SupportPoint& sp, Real size, int& iterations) noexcept {
  Vec3 g3 = tangential(md, u, sp);
  f = dot(sp.w, u);
  const Real f_start = f;
  Real radius = 0.05;  // trust radius, radians
  constexpr Real eta = kPolishStep;
  for (int it = 0; it < kMaxPolishIterations; ++it) {
    ++iterations;
    Vec3 e1, e2;
    orthonormal_basis(u, e1, e2);
    const Real g[2] = {dot(g3, e1), dot(g3, e2)};
    const Real gnorm = std::hypot(g[0], g[1]);
    if (!(gnorm > kPolishRelTol * size)) break;
    // Hessian of f in the chart by central differences of the tangential gradient.
    Real h[2][2];
    SupportPoint tmp;
    const Vec3 e[2] = {e1, e2};
    for (int j = 0; j < 2; ++j) {
      const Vec3 tp = tangential(md, normalized(u + e[j] * eta), tmp);
      const Vec3 tm = tangential(md, normalized(u - e[j] * eta), tmp);
      h[0][j] = dot(tp - tm, e1) / (2 * eta);
      h[1][j] = dot(tp - tm, e2) / (2 * eta);
    }
    const Real h01 = 0.5 * (h[0][1] + h[1][0]);
    const Real det = h[0][0] * h[1][1] - h01 * h01;
    Real step[2];
    if (det > 0 && h[0][0] > 0) {
      step[0] = -(h[1][1] * g[0] - h01 * g[1]) / det;
      step[1] = -(h[0][0] * g[1] - h01 * g[0]) / det;
    } else {  // not locally convex (a kink or a saddle): steepest descent
      step[0] = -g[0] / gnorm * radius;
      step[1] = -g[1] / gnorm * radius;
    }
    const Real len = std::hypot(step[0], step[1]);
    if (len > radius) { step[0] *= radius / len; step[1] *= radius / len; }
    // Backtrack along the Newton step; at a kink (a cylinder's rim, where f
    // has a V-shaped valley) the finite-difference Hessian can point it
    // across the valley, so then backtrack along steepest descent.
    bool improved = false;
    for (int pass = 0; pass < 2 && !improved; ++pass) {
      if (pass == 1) step[0] = -g[0] / gnorm * radius, step[1] = -g[1] / gnorm * radius;
      for (int tries = 0; tries < 30 && !improved; ++tries) {
        const Vec3 u_new = normalized(u + e1 * step[0] + e2 * step[1]);
        SupportPoint sp_new;
        const Vec3 g_new = tangential(md, u_new, sp_new);
        const Real f_new = dot(sp_new.w, u_new);
        if (f_new < f) {
          u = u_new; f = f_new; sp = sp_new; g3 = g_new;
          improved = true;
        } else {
          step[0] *= 0.25; step[1] *= 0.25;
        }
      }
    }
    if (!improved) break;
    radius = std::fmin(0.5, 2 * std::hypot(step[0], step[1]) + 1e-12);
  }
  return f < f_start;
}

/// Refines a separated GJK answer that stalled on a pair with a curved core:
/// GJK's normal -v / |v| is then only as good as the gap it left (an
/// ellipsoid 0.1 from a cone: certified to 2e-11, claimed 1e-12), because a
/// support point a size away from v shortens it by gap^2 / size^2, below
/// round-off. The separation max over n of -h_{A-B}(n) is the function the
/// penetration polish minimises, and every value is a certified lower bound:
/// a normal is kept only when it certifies a larger gap, >= 0 and <= |v|,
/// and that gap becomes the distance. GJK's witnesses (|v| apart along the
/// old normal) are then placed about their midpoint, the gap apart along the
/// new one, so that witness_b - witness_a = distance * normal still holds.
template <class MD>
void polish_separation(MD& md, Vec3& normal, Real& gap, Vec3& on_a, Vec3& on_b, Real size) noexcept {
  using CoreA = typename MD::TypeA;
  using CoreB = typename MD::TypeB;
  if constexpr (kCurvedCore<CoreA> || kCurvedCore<CoreB>) {
    Vec3 u = normal;
    Real f = 0;
    SupportPoint sp;
    int steps = 0;
    // A separation below zero certifies nothing (near touching, GJK's normal
    // can be noise, and the polish then stays among overlapping directions).
    if (!polish_direction(md, u, f, sp, size, steps) || !(-f <= gap) || !(-f >= 0)) return;
    normal = u;
    gap = -f;
    const Vec3 middle = (on_a + on_b) * 0.5;
    on_a = middle - u * (gap / 2);
    on_b = middle + u * (gap / 2);
  }
}

namespace witness2d {

// The point of the hull h nearest to q (q itself inside).
inline Vec2 nearest(const Vec2* h, int n, const Vec2& q) noexcept {
  if (n == 1) return h[0];
  bool inside = n >= 3;
  for (int m = 0; m < n && inside; ++m) inside = cross(h[(m + 1) % n] - h[m], q - h[m]) >= 0;
  if (inside) return q;
  Vec2 best = h[0];
  for (int m = 0; m < (n == 2 ? 1 : n); ++m) {
    const Vec2 a = h[m], e = h[(m + 1) % n] - a;
    const Vec2 p = a + e * std::clamp(dot(q - a, e) / dot(e, e), Real(0), Real(1));
    if (length(q - p) < length(q - best)) best = p;
  }
  return best;
}

}  // namespace witness2d

/// Witnesses of a penetration along unit u with depth f when both cores may
/// have support sets (a cylinder's or cone's side, a cap). A's support point
/// alone can lie anywhere on its generator line, and a - f u then far outside
/// B (a small cylinder sunk in a cone's side: 3 units off, and another point
/// with A and B swapped or scaled). Each side's support set is sampled by its
/// support points at u and at u tilted by kWitnessProbeAngle eight ways (the
/// ends of a segment, the corners of a face, points of a disc's rim); seen along u, the two sets'
/// hulls overlap where the contact is, and the witness is the mean of the
/// vertices of that overlap, the same whichever shape comes first.
template <class MD>
void penetration_witnesses(MD& md, const Vec3& u, Real f, Real size, Vec3& on_a, Vec3& on_b) noexcept {
  // A basis that does not depend on the sign of u: A and B swapped agree.
  const int axis = std::fabs(u.x) >= std::fabs(u.y) ? (std::fabs(u.x) >= std::fabs(u.z) ? 0 : 2)
                                                    : (std::fabs(u.y) >= std::fabs(u.z) ? 1 : 2);
  Vec3 e1, e2;
  orthonormal_basis(u[axis] >= 0 ? u : -u, e1, e2);
  // Tilts along the basis and its diagonals: a face whose edges run along
  // e1 and e2 (a box's, for u along an axis) answers the axis tilts with
  // ties and shows all its corners only to the diagonal ones.
  constexpr int kProbes = 9;
  Vec2 pa[kProbes], pb[kProbes];
  Real level = 0;  // A's support plane along u
  const Vec3 tilt[kProbes] = {Vec3{}, e1, -e1, e2, -e2, e1 + e2, e1 - e2, -e1 + e2, -e1 - e2};
  for (int m = 0; m < kProbes; ++m) {
    const SupportPoint sp = md.support(normalized(u + tilt[m] * kWitnessProbeAngle));
    if (m == 0) level = dot(sp.a, u);
    const Vec3 b = sp.b + u * f;  // B moved onto A's support plane
    pa[m] = {dot(sp.a, e1), dot(sp.a, e2)};
    pb[m] = {dot(b, e1), dot(b, e2)};
  }
  const Real tol = kWitnessProbeTol * size;
  Vec2 ha[kProbes], hb[kProbes];
  const std::vector<int> hull_a = convex_hull_2d(pa, tol), hull_b = convex_hull_2d(pb, tol);
  const int na = static_cast<int>(hull_a.size()), nb = static_cast<int>(hull_b.size());
  for (int m = 0; m < na; ++m) ha[m] = pa[hull_a[m]];
  for (int m = 0; m < nb; ++m) hb[m] = pb[hull_b[m]];
  Vec2 sum{};
  int count = 0;
  for (int m = 0; m < na; ++m)
    if (length(witness2d::nearest(hb, nb, ha[m]) - ha[m]) <= tol) sum = sum + ha[m], ++count;
  for (int m = 0; m < nb; ++m)
    if (length(witness2d::nearest(ha, na, hb[m]) - hb[m]) <= tol) sum = sum + hb[m], ++count;
  // Edges crossing (a two-point hull is one edge, not two).
  const int edges_a = na < 2 ? 0 : na == 2 ? 1 : na, edges_b = nb < 2 ? 0 : nb == 2 ? 1 : nb;
  for (int i = 0; i < edges_a; ++i)
    for (int j = 0; j < edges_b; ++j) {
      const Vec2 a0 = ha[i], a1 = ha[(i + 1) % na], b0 = hb[j], b1 = hb[(j + 1) % nb];
      const Vec2 da = a1 - a0, db = b1 - b0;
      const Real den = cross(da, db);
      if (!(std::fabs(den) > 0)) continue;
      const Real s = cross(b0 - a0, db) / den, t = cross(b0 - a0, da) / den;
      if (s > 0 && s < 1 && t > 0 && t < 1) sum = sum + (a0 + da * s), ++count;
    }
  Vec2 w;
  if (count > 0) {
    w = sum * (Real(1) / count);
  } else {
    // Apart by more than the tolerance (the normal is good to the square root
    // of the depth's error, and a curved side falls away from its support
    // line): the middle of the closest points of the two hulls.
    Real best = std::numeric_limits<Real>::infinity();
    for (int side = 0; side < 2; ++side)
      for (int m = 0; m < (side == 0 ? na : nb); ++m) {
        const Vec2 q = side == 0 ? ha[m] : hb[m];
        const Vec2 p = side == 0 ? witness2d::nearest(hb, nb, q) : witness2d::nearest(ha, na, q);
        if (length(p - q) < best) best = length(p - q), w = (p + q) * Real(0.5);
      }
  }
  on_a = e1 * w.x + e2 * w.y + u * level;
  on_b = on_a - u * f;
}

/// Refines an unconverged EPA answer on pairs with a curved core (ellipsoid,
/// superellipsoid, cylinder, cone): the normal is polished, the depth becomes
/// f at the polished normal, and the witness on a unique-support side is its
/// support point (else penetration_witnesses).
template <class MD>
void polish_penetration(MD& md, EpaOutput& e, Real size) noexcept {
  using CoreA = typename MD::TypeA;
  using CoreB = typename MD::TypeB;
  if constexpr (kCurvedCore<CoreA> || kCurvedCore<CoreB>) {
    if (e.status != EpaStatus::OutOfMemory && e.status != EpaStatus::MaxIterations) return;
    Vec3 u = e.normal;
    Real f = 0;
    SupportPoint sp;
    int steps = 0;
    const Real lower_bound = e.depth;  // EPA's closest face: the true depth is at least this
    // f(u) is an upper bound at every u, EPA's face a lower bound. A polish
    // that cannot improve on EPA's normal sits at the minimum already (at a
    // kink, where EPA's inner polytope needs endless vertices: two coaxial
    // cylinders came out 3e-4 short), and f there is the depth.
    polish_direction(md, u, f, sp, size, steps);
    if (f < lower_bound) return;
    e.iterations += steps;
    e.depth = f;
    e.normal = u;
    if constexpr (kUniqueSupport<CoreA>) {
      e.witness_a = sp.a;
      e.witness_b = sp.a - u * f;
    } else if constexpr (kUniqueSupport<CoreB>) {
      e.witness_b = sp.b;
      e.witness_a = sp.b + u * f;
    } else {  // both may have support sets (a cylinder's side)
      penetration_witnesses(md, u, f, size, e.witness_a, e.witness_b);
    }
    e.status = EpaStatus::Converged;
  }
}

}  // namespace gjkdem::detail
