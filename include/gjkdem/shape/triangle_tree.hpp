#pragma once
// A bounding-volume hierarchy of a surface's triangles: axis-aligned boxes
// in the surface's own frame, built once (top-down, split at the median
// centre along the box's longest side) and stored flat. Queries visit only
// the nodes whose boxes meet the query's.
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/shape/aabb.hpp"

namespace gjkdem {

struct TriangleTree {
  struct Node {
    Aabb box;
    std::uint32_t first = 0;  ///< a leaf: its triangles are items[first, first + count); else the left child
    std::uint32_t count = 0;  ///< 0 for an inner node
    std::uint32_t right = 0;  ///< an inner node's right child
  };
  std::vector<Node> nodes;            ///< nodes[0] is the root (empty for no triangles)
  std::vector<std::uint32_t> items;   ///< triangle indices, grouped by leaf
};

/// The tree over triangles with these boxes.
TriangleTree build_triangle_tree(std::span<const Aabb> boxes);

/// Appends to `out` every triangle whose box meets `box` (touching counts).
void query_triangle_tree(const TriangleTree& tree, const Aabb& box, std::vector<std::uint32_t>& out);

/// Calls visit(i, j) for every pair of triangles, i of a and j of b, whose
/// boxes meet; b's boxes are taken as they are (the same frame as a's).
template <class Visit>
void overlapping_triangles(const TriangleTree& a, const TriangleTree& b, Visit&& visit) {
  if (a.nodes.empty() || b.nodes.empty()) return;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const TriangleTree::Node& n = a.nodes[i];
    const TriangleTree::Node& m = b.nodes[j];
    if (!overlaps(n.box, m.box)) continue;
    if (n.count && m.count) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s)
        for (std::uint32_t t = m.first; t < m.first + m.count; ++t) visit(a.items[s], b.items[t]);
    } else if (m.count || (!n.count && n.box.hi.x - n.box.lo.x + n.box.hi.y - n.box.lo.y + n.box.hi.z - n.box.lo.z >=
                                            m.box.hi.x - m.box.lo.x + m.box.hi.y - m.box.lo.y + m.box.hi.z - m.box.lo.z)) {
      stack.push_back({n.first, j});
      stack.push_back({n.right, j});
    } else {
      stack.push_back({i, m.first});
      stack.push_back({i, m.right});
    }
  }
}

}  // namespace gjkdem
