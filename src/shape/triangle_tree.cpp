#include "gjkdem/shape/triangle_tree.hpp"

#include <algorithm>

namespace gjkdem {
namespace {

constexpr std::uint32_t kLeafSize = 4;  // triangles per leaf

Aabb merged(const Aabb& a, const Aabb& b) { return {min(a.lo, b.lo), max(a.hi, b.hi)}; }

std::uint32_t build(TriangleTree& tree, std::span<const Aabb> boxes, std::uint32_t first, std::uint32_t count) {
  const std::uint32_t index = static_cast<std::uint32_t>(tree.nodes.size());
  tree.nodes.emplace_back();
  Aabb box = boxes[tree.items[first]];
  for (std::uint32_t k = first + 1; k < first + count; ++k) box = merged(box, boxes[tree.items[k]]);
  tree.nodes[index].box = box;
  if (count <= kLeafSize) {
    tree.nodes[index].first = first;
    tree.nodes[index].count = count;
    return index;
  }
  const Vec3 size = box.hi - box.lo;
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
  const auto centre = [&](std::uint32_t t) { return boxes[t].lo[axis] + boxes[t].hi[axis]; };
  const std::uint32_t half = count / 2;
  std::nth_element(tree.items.begin() + first, tree.items.begin() + first + half, tree.items.begin() + first + count,
                   [&](std::uint32_t s, std::uint32_t t) { return centre(s) < centre(t) || (centre(s) == centre(t) && s < t); });
  const std::uint32_t left = build(tree, boxes, first, half);
  const std::uint32_t right = build(tree, boxes, first + half, count - half);
  tree.nodes[index].first = left;
  tree.nodes[index].right = right;
  return index;
}

}  // namespace

TriangleTree build_triangle_tree(std::span<const Aabb> boxes) {
  TriangleTree tree;
  if (boxes.empty()) return tree;
  tree.items.resize(boxes.size());
  for (std::uint32_t k = 0; k < boxes.size(); ++k) tree.items[k] = k;
  tree.nodes.reserve(2 * boxes.size() / kLeafSize + 2);
  build(tree, boxes, 0, static_cast<std::uint32_t>(boxes.size()));
  return tree;
}

void query_triangle_tree(const TriangleTree& tree, const Aabb& box, std::vector<std::uint32_t>& out) {
  if (tree.nodes.empty()) return;
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const TriangleTree::Node& n = tree.nodes[stack.back()];
    stack.pop_back();
    if (!overlaps(n.box, box)) continue;
    if (n.count) {
      out.insert(out.end(), tree.items.begin() + n.first, tree.items.begin() + n.first + n.count);
    } else {
      stack.push_back(n.first);
      stack.push_back(n.right);
    }
  }
}

}  // namespace gjkdem
