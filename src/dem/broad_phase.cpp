#include "gjkdem/dem/broad_phase.hpp"

#include <algorithm>

namespace gjkdem {

Aabb aabb(const Shape& shape, const Transform& pose, Real pad) noexcept {
  Aabb box;
  for (int k = 0; k < 3; ++k) {
    Vec3 axis;
    axis[k] = 1;
    // Support along +-axis in world = pose applied to the support along R^T axis.
    const Vec3 local = apply_inverse_rotation(pose, axis);
    box.hi[k] = apply(pose, support(shape, local))[k] + pad;
    box.lo[k] = apply(pose, support(shape, -local))[k] - pad;
  }
  return box;
}

void overlapping_pairs(std::span<const Aabb> boxes, std::vector<std::uint32_t>& order, std::vector<BodyPair>& pairs) {
  pairs.clear();
  const std::size_t n = boxes.size();
  if (n < 2) return;
  // Sweep axis: largest variance of the centres.
  Vec3 mean, sq;
  for (const Aabb& b : boxes) {
    const Vec3 c = (b.lo + b.hi) * 0.5;
    mean += c;
    sq += hadamard(c, c);
  }
  mean /= static_cast<Real>(n);
  const Vec3 var = sq / static_cast<Real>(n) - hadamard(mean, mean);
  const int axis = var.x >= var.y ? (var.x >= var.z ? 0 : 2) : (var.y >= var.z ? 1 : 2);
  if (order.size() != n) {
    order.resize(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  }
  // Insertion sort: linear when the order from the last step is nearly right.
  auto key = [&](std::uint32_t i) { return boxes[i].lo[axis]; };
  for (std::size_t i = 1; i < n; ++i) {
    const std::uint32_t v = order[i];
    std::size_t j = i;
    for (; j > 0 && key(order[j - 1]) > key(v); --j) order[j] = order[j - 1];
    order[j] = v;
  }
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  for (std::size_t a = 0; a < n; ++a) {
    const Aabb& ba = boxes[order[a]];
    for (std::size_t b = a + 1; b < n && key(order[b]) <= ba.hi[axis]; ++b) {
      const Aabb& bb = boxes[order[b]];
      if (bb.lo[u] > ba.hi[u] || bb.hi[u] < ba.lo[u] || bb.lo[w] > ba.hi[w] || bb.hi[w] < ba.lo[w]) continue;
      pairs.emplace_back(std::min(order[a], order[b]), std::max(order[a], order[b]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
}

}  // namespace gjkdem
