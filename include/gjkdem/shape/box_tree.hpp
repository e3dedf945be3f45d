#pragma once
// A bounding-volume tree over axis-aligned boxes, each with an id: median
// splits on the longest axis of the boxes' centres, two children a node,
// stored flat. The fixed bodies of a world (dem/broad_phase.hpp) and the
// triangles of a surface (surface.hpp) are kept in one. Queries visit only
// the nodes, and report only the boxes, that meet the query's box.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "gjkdem/shape/aabb.hpp"

namespace gjkdem {

struct BoxTree {
  struct Node {
    Aabb box;
    std::uint32_t first = 0, count = 0;  ///< leaf: items[first .. first + count); inner: count = 0
    std::uint32_t left = 0, right = 0;   ///< children (inner nodes)
  };
  std::vector<Node> nodes;             ///< nodes[0] is the root (empty tree: no nodes)
  std::vector<Aabb> item_boxes;        ///< leaf by leaf
  std::vector<std::uint32_t> items;    ///< the ids given to build, leaf by leaf
};

/// Builds the tree of `boxes`, each with the id at the same position in `ids`.
void build_box_tree(std::span<const Aabb> boxes, std::span<const std::uint32_t> ids, BoxTree& tree);

/// The same tree over moved boxes (`boxes[id]`: each id's box now): the
/// boxes and nodes refitted, the tree's shape kept.
void refit_box_tree(BoxTree& tree, std::span<const Aabb> boxes);

/// Appends to `found` the id of every box of the tree that overlaps `box`
/// (touching counts).
void query_box_tree(const BoxTree& tree, const Aabb& box, std::vector<std::uint32_t>& found);

/// Calls visit(i, j) for every pair of ids, i of a and j of b, whose boxes
/// overlap (the same frame), except under a pair of nodes n of a and m of b
/// for which skip(n, m) holds (node indices: the caller knows what their
/// items share).
template <class Visit, class Skip>
void overlapping_items(const BoxTree& a, const BoxTree& b, Visit&& visit, Skip&& skip) {
  if (a.nodes.empty() || b.nodes.empty()) return;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const BoxTree::Node& n = a.nodes[i];
    const BoxTree::Node& m = b.nodes[j];
    if (!overlaps(n.box, m.box) || skip(i, j)) continue;
    if (n.count && m.count) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s)
        for (std::uint32_t t = m.first; t < m.first + m.count; ++t)
          if (overlaps(a.item_boxes[s], b.item_boxes[t])) visit(a.items[s], b.items[t]);
      continue;
    }
    const Vec3 sn = n.box.hi - n.box.lo, sm = m.box.hi - m.box.lo;
    if (m.count || (!n.count && sn.x + sn.y + sn.z >= sm.x + sm.y + sm.z)) {  // split the larger
      stack.push_back({n.left, j});
      stack.push_back({n.right, j});
    } else {
      stack.push_back({i, m.left});
      stack.push_back({i, m.right});
    }
  }
}

template <class Visit>
void overlapping_items(const BoxTree& a, const BoxTree& b, Visit&& visit) {
  overlapping_items(a, b, visit, [](std::uint32_t, std::uint32_t) { return false; });
}

}  // namespace gjkdem
