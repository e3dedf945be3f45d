#pragma once
// Broad phase: tight axis-aligned boxes from support functions, and the pairs
// of overlapping boxes by sweep and prune (Baraff 1992; Cohen et al. 1995) on
// the axis along which the boxes' centres spread most. The sort is the only
// super-linear step; callers that keep `order` between steps pay an almost
// linear insertion sort on coherent motion.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

struct Aabb {
  Vec3 lo, hi;
};

/// The smallest axis-aligned box holding the placed shape (six support calls),
/// grown by `pad` (m) on every side (the contact margin, or a skin for reuse).
Aabb aabb(const Shape& shape, const Transform& pose, Real pad = 0) noexcept;

using BodyPair = std::pair<std::uint32_t, std::uint32_t>;

/// Every pair (i < j) of overlapping boxes (touching counts), sorted. `order`
/// is the sweep order kept between calls (any content is accepted; it is
/// rebuilt when its size does not match).
void overlapping_pairs(std::span<const Aabb> boxes, std::vector<std::uint32_t>& order, std::vector<BodyPair>& pairs);

}  // namespace gjkdem
