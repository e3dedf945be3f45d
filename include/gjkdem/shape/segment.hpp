#pragma once
// Line segment between two local points. With a margin it is a capsule.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Segment {
  Vec3 a, b;  ///< end points, local frame
};

inline Vec3 support(const Segment& s, const Vec3& d, int&) noexcept { return dot(s.b - s.a, d) > 0 ? s.b : s.a; }
inline Real bounding_radius(const Segment& s) noexcept { return std::fmax(length(s.a), length(s.b)); }

}  // namespace gjkdem
