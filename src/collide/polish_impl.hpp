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

/// Refines an unconverged EPA answer on pairs with a curved core (ellipsoid,
/// superellipsoid, cylinder, cone): the normal is polished, the depth becomes
/// f at the polished normal, and the witness on a unique-support side is its
/// support point (else A's).
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
    } else {  // both may have support sets (a cylinder's side): A's support point
      e.witness_a = sp.a;
      e.witness_b = sp.a - u * f;
    }
    e.status = EpaStatus::Converged;
  }
}

}  // namespace gjkdem::detail
