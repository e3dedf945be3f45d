#pragma once
// Solid circular cylinder along local z, flat caps at z = +-half_height.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Cylinder {
  Real radius = 0;       ///< > 0
  Real half_height = 0;  ///< > 0
};

/// Rim point in the direction of d's radial part; the cap centre when d is axial.
inline Vec3 support(const Cylinder& c, const Vec3& d, int&) noexcept {
  const Real z = std::copysign(c.half_height, d.z);
  const Real r = std::hypot(d.x, d.y);
  if (!(r > 0)) return {0, 0, z};
  return {c.radius * d.x / r, c.radius * d.y / r, z};
}
inline Real bounding_radius(const Cylinder& c) noexcept { return std::hypot(c.radius, c.half_height); }

}  // namespace gjkdem
