// Deep points of a closed surface's solid (deep_points.hpp).
#include "gjkdem/shape/deep_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {

Real box_distance2(const Aabb& box, const Vec3& p) noexcept {
  const Vec3 out = max(max(box.lo - p, p - box.hi), Vec3{});
  return dot(out, out);
}

// A candidate's depth raised by a compass search: steps toward the 26
// neighbours of a cube's centre (a step shorter than the depth stays
// inside) taken while one goes deeper, halved while none does. The depth is
// 1-Lipschitz and concave across each convex region of the solid, so this
// climbs to the middle of the part the point is in (a torus's core circle,
// an arm's axis); the diagonals climb the ridges where two or three faces
// are nearest, which no step along one axis does.
DeepPoint deepen(const Surface& s, DeepPoint d) {
  std::array<Vec3, 26> axes;
  std::size_t n = 0;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) axes[n++] = normalized(Vec3{Real(x), Real(y), Real(z)});
  Real step = 0.5 * d.depth;
  const Real smallest = kDeepPointStepRel * d.depth;
  for (int k = 0; k < kDeepPointSteps && step > smallest; ++k) {
    DeepPoint best = d;
    for (const Vec3& u : axes) {
      const Vec3 q = d.point + u * step;
      const Real depth = distance_to_surface(s, q);
      if (depth > best.depth) best = {q, depth};
    }
    if (best.depth > d.depth) d = best, step = std::fmin(step, 0.5 * d.depth);
    else step *= 0.5;
  }
  return d;
}

// Deepest first, at most kDeepPointsMax, none within another's depth, none
// shallower than `floor`.
std::vector<DeepPoint> apart(std::vector<DeepPoint> found, Real floor) {
  std::stable_sort(found.begin(), found.end(), [](const DeepPoint& x, const DeepPoint& y) { return x.depth > y.depth; });
  std::vector<DeepPoint> kept;
  for (const DeepPoint& d : found) {
    if (kept.size() == kDeepPointsMax || d.depth < floor) break;
    if (std::all_of(kept.begin(), kept.end(), [&](const DeepPoint& k) { return length(d.point - k.point) > k.depth; }))
      kept.push_back(d);
  }
  return kept;
}

// 2 kDeepPointsMax of the candidates, the deepest first, then each the one
// farthest from those taken (so that every part of the solid has some,
// whatever the order of the grid).
std::vector<DeepPoint> spread(std::vector<DeepPoint> found) {
  std::vector<DeepPoint> taken;
  if (found.empty()) return taken;
  std::vector<Real> gap(found.size(), std::numeric_limits<Real>::infinity());
  std::size_t next = static_cast<std::size_t>(std::max_element(found.begin(), found.end(), [](const DeepPoint& x, const DeepPoint& y) {
                                                return x.depth < y.depth;
                                              }) - found.begin());
  while (taken.size() < 2 * kDeepPointsMax && gap[next] > 0) {
    taken.push_back(found[next]);
    for (std::size_t i = 0; i < found.size(); ++i) gap[i] = std::fmin(gap[i], length(found[i].point - found[next].point));
    next = static_cast<std::size_t>(std::max_element(gap.begin(), gap.end()) - gap.begin());
  }
  return taken;
}

}  // namespace

Real distance_to_surface(const Surface& s, const Vec3& p) {
  // Through the tree of the triangles' boxes, nearer child first, skipping
  // nodes no nearer than the best so far.
  const BoxTree& tree = s.tree;
  Real best2 = std::numeric_limits<Real>::infinity();
  if (tree.nodes.empty()) return std::sqrt(best2);
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BoxTree::Node& n = tree.nodes[stack[--top]];
    if (box_distance2(n.box, p) >= best2) continue;
    if (n.count) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        if (box_distance2(tree.item_boxes[i], p) >= best2) continue;
        const TriangleIndices& k = s.triangles[tree.items[i]];
        const Vec3 d = p - closest_point_on_triangle(p, s.vertices[k[0]], s.vertices[k[1]], s.vertices[k[2]]);
        best2 = std::fmin(best2, dot(d, d));
      }
      continue;
    }
    const Real left = box_distance2(tree.nodes[n.left].box, p), right = box_distance2(tree.nodes[n.right].box, p);
    if (top + 2 > 64) {  // deeper than any median-split tree of 2^32 boxes: scan what is left
      for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        const TriangleIndices& k = s.triangles[t];
        const Vec3 d = p - closest_point_on_triangle(p, s.vertices[k[0]], s.vertices[k[1]], s.vertices[k[2]]);
        best2 = std::fmin(best2, dot(d, d));
      }
      break;
    }
    stack[top++] = left < right ? n.right : n.left;  // the nearer popped first
    stack[top++] = left < right ? n.left : n.right;
  }
  return std::sqrt(best2);
}

std::vector<DeepPoint> deep_points(const Surface& s) {
  std::vector<DeepPoint> found;
  auto consider = [&](const Vec3& p) {
    if (winding_number(s.vertices, s.triangles, p) > 0.5) found.push_back({p, distance_to_surface(s, p)});
  };
  consider(s.centroid);
  const Vec3 size = s.box.hi - s.box.lo;
  constexpr int n = kDeepPointGrid;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        consider(s.box.lo + Vec3{size.x * (i + 0.5) / n, size.y * (j + 0.5) / n, size.z * (k + 0.5) / n});
  // A spread of the candidates deepened, then spread again (some climb to
  // one place).
  std::vector<DeepPoint> deepened = spread(std::move(found));
  for (DeepPoint& d : deepened) d = deepen(s, d);
  if (deepened.empty()) return deepened;
  const Real deepest = std::max_element(deepened.begin(), deepened.end(), [](const DeepPoint& x, const DeepPoint& y) {
                         return x.depth < y.depth;
                       })->depth;
  return apart(std::move(deepened), kDeepPointRel * deepest);
}

std::shared_ptr<DeepPointsSlot> deep_points_slot(const Surface& s) {
  Real area = 0;
  for (const TriangleIndices& k : s.triangles)
    area += 0.5 * length(cross(s.vertices[k[1]] - s.vertices[k[0]], s.vertices[k[2]] - s.vertices[k[0]]));
  auto slot = std::make_shared<DeepPointsSlot>();
  slot->reach_bound = area > 0 ? kDeepReachRel * kDeepPointRel * s.volume / area : 0;
  return slot;
}

const std::vector<DeepPoint>& deep_points(const Surface& s, DeepPointsSlot& slot) {
  std::call_once(slot.made, [&] { slot.points = deep_points(s); });
  return slot.points;
}

}  // namespace gjkdem
