#pragma once
// Axis-aligned box centred at the local origin.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Box {
  Vec3 half_extents;  ///< >= 0, local frame
};

inline Vec3 support(const Box& b, const Vec3& d, int&) noexcept {
  return {std::copysign(b.half_extents.x, d.x), std::copysign(b.half_extents.y, d.y),
          std::copysign(b.half_extents.z, d.z)};
}
inline Real bounding_radius(const Box& b) noexcept { return length(b.half_extents); }

/// Corners of the face with outward normal sign * e_axis (sign = +-1),
/// counter-clockwise seen from outside.
inline void box_face(const Box& b, int axis, Real sign, Vec3 (&corners)[4]) noexcept {
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  const Real cu[4] = {-1, 1, 1, -1}, cw[4] = {-1, -1, 1, 1};
  for (int k = 0; k < 4; ++k) {
    const int j = sign > 0 ? k : 3 - k;  // the negative face winds the other way
    corners[k][axis] = sign * b.half_extents[axis];
    corners[k][u] = cu[j] * b.half_extents[u];
    corners[k][w] = cw[j] * b.half_extents[w];
  }
}

}  // namespace gjkdem
