#pragma once
// Axis-aligned boxes: the bound of a placed shape (six support calls, or a
// small hull's corners placed), and the overlap test the broad phase, the
// domains and the scene checks share.
#include "gjkdem/math/transform.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

struct Aabb {
  Vec3 lo, hi;
};

/// True when the boxes overlap (touching counts).
inline bool overlaps(const Aabb& a, const Aabb& b) noexcept {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

/// The smallest box holding both.
inline Aabb enclose(const Aabb& a, const Aabb& b) noexcept { return {min(a.lo, b.lo), max(a.hi, b.hi)}; }

/// The smallest axis-aligned box holding the placed shape (six support calls,
/// or a small hull's corners placed: the same bits), grown by `pad` (m) on
/// every side (the contact margin, or a skin for reuse).
Aabb aabb(const Shape& shape, const Transform& pose, Real pad = 0) noexcept;

}  // namespace gjkdem
