#pragma once
// The parts of surface_overlap (surface_overlap.cpp) that other files of it
// share: a surface's edges crossing the other's triangles, decided exactly
// in the perturbation (shape/predicates.hpp), and the status of its
// vertices (surface_status.cpp); edges where the two solids pinch
// (surface_pinch.cpp). Private to src/contact.
#include <array>
#include <cstdint>
#include <vector>

#include "gjkdem/shape/predicates.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem::surface_overlap_detail {

// An edge of one surface passing through a triangle of the other.
struct Crossing {
  std::uint32_t edge, triangle;
  Real t;      // along the edge from its lower vertex to its higher
  Vec3 point;  // relative to the overlap's reference point
  bool exits;  // the edge, run from lower to higher vertex, leaves the other solid here
};

// One surface seen against the other solid: its side in the perturbation,
// the crossings of its edges, the status of its vertices. Only the
// triangles whose boxes meet the solid's box ("near") can be cut or lie
// inside: the passes over the surface visit those alone, so that a shallow
// overlap of big surfaces costs what the overlap does.
struct View {
  const Surface* s = nullptr;
  Side side = Side::A;
  std::vector<Crossing> crossings;  // sorted by edge, then t
  // Per edge, its crossings: crossings[edge_crossings[e][0] .. edge_crossings[e][1]).
  std::vector<std::array<std::uint32_t, 2>> edge_crossings;
  std::vector<std::int8_t> inside;             // per vertex: 1 inside the other solid, 0 outside
  std::vector<std::uint32_t> in_plane;         // edges lying in the plane of a triangle of the other surface
  std::vector<std::uint32_t> near;             // triangles whose boxes meet the solid's box
  std::vector<std::uint32_t> near_vertices;    // their corners within the solid's box
  std::vector<std::uint32_t> queue, hits;      // find_status's

  // The per-edge and per-vertex arrays are kept all clear between calls,
  // cleared where the last call wrote them (its crossings' edges, its
  // vertices in the box): a shallow overlap of big surfaces touches few.
  void reset(const Surface& surface, Side which) {
    for (const Crossing& c : crossings) edge_crossings[c.edge] = {0, 0};
    for (const std::uint32_t i : near_vertices) inside[i] = 0;
    crossings.clear();
    near_vertices.clear();
    in_plane.clear();
    s = &surface;
    side = which;
    if (edge_crossings.size() < surface.edges.size()) edge_crossings.resize(surface.edges.size(), {0, 0});
    if (inside.size() < surface.vertices.size()) inside.resize(surface.vertices.size(), 0);
  }
  std::uint32_t crossings_along(std::uint32_t e) const { return edge_crossings[e][1] - edge_crossings[e][0]; }
};

inline Side other(Side s) { return s == Side::A ? Side::B : Side::A; }

// Line pq (an edge of surface `pq_side`, its ends on either side of the
// plane abc of the other's triangle) passes through the triangle.
inline bool passes_through(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Side pq_side) {
  const int o1 = perturbed_orient3d_edges(p, q, a, b, pq_side);
  return perturbed_orient3d_edges(p, q, b, c, pq_side) == o1 && perturbed_orient3d_edges(p, q, c, a, pq_side) == o1;
}

// Segment pq of surface `pq_side` through triangle abc of the other.
inline bool crosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Side pq_side) {
  const Side abc = other(pq_side);
  return perturbed_orient3d(a, b, c, p, abc) != perturbed_orient3d(a, b, c, q, abc) &&
         passes_through(p, q, a, b, c, pq_side);
}

// The crossings sorted along each edge, and each edge's.
void index_crossings(View& v);

// The near triangles and every vertex's status, inside or outside `solid`
// (the vertices beyond the solid's box outside, without a look).
void find_status(View& v, const Surface& solid);

// Crossings at one point along an edge put in the order the statuses imply.
void order_crossings(View& v);

// Edge e of s lies along an edge of `solid`'s where the two solids' wedges
// pinch (A ∩ B is two pieces touching along the line there).
bool pinched(const Surface& s, std::uint32_t e, const Surface& solid, std::vector<std::uint32_t>& near);

}  // namespace gjkdem::surface_overlap_detail
