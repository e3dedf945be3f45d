// The status of a surface's vertices against the other solid, and the
// order of the crossings along its edges (surface_overlap_detail.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "surface_overlap_detail.hpp"

namespace gjkdem::surface_overlap_detail {
namespace {

// Whether vertex x of v's surface lies inside `solid`: the parity of the
// crossings of a segment from x to a point beyond the solid's box.
bool inside_by_ray(View& v, std::uint32_t x, const Surface& solid) {
  const Vec3& p = v.s->vertices[x];
  const Vec3 far{solid.box.hi.x + std::fabs(solid.box.hi.x) + 1, p.y, p.z};
  std::vector<std::uint32_t>& hits = v.hits;
  hits.clear();
  query_box_tree(solid.tree, Aabb{p, far}, hits);
  int count = 0;
  for (const std::uint32_t t : hits) {
    const TriangleIndices& tri = solid.triangles[t];
    count += crosses(p, far, solid.vertices[tri[0]], solid.vertices[tri[1]], solid.vertices[tri[2]], v.side);
  }
  return count % 2 == 1;
}

}  // namespace

// The crossings sorted along each edge, and each edge's (the edges without
// any keep their empty span: View::reset).
void index_crossings(View& v) {
  std::sort(v.crossings.begin(), v.crossings.end(),
            [](const Crossing& x, const Crossing& y) { return x.edge < y.edge || (x.edge == y.edge && x.t < y.t); });
  for (std::uint32_t c = 0; c < v.crossings.size();) {
    const std::uint32_t e = v.crossings[c].edge, begin = c;
    while (c < v.crossings.size() && v.crossings[c].edge == e) ++c;
    v.edge_crossings[e] = {begin, c};
  }
}

// Every vertex's status: outside where it lies beyond the solid's box (the
// corners of triangles far from it are, without a look), carried along the
// edges (a crossing flips it) from there into the box, a ray where nothing
// reaches. The walk starts at the box's edge, so its cost follows the
// vertices inside the box, not the whole surface.
void find_status(View& v, const Surface& solid) {
  const Surface& s = *v.s;
  v.near.clear();
  query_box_tree(s.tree, solid.box, v.near);
  for (const std::uint32_t t : v.near)
    for (const std::uint32_t i : s.triangles[t]) {
      const Vec3& p = s.vertices[i];
      if (v.inside[i] == 0 && p.x >= solid.box.lo.x && p.y >= solid.box.lo.y && p.z >= solid.box.lo.z &&
          p.x <= solid.box.hi.x && p.y <= solid.box.hi.y && p.z <= solid.box.hi.z) {
        v.inside[i] = -1;  // not known yet
        v.near_vertices.push_back(i);
      }
    }
  std::vector<std::uint32_t>& queue = v.queue;
  queue.clear();
  for (const std::uint32_t i : v.near_vertices) {  // the box's edge: where the walk starts
    if (v.inside[i] >= 0) continue;
    for (std::uint32_t k = s.vertex_edge_begin[i]; k < s.vertex_edge_begin[i + 1]; ++k) {
      const std::uint32_t e = s.vertex_edges[k];
      const std::uint32_t j = s.edges[e][0] == i ? s.edges[e][1] : s.edges[e][0];
      if (v.inside[j] < 0) continue;
      v.inside[i] = static_cast<std::int8_t>(v.inside[j] ^ (v.crossings_along(e) & 1));
      queue.push_back(i);
      break;
    }
  }
  const auto spread = [&] {
    while (!queue.empty()) {
      const std::uint32_t i = queue.back();
      queue.pop_back();
      for (std::uint32_t k = s.vertex_edge_begin[i]; k < s.vertex_edge_begin[i + 1]; ++k) {
        const std::uint32_t e = s.vertex_edges[k];
        const std::uint32_t j = s.edges[e][0] == i ? s.edges[e][1] : s.edges[e][0];
        if (v.inside[j] >= 0) continue;
        v.inside[j] = static_cast<std::int8_t>(v.inside[i] ^ (v.crossings_along(e) & 1));
        queue.push_back(j);
      }
    }
  };
  spread();
  for (const std::uint32_t i : v.near_vertices)
    if (v.inside[i] < 0) {
      v.inside[i] = inside_by_ray(v, i, solid);
      queue.push_back(i);
      spread();
    }
}

// Crossings at the same point along an edge (an edge through another
// surface's edge or vertex) may be sorted either way by their rounded
// positions: put each run of them in the order the exact statuses imply,
// an entry where the edge is outside, an exit where it is inside.
void order_crossings(View& v) {
  for (std::uint32_t first = 0; first < v.crossings.size();) {
    const std::uint32_t e = v.crossings[first].edge, end = v.edge_crossings[e][1];
    bool in = v.inside[v.s->edges[e][0]];
    for (std::uint32_t c = first; c < end; ++c) {
      if (v.crossings[c].exits != in) {
        std::uint32_t d = c + 1;  // the next crossing that fits
        while (d < end && v.crossings[d].exits != in) ++d;
        if (d == end) throw std::logic_error("surface_overlap: crossings out of step along an edge");
        std::swap(v.crossings[c], v.crossings[d]);
      }
      in = !in;
    }
    if (in != static_cast<bool>(v.inside[v.s->edges[e][1]]))
      throw std::logic_error("surface_overlap: an edge's crossings disagree with its ends");
    first = end;
  }
}

}  // namespace gjkdem::surface_overlap_detail
