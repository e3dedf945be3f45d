#pragma once
// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 <= 1 in the local frame.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Ellipsoid {
  Vec3 radii;  ///< semi-axes a, b, c > 0
};

/// s(d) = R^2 d / |R d| with R = diag(radii): the point whose normal is along d.
inline Vec3 support(const Ellipsoid& e, const Vec3& d, int&) noexcept {
  const Vec3 rd = hadamard(e.radii, d);
  const Real len = length(rd);
  if (!(len > 0)) return {0, 0, e.radii.z};
  return hadamard(e.radii, rd) / len;
}
inline Real bounding_radius(const Ellipsoid& e) noexcept { return max_abs(e.radii); }

}  // namespace gjkdem
