#pragma once
// Barr's superellipsoid in the local frame:
//   (|x/a|^(2/e2) + |y/b|^(2/e2))^(e2/e1) + |z/c|^(2/e1) <= 1,  0 < e1, e2 <= 2 (convex).
// e1 = e2 = 1 is the ellipsoid, small exponents approach the box, 2 the octahedron.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Superellipsoid {
  Vec3 radii;     ///< a, b, c > 0
  Real e1 = 1;    ///< "north-south" exponent (z against the xy-plane)
  Real e2 = 1;    ///< "east-west" exponent (x against y)
};

namespace detail {
/// ||(x, y)||_p for x, y >= 0 and p in [1, inf], and the partial derivatives
/// (x/n)^(p-1), (y/n)^(p-1). For p = inf exactly one derivative is 1, so the
/// support point stays on the shape when x == y.
inline Real nested_norm(Real x, Real y, Real p, Real& dx, Real& dy) noexcept {
  const Real big = std::fmax(x, y);
  if (!(big > 0)) { dx = dy = 0; return 0; }
  if (std::isinf(p)) { dx = x >= y ? 1 : 0; dy = 1 - dx; return big; }
  const Real small = std::fmin(x, y);
  const Real n = big * std::pow(1 + std::pow(small / big, p), 1 / p);
  dx = std::pow(std::fmin(x / n, Real(1)), p - 1);
  dy = std::pow(std::fmin(y / n, Real(1)), p - 1);
  return n;
}
}  // namespace detail

/// The support function of the unit superellipsoid is the dual nested norm
/// h(g) = ||( ||(g1, g2)||_p2, g3 )||_p1 with p2 = 2/(2 - e2), p1 = 2/(2 - e1),
/// evaluated at g = radii * d; the support point is radii * grad h(g).
inline Vec3 support(const Superellipsoid& s, const Vec3& d, int&) noexcept {
  const Vec3 g = hadamard(s.radii, d);
  const Real p2 = 2 / (2 - s.e2), p1 = 2 / (2 - s.e1);  // inf when an exponent is 2
  Real d1, d2, drho, d3;
  const Real rho = detail::nested_norm(std::fabs(g.x), std::fabs(g.y), p2, d1, d2);
  detail::nested_norm(rho, std::fabs(g.z), p1, drho, d3);
  const Vec3 grad{std::copysign(drho * d1, g.x), std::copysign(drho * d2, g.y), std::copysign(d3, g.z)};
  return hadamard(s.radii, grad);
}
inline Real bounding_radius(const Superellipsoid& s) noexcept { return length(s.radii); }

}  // namespace gjkdem
