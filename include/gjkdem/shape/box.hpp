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

}  // namespace gjkdem
