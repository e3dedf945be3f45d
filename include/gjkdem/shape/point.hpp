#pragma once
// A single point at the local origin. With a margin it is a sphere.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Point {};

/// Support functions take the shape first, a local direction (need not be unit),
/// and a hint slot that only polytopes use (a vertex index to start from).
inline Vec3 support(const Point&, const Vec3&, int&) noexcept { return {}; }
inline Real bounding_radius(const Point&) noexcept { return 0; }

}  // namespace gjkdem
