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

/// A direction of the polish with its value f = h_{A-B}(u), support point
/// and tangential gradient.
struct PolishPoint {
  Vec3 u, gradient;
  Real f = 0;
  SupportPoint sp;
};

template <class MD>
Vec3 tangential(MD& md, const Vec3& u, SupportPoint& sp) noexcept {
  sp = md.support(u);
  return sp.w - u * dot(sp.w, u);
}

template <class MD>
PolishPoint polish_point(MD& md, const Vec3& u) noexcept {
  PolishPoint p;
  p.u = u;
  p.gradient = tangential(md, u, p.sp);
  p.f = dot(p.sp.w, u);
  return p;
}

/// Evaluates f at the unit direction u_new and takes it as `best` when lower.
template <class MD>
bool try_direction(MD& md, const Vec3& u_new, PolishPoint& best) noexcept {
  const PolishPoint p = polish_point(md, u_new);
  if (!(p.f < best.f)) return false;
  best = p;
  return true;
}

/// The point of the convex hull of g[0..n) (2D) nearest the origin: the
/// steepest descent direction of a max of smooth pieces whose gradients these
/// are. Zero when the hull holds the origin.
inline Vec2 min_norm_in_hull(const Vec2* g, int n) noexcept {
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        const Real a = cross(g[j] - g[i], -g[i]), b = cross(g[k] - g[j], -g[j]), c = cross(g[i] - g[k], -g[k]);
        const bool inside = (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
        if (inside && cross(g[j] - g[i], g[k] - g[i]) != 0) return {};
      }
  Vec2 best = g[0];
  for (int i = 0; i < n; ++i) {
    if (dot(g[i], g[i]) < dot(best, best)) best = g[i];
    for (int j = i + 1; j < n; ++j) {
      const Vec2 e = g[j] - g[i];
      const Real ee = dot(e, e);
      if (!(ee > 0)) continue;
      const Vec2 p = g[i] + e * std::clamp(-dot(g[i], e) / ee, Real(0), Real(1));
      if (dot(p, p) < dot(best, best)) best = p;
    }
  }
  return best;
}

/// A descent step along a kinked valley, where f is the max of smooth pieces
/// (a cylinder's rim: the support point jumps from one cap to the other) and
/// neither Newton nor steepest descent lowers f much: the gradients are
/// sampled at the point tilted by `spread` four ways, and the step goes
/// against the point of their hull nearest the origin (gradient sampling,
/// Burke, Lewis and Overton 2005), along the valley. The spread shrinks
/// tenfold while no step helps. On success `best` is the new point and
/// `length` the step (rad).
template <class MD>
bool valley_step(MD& md, const PolishPoint& from, Real radius, Real size, PolishPoint& best, Real& length) noexcept {
  Vec3 e1, e2;
  orthonormal_basis(from.u, e1, e2);
  const Vec3 tilt[4] = {e1, -e1, e2, -e2};
  for (Real spread = radius; spread > kPolishMinSpread; spread *= 0.1) {
    Vec2 g[5];
    g[0] = {dot(from.gradient, e1), dot(from.gradient, e2)};
    for (int m = 0; m < 4; ++m) {
      const Vec3 gm = polish_point(md, normalized(from.u + tilt[m] * spread)).gradient;
      g[m + 1] = {dot(gm, e1), dot(gm, e2)};
    }
    const Vec2 d = min_norm_in_hull(g, 5);
    const Real dn = gjkdem::length(d);
    if (!(dn > kPolishRelTol * size)) continue;  // stationary at this spread
    // The valley's floor can be nearly level (coaxial cylinders a hair off
    // axis: a slope of 5e-3 against walls of 35, the minimum 1.6 rad away),
    // so the search starts long whatever the spread.
    for (Real t = std::fmax(Real(0.5), 4 * spread); t > kPolishShortestStep * spread; t *= 0.25) {
      if (try_direction(md, normalized(from.u - (e1 * d.x + e2 * d.y) * (t / dn)), best)) {
        length = t;
        return true;
      }
    }
  }
  return false;
}

/// Minimises f from the unit direction u; returns false when nothing improved.
/// On return u is the best direction, f its value and sp its support point.
template <class MD>
bool polish_direction(MD& md, Vec3& u, Real& f, SupportPoint& sp, Real size, int& iterations) noexcept {
  PolishPoint at = polish_point(md, u);
  const Real f_start = at.f;
  Real radius = 0.05;  // trust radius, radians
  constexpr Real eta = kPolishStep;
  for (int it = 0; it < kMaxPolishIterations; ++it) {
    ++iterations;
    Vec3 e1, e2;
    orthonormal_basis(at.u, e1, e2);
    const Real g[2] = {dot(at.gradient, e1), dot(at.gradient, e2)};
    const Real gnorm = std::hypot(g[0], g[1]);
    if (!(gnorm > kPolishRelTol * size)) break;
    // Hessian of f in the chart by central differences of the tangential gradient.
    Real h[2][2];
    SupportPoint tmp;
    const Vec3 e[2] = {e1, e2};
    for (int j = 0; j < 2; ++j) {
      const Vec3 tp = tangential(md, normalized(at.u + e[j] * eta), tmp);
      const Vec3 tm = tangential(md, normalized(at.u - e[j] * eta), tmp);
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
    PolishPoint next = at;
    bool improved = false, full_newton = false;
    for (int pass = 0; pass < 2 && !improved; ++pass) {
      if (pass == 1) step[0] = -g[0] / gnorm * radius, step[1] = -g[1] / gnorm * radius;
      for (int tries = 0; tries < 30 && !improved; ++tries) {
        improved = try_direction(md, normalized(at.u + e1 * step[0] + e2 * step[1]), next);
        if (improved) full_newton = pass == 0 && tries == 0;
        else step[0] *= 0.25, step[1] *= 0.25;
      }
    }
    Real length = std::hypot(step[0], step[1]);
    if (!full_newton) {
      // Backtracked or fell back to steepest descent: a kink. Steepest
      // descent zigzags across a V-shaped valley in ever shorter steps (two
      // coaxial cylinders stopped 1.6e-4 deep of the minimum after 30), so
      // the valley's own direction is tried too, and the lower point kept.
      Real length_v = 0;
      if (valley_step(md, at, radius, size, next, length_v)) {
        length = length_v;
        improved = true;
      }
    }
    if (!improved) break;
    at = next;
    radius = std::fmin(0.5, 2 * length + kPolishMinRadius);
  }
  u = at.u;
  f = at.f;
  sp = at.sp;
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
  int hull_a[3 * kProbes], hull_b[3 * kProbes];
  const int na = static_cast<int>(convex_hull_2d(pa, tol, hull_a)), nb = static_cast<int>(convex_hull_2d(pb, tol, hull_b));
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
void polish_penetration(MD& md, EpaOutput& e, const EpaPolytope& poly, Real size) noexcept {
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
    // f can have more than one local minimum on the sphere: two coaxial
    // cylinders have a ring of radial minima (f = R all round) and one
    // along the axis (H - offset), and EPA's closest face may lie on the
    // ring (6.4e-5 too deep). f at each normal of EPA's faces is an upper
    // bound too (f >= the face's distance): the lowest one, when below the
    // polished f, lies in a lower basin, and the polish starts again there.
    const Real below = f - (kEpaRelTol * f + kEpaAbsTol * size);
    Vec3 u2;
    Real f2 = below;
    for (int k = 0; k < poly.num_faces; ++k) {
      const EpaFace& face = poly.faces[k];
      if (face.obsolete || !(face.dist < f2)) continue;
      const Real fk = dot(md.support(face.normal).w, face.normal);
      if (fk < f2) { f2 = fk; u2 = face.normal; }
    }
    if (f2 < below) {
      SupportPoint sp2;
      polish_direction(md, u2, f2, sp2, size, steps);
      if (f2 < f) { u = u2; f = f2; sp = sp2; }
    }
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
