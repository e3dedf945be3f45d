#include "gjkdem/shape/box_tree.hpp"

#include <algorithm>

namespace gjkdem {
namespace {

// Boxes per leaf.
constexpr std::uint32_t kLeafSize = 4;

// Node over items[first, first + count): a leaf, or a median split on the
// longest axis of the items' centres.
std::uint32_t build_node(BoxTree& t, std::vector<std::uint32_t>& order, std::uint32_t first, std::uint32_t count) {
  const std::uint32_t index = static_cast<std::uint32_t>(t.nodes.size());
  t.nodes.emplace_back();
  Aabb box = t.item_boxes[order[first]], centres{box.lo + box.hi, box.lo + box.hi};
  for (std::uint32_t k = first; k < first + count; ++k) {
    const Aabb& b = t.item_boxes[order[k]];
    box = enclose(box, b);
    centres = enclose(centres, Aabb{b.lo + b.hi, b.lo + b.hi});
  }
  t.nodes[index].box = box;
  if (count <= kLeafSize) {
    t.nodes[index].first = first;
    t.nodes[index].count = count;
    return index;
  }
  const Vec3 spread = centres.hi - centres.lo;
  const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
  const std::uint32_t half = count / 2;
  std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                   [&](std::uint32_t p, std::uint32_t q) {
                     return t.item_boxes[p].lo[axis] + t.item_boxes[p].hi[axis] <
                            t.item_boxes[q].lo[axis] + t.item_boxes[q].hi[axis];
                   });
  const std::uint32_t left = build_node(t, order, first, half);
  const std::uint32_t right = build_node(t, order, first + half, count - half);
  t.nodes[index].left = left;
  t.nodes[index].right = right;
  return index;
}

}  // namespace

void build_box_tree(std::span<const Aabb> boxes, std::span<const std::uint32_t> ids, BoxTree& tree) {
  tree.nodes.clear();
  tree.item_boxes.assign(boxes.begin(), boxes.end());
  std::vector<std::uint32_t> order(boxes.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  if (!boxes.empty()) build_node(tree, order, 0, static_cast<std::uint32_t>(boxes.size()));
  // Leaves hold ranges of `order`: store boxes and ids in that order.
  tree.items.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    tree.items[k] = ids[order[k]];
    tree.item_boxes[k] = boxes[order[k]];
  }
}

void query_box_tree(const BoxTree& tree, const Aabb& box, std::vector<std::uint32_t>& found) {
  if (tree.nodes.empty()) return;
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BoxTree::Node& node = tree.nodes[stack[--top]];
    if (!overlaps(node.box, box)) continue;
    if (node.count > 0) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
        if (overlaps(tree.item_boxes[k], box)) found.push_back(tree.items[k]);
    } else {
      stack[top++] = node.left;  // depth <= log2(n / kLeafSize) + 1, far below 64
      stack[top++] = node.right;
    }
  }
}

namespace {

// enclose() without the library's NaN rules (boxes here are finite): inline
// compares, where fmin and fmax are calls; a moved surface refits every step.
Aabb enclose_finite(const Aabb& a, const Aabb& b) noexcept {
  return {{a.lo.x < b.lo.x ? a.lo.x : b.lo.x, a.lo.y < b.lo.y ? a.lo.y : b.lo.y, a.lo.z < b.lo.z ? a.lo.z : b.lo.z},
          {a.hi.x > b.hi.x ? a.hi.x : b.hi.x, a.hi.y > b.hi.y ? a.hi.y : b.hi.y, a.hi.z > b.hi.z ? a.hi.z : b.hi.z}};
}

}  // namespace

void refit_box_tree(BoxTree& tree, std::span<const Aabb> boxes) {
  for (std::size_t k = 0; k < tree.items.size(); ++k) tree.item_boxes[k] = boxes[tree.items[k]];
  for (std::size_t k = tree.nodes.size(); k-- > 0;) {  // children come after their parent
    BoxTree::Node& n = tree.nodes[k];
    if (n.count) {
      n.box = tree.item_boxes[n.first];
      for (std::uint32_t i = n.first + 1; i < n.first + n.count; ++i) n.box = enclose_finite(n.box, tree.item_boxes[i]);
    } else {
      n.box = enclose_finite(tree.nodes[n.left].box, tree.nodes[n.right].box);
    }
  }
}

}  // namespace gjkdem
