#pragma once
// A flat triangle (the element of wall meshes and of the seed's triangle-pair query).
#include <cmath>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Triangle {
  Vec3 v[3];  ///< corners, local frame
};

inline Vec3 support(const Triangle& t, const Vec3& d, int&) noexcept {
  const Real d0 = dot(t.v[0], d), d1 = dot(t.v[1], d), d2 = dot(t.v[2], d);
  if (d0 >= d1) return d0 >= d2 ? t.v[0] : t.v[2];
  return d1 >= d2 ? t.v[1] : t.v[2];
}
inline Real bounding_radius(const Triangle& t) noexcept {
  return std::fmax(length(t.v[0]), std::fmax(length(t.v[1]), length(t.v[2])));
}

/// The point of triangle abc nearest p, by the region of its plane p
/// projects into (a corner, an edge or the inside: barycentric coordinates
/// from dot products); a degenerate triangle's first corner where no region
/// holds it.
inline Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Real d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const Real d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const Real d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const Real sum = va + vb + vc;
  if (!(sum > 0)) return a;
  return a + ab * (vb / sum) + ac * (vc / sum);
}

}  // namespace gjkdem
