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

// The crossings sorted along each edge, and where each edge's begin.
void index_crossings(View& v) {
  std::sort(v.crossings.begin(), v.crossings.end(),
            [](const Crossing& x, const Crossing& y) { return x.edge < y.edge || (x.edge == y.edge && x.t < y.t); });
  v.first_crossing.assign(v.s->edges.size() + 1, 0);
  for (const Crossing& c : v.crossings) ++v.first_crossing[c.edge + 1];
  for (std::size_t e = 0; e < v.s->edges.size(); ++e) v.first_crossing[e + 1] += v.first_crossing[e];
}

// Every vertex's status: outside where it lies beyond the solid's box,
// carried along the edges (a crossing flips it) from there into the box, a
// ray where nothing reaches. The walk starts at the box's edge, so its cost
// follows the vertices inside the box, not the whole surface.
void find_status(View& v, const Surface& solid) {
  const Surface& s = *v.s;
  v.inside.assign(s.vertices.size(), -1);
  std::vector<std::uint32_t>& queue = v.queue;
  queue.clear();
  for (std::uint32_t i = 0; i < s.vertices.size(); ++i) {
    const Vec3& p = s.vertices[i];
    if (p.x < solid.box.lo.x || p.y < solid.box.lo.y || p.z < solid.box.lo.z || p.x > solid.box.hi.x ||
        p.y > solid.box.hi.y || p.z > solid.box.hi.z)
      v.inside[i] = 0;
  }
  for (std::uint32_t i = 0; i < s.vertices.size(); ++i) {  // the box's edge: where the walk starts
    if (v.inside[i] >= 0) continue;
    for (std::uint32_t k = s.vertex_edge_begin[i]; k < s.vertex_edge_begin[i + 1]; ++k) {
      const std::uint32_t e = s.vertex_edges[k];
      const std::uint32_t j = s.edges[e][0] == i ? s.edges[e][1] : s.edges[e][0];
      if (v.inside[j] < 0) continue;
      v.inside[i] = static_cast<std::int8_t>(v.inside[j] ^ ((v.first_crossing[e + 1] - v.first_crossing[e]) & 1));
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
        const std::uint32_t flips = v.first_crossing[e + 1] - v.first_crossing[e];
        v.inside[j] = static_cast<std::int8_t>(v.inside[i] ^ (flips & 1));
        queue.push_back(j);
      }
    }
  };
  spread();
  for (std::uint32_t i = 0; i < s.vertices.size(); ++i)
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
  for (std::size_t e = 0; e < v.s->edges.size(); ++e) {
    bool in = v.inside[v.s->edges[e][0]];
    for (std::uint32_t c = v.first_crossing[e]; c < v.first_crossing[e + 1]; ++c) {
      if (v.crossings[c].exits != in) {
        std::uint32_t d = c + 1;  // the next crossing that fits
        while (d < v.first_crossing[e + 1] && v.crossings[d].exits != in) ++d;
        if (d == v.first_crossing[e + 1]) throw std::logic_error("surface_overlap: crossings out of step along an edge");
        std::swap(v.crossings[c], v.crossings[d]);
      }
      in = !in;
    }
    if (in != static_cast<bool>(v.inside[v.s->edges[e][1]]))
      throw std::logic_error("surface_overlap: an edge's crossings disagree with its ends");
  }
}

}  // namespace gjkdem::surface_overlap_detail
