#pragma once
// A flat triangle (the element of wall meshes and of the seed's triangle-pair query).
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

}  // namespace gjkdem
