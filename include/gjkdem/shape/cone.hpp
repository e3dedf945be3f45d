#pragma once
// Solid circular cone along local z: apex at z = +half_height, base disc of
// `radius` at z = -half_height.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Cone {
  Real radius = 0;       ///< base radius > 0
  Real half_height = 0;  ///< > 0
};

/// The apex or a base rim point, whichever reaches further along d.
inline Vec3 support(const Cone& c, const Vec3& d, int&) noexcept {
  const Real r = std::hypot(d.x, d.y);
  const Real apex = c.half_height * d.z;
  const Real rim = c.radius * r - c.half_height * d.z;
  if (apex >= rim) return {0, 0, c.half_height};
  if (!(r > 0)) return {0, 0, -c.half_height};
  return {c.radius * d.x / r, c.radius * d.y / r, -c.half_height};
}
inline Real bounding_radius(const Cone& c) noexcept { return std::fmax(c.half_height, std::hypot(c.radius, c.half_height)); }

}  // namespace gjkdem
