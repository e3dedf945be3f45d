// Edges along which the two solids' wedges pinch: A ∩ B is two pieces
// touching along the line there (surface_overlap_detail.hpp).
#include <cmath>

#include "gjkdem/tolerances.hpp"
#include "surface_overlap_detail.hpp"

namespace gjkdem::surface_overlap_detail {
namespace {

// The solid's wedge at an edge of its surface, seen down the line d (from
// p): the angle (about d, from `ref`) where it starts and its width,
// counter-clockwise, between the rays of the edge's two faces.
struct Wedge {
  Real start, width;
};

Wedge wedge_at(const Surface& s, std::uint32_t e, const Vec3& d, const Vec3& ref) {
  const Vec3& p = s.vertices[s.edges[e][0]];
  const Vec3 side = cross(d, ref);
  const auto angle = [&](const Vec3& u) { return std::atan2(dot(u, side), dot(u, ref)); };
  Real rays[2];
  Vec3 inward[2];
  for (int k = 0; k < 2; ++k) {
    const TriangleIndices& t = s.triangles[s.edge_triangles[e][k]];
    Vec3 w;  // the triangle's corner off the edge
    for (const std::uint32_t i : t)
      if (i != s.edges[e][0] && i != s.edges[e][1]) w = s.vertices[i];
    rays[k] = angle(w - p);
    inward[k] = -cross(s.vertices[t[1]] - s.vertices[t[0]], s.vertices[t[2]] - s.vertices[t[0]]);
  }
  // The solid lies on the inward side of the first face's ray: counter-
  // clockwise from it when the inward normal points that way.
  const Real turn = angle(inward[0]) - rays[0];
  const bool ccw = std::sin(turn) > 0;
  const Real from = ccw ? rays[0] : rays[1], to = ccw ? rays[1] : rays[0];
  Real width = to - from;
  while (width <= 0) width += 2 * kPi;
  while (width > 2 * kPi) width -= 2 * kPi;
  return {from, width};
}

// Whether the intersection of two wedges about one line is two sectors that
// touch along the line only: their gaps (the complements) do not meet.
bool wedges_pinch(const Wedge& x, const Wedge& y) {
  const auto wrap = [](Real a) {
    while (a < 0) a += 2 * kPi;
    while (a >= 2 * kPi) a -= 2 * kPi;
    return a;
  };
  // Gaps: from start + width, of length 2 pi - width; disjoint when the
  // other gap's start lies outside this one and this one's outside that.
  const Real gx = wrap(x.start + x.width), lx = 2 * kPi - x.width;
  const Real gy = wrap(y.start + y.width), ly = 2 * kPi - y.width;
  const bool y_starts_in_x = wrap(gy - gx) <= lx, x_starts_in_y = wrap(gx - gy) <= ly;
  return !y_starts_in_x && !x_starts_in_y;
}

}  // namespace

// Edge e of v's surface lies along an edge of `solid`'s (among the
// triangles `near`) where the two solids' wedges pinch: A ∩ B is two pieces
// touching along the line there, and e's faces belong one to each.
bool pinched(const Surface& s, std::uint32_t e, const Surface& solid, std::vector<std::uint32_t>& near) {
  near.clear();
  query_box_tree(solid.tree, s.edge_boxes[e], near);
  const Vec3 &p = s.vertices[s.edges[e][0]], &q = s.vertices[s.edges[e][1]];
  const Vec3 d = q - p;
  for (const std::uint32_t t : near)
    for (const std::uint32_t f : solid.triangle_edges[t]) {
      const Vec3 &r = solid.vertices[solid.edges[f][0]], &w = solid.vertices[solid.edges[f][1]];
      const Real scale = dot(d, d) * (dot(r - p, r - p) + dot(w - p, w - p));
      if (dot(cross(d, r - p), cross(d, r - p)) + dot(cross(d, w - p), cross(d, w - p)) > kCollinearScreenRel2 * scale)
        continue;  // clearly off the line (the exact test below decides the rest)
      bool collinear = true;
      for (int axis = 0; axis < 3 && collinear; ++axis)
        collinear = cross_sign(p, q, p, r, axis) == 0 && cross_sign(p, q, p, w, axis) == 0;
      if (!collinear) continue;
      const Real lo = std::fmin(dot(r - p, d), dot(w - p, d)), hi = std::fmax(dot(r - p, d), dot(w - p, d));
      if (!(std::fmin(hi, dot(d, d)) > std::fmax(lo, Real(0)))) continue;  // they share no length
      const Vec3 ref = std::fabs(d.x) < std::fabs(d.y) ? cross(d, Vec3{1, 0, 0}) : cross(d, Vec3{0, 1, 0});
      if (wedges_pinch(wedge_at(s, e, d, ref), wedge_at(solid, f, d, ref))) return true;
    }
  return false;
}

}  // namespace gjkdem::surface_overlap_detail
