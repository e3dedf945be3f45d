#include "gjkdem/shape/predicates.hpp"

#include <cmath>
#include <gmpxx.h>

namespace gjkdem {
namespace {

// A filter's answer is trusted when the value exceeds this many times the
// sum of the magnitudes of its terms (the bound on the rounding error of
// the floating-point evaluation, Shewchuk's 7 eps for orient3d, with room);
// below kTinyPermanent products may have lost bits to underflow.
constexpr Real kFilterRelBound = 2e-15;
constexpr Real kTinyPermanent = 1e-250;

int sign_of(Real v) { return (v > 0) - (v < 0); }
int sign_of(const mpq_class& v) { return sgn(v); }

// Whether one of the factors of x y z is zero (so the product is zero
// exactly, not by underflow).
bool has_zero(Real x, Real y, Real z) { return x == 0 || y == 0 || z == 0; }

mpq_class exact(Real v) { return mpq_class(v); }

int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const mpq_class bx = exact(b.x) - exact(a.x), by = exact(b.y) - exact(a.y), bz = exact(b.z) - exact(a.z);
  const mpq_class cx = exact(c.x) - exact(a.x), cy = exact(c.y) - exact(a.y), cz = exact(c.z) - exact(a.z);
  const mpq_class dx = exact(d.x) - exact(a.x), dy = exact(d.y) - exact(a.y), dz = exact(d.z) - exact(a.z);
  const mpq_class det = bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
  return sign_of(det);
}

int cross_sign_exact(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, int axis) {
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  const mpq_class ui = exact(q[i]) - exact(p[i]), uj = exact(q[j]) - exact(p[j]);
  const mpq_class vi = exact(s[i]) - exact(r[i]), vj = exact(s[j]) - exact(r[j]);
  return sign_of(mpq_class(ui * vj - uj * vi));
}

// The first nonzero sign of the components of v (x, then y, then z): the
// sign of v . delta as e -> 0+.
template <class Component>
int delta_sign(Component component) {
  for (int axis = 0; axis < 3; ++axis)
    if (const int s = component(axis)) return s;
  return 0;
}

}  // namespace

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const Real m1 = v.y * w.z, m2 = v.z * w.y, m3 = v.x * w.z, m4 = v.z * w.x, m5 = v.x * w.y, m6 = v.y * w.x;
  const Real det = u.x * (m1 - m2) - u.y * (m3 - m4) + u.z * (m5 - m6);
  const Real permanent = std::fabs(u.x) * (std::fabs(m1) + std::fabs(m2)) + std::fabs(u.y) * (std::fabs(m3) + std::fabs(m4)) +
                         std::fabs(u.z) * (std::fabs(m5) + std::fabs(m6));
  if (std::fabs(det) > kFilterRelBound * permanent && permanent > kTinyPermanent) return sign_of(det);
  // A permanent of 0 is a determinant of 0 where each of its six products
  // has a zero factor, not where products of tiny numbers underflowed.
  if (permanent == 0 && has_zero(u.x, v.y, w.z) && has_zero(u.x, v.z, w.y) && has_zero(u.y, v.x, w.z) &&
      has_zero(u.y, v.z, w.x) && has_zero(u.z, v.x, w.y) && has_zero(u.z, v.y, w.x))
    return 0;
  return orient3d_exact(a, b, c, d);
}

int cross_sign(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, int axis) {
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  const Real ui = q[i] - p[i], uj = q[j] - p[j], vi = s[i] - r[i], vj = s[j] - r[j];
  const Real a = ui * vj, b = uj * vi;
  const Real permanent = std::fabs(a) + std::fabs(b);
  if (std::fabs(a - b) > kFilterRelBound * permanent && permanent > kTinyPermanent) return sign_of(a - b);
  if (permanent == 0 && (ui == 0 || vj == 0) && (uj == 0 || vi == 0)) return 0;  // (as in orient3d)
  return cross_sign_exact(p, q, r, s, axis);
}

int perturbed_orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Side abc) {
  bool on_plane = false;
  return perturbed_orient3d(a, b, c, d, abc, on_plane);
}

int perturbed_orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Side abc, bool& on_plane) {
  on_plane = false;
  if (const int s = orient3d(a, b, c, d)) return s;
  on_plane = true;
  // det[b - a, c - a, d -/+ delta - a] = det - / + n . delta, n = (b - a) x (c - a).
  const int n = delta_sign([&](int axis) { return cross_sign(a, b, a, c, axis); });
  return abc == Side::B ? -n : n;
}

void perturbed_orient3d_three(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3 (&d)[3], Side abc, int (&sign)[3],
                              bool (&on_plane)[3]) {
  // det[b - a, c - a, d - a] = (d - a) . n, n = (b - a) x (c - a): the same
  // six triple products as orient3d's, so the same permanent and bound.
  const Vec3 u = b - a, v = c - a;
  const Real n1 = u.y * v.z, n2 = u.z * v.y, n3 = u.z * v.x, n4 = u.x * v.z, n5 = u.x * v.y, n6 = u.y * v.x;
  const Vec3 n{n1 - n2, n3 - n4, n5 - n6};
  const Vec3 bound{std::fabs(n1) + std::fabs(n2), std::fabs(n3) + std::fabs(n4), std::fabs(n5) + std::fabs(n6)};
  for (int k = 0; k < 3; ++k) {
    const Vec3 w = d[k] - a;
    const Real det = w.x * n.x + w.y * n.y + w.z * n.z;
    const Real permanent = std::fabs(w.x) * bound.x + std::fabs(w.y) * bound.y + std::fabs(w.z) * bound.z;
    on_plane[k] = false;
    if (std::fabs(det) > kFilterRelBound * permanent && permanent > kTinyPermanent) sign[k] = sign_of(det);
    else sign[k] = perturbed_orient3d(a, b, c, d[k], abc, on_plane[k]);
  }
}

int perturbed_orient3d_edges(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, Side pq) {
  if (const int o = orient3d(p, q, r, s)) return o;
  // Edge rs moved by delta: det[q - p, r - p, s - p] + ((q - p) x (r - s)) . delta;
  // edge pq moved: the same with -delta.
  const int m = delta_sign([&](int axis) { return cross_sign(p, q, s, r, axis); });
  return pq == Side::A ? m : -m;
}

}  // namespace gjkdem
