#include "gjkdem/collide/surface_distance.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "gjkdem/collide/triangle_contact.hpp"

namespace gjkdem {
namespace {

// The squared distance between two boxes (plain selects: libm's fmax is a
// call, and this runs for every node pair the walk meets).
Real box_distance2(const Aabb& a, const Aabb& b) {
  Real d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const Real below = a.lo[k] - b.hi[k], above = b.lo[k] - a.hi[k];
    const Real gap = below > above ? below : above;
    if (gap > 0) d2 += gap * gap;
  }
  return d2;
}

}  // namespace

SurfaceDistance surface_distance(const Surface& a, const Surface& b) {
  SurfaceDistance best;
  best.distance = std::numeric_limits<Real>::infinity();
  if (a.tree.nodes.empty() || b.tree.nodes.empty()) return best;
  const auto corner = [](const Surface& s, std::uint32_t t, int k) -> const Vec3& { return s.vertices[s.triangles[t][k]]; };
  // Triangle pairs wait in a batch for the kernel; the bound tightens at
  // each flush (a few more pairs tested than one by one, each far cheaper).
  constexpr std::size_t kFlushPairs = 8 * kTriangleLanes;
  TrianglePairs batch;
  std::vector<TriangleDistanceBlock> answers;
  const auto flush = [&] {
    if (batch.size == 0) return;
    triangle_distances(batch, answers);
    for (std::size_t i = 0; i < batch.size; ++i) {
      const TriangleDistanceBlock& r = answers[i / kTriangleLanes];
      const std::size_t l = i % kTriangleLanes;
      if (r.distance[l] < best.distance)
        best = {r.distance[l], {r.witness_a[0][l], r.witness_a[1][l], r.witness_a[2][l]},
                {r.witness_b[0][l], r.witness_b[1][l], r.witness_b[2][l]}};
    }
    batch.clear();
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const BoxTree::Node& n = a.tree.nodes[i];
    const BoxTree::Node& m = b.tree.nodes[j];
    if (box_distance2(n.box, m.box) >= best.distance * best.distance) continue;
    if (n.count && m.count) {
      for (std::uint32_t s = n.first; s < n.first + n.count; ++s)
        for (std::uint32_t t = m.first; t < m.first + m.count; ++t) {
          if (box_distance2(a.tree.item_boxes[s], b.tree.item_boxes[t]) >= best.distance * best.distance) continue;
          const std::uint32_t ta = a.tree.items[s], tb = b.tree.items[t];
          batch.push_back(corner(a, ta, 0), corner(a, ta, 1), corner(a, ta, 2), corner(b, tb, 0), corner(b, tb, 1),
                          corner(b, tb, 2));
        }
      if (batch.size >= kFlushPairs) flush();
      continue;
    }
    const Vec3 sn = n.box.hi - n.box.lo, sm = m.box.hi - m.box.lo;
    const bool split_a = !n.count && (m.count || sn.x + sn.y + sn.z >= sm.x + sm.y + sm.z);
    // The nearer child last, so that it is looked at first.
    std::pair<std::uint32_t, std::uint32_t> c1 = split_a ? std::pair{n.left, j} : std::pair{i, m.left};
    std::pair<std::uint32_t, std::uint32_t> c2 = split_a ? std::pair{n.right, j} : std::pair{i, m.right};
    const auto gap = [&](const std::pair<std::uint32_t, std::uint32_t>& c) {
      return box_distance2(a.tree.nodes[c.first].box, b.tree.nodes[c.second].box);
    };
    if (gap(c1) < gap(c2)) std::swap(c1, c2);
    stack.push_back(c1);
    stack.push_back(c2);
  }
  flush();
  return best;
}

}  // namespace gjkdem
