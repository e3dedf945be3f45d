#include "gjkdem/contact/surface_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "gjkdem/shape/predicates.hpp"

namespace gjkdem {
namespace {

// An edge of one surface passing through a triangle of the other.
struct Crossing {
  std::uint32_t edge, triangle;
  Real t;      // along the edge from its lower vertex to its higher
  Vec3 point;  // relative to the overlap's reference point
  bool exits;  // the edge, run from lower to higher vertex, leaves the other solid here
};

// One surface seen against the other solid: its side in the perturbation,
// the crossings of its edges, the status of its vertices.
struct View {
  const Surface& s;
  Side side;
  std::vector<Crossing> crossings;           // sorted by edge, then t
  std::vector<std::uint32_t> first_crossing;  // per edge, into crossings (size edges + 1)
  std::vector<std::int8_t> inside;           // per vertex: 1 inside the other solid, 0 outside
};

Side other(Side s) { return s == Side::A ? Side::B : Side::A; }

// Edge pq of surface `pq_side` through triangle abc of the other: whether
// it crosses and, if so, whether it goes from inside to outside.
bool crosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Side pq_side, bool& exits) {
  const Side abc = other(pq_side);
  const int sp = perturbed_orient3d(a, b, c, p, abc), sq = perturbed_orient3d(a, b, c, q, abc);
  if (sp == sq) return false;
  const int o1 = perturbed_orient3d_edges(p, q, a, b, pq_side);
  const int o2 = perturbed_orient3d_edges(p, q, b, c, pq_side);
  const int o3 = perturbed_orient3d_edges(p, q, c, a, pq_side);
  if (o1 != o2 || o2 != o3) return false;
  exits = sp < 0;
  return true;
}

// Crossings of v's edges through the triangles of `solid` listed per pair.
void find_crossings(View& v, const Surface& solid, std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                    const Vec3& origin) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const auto& [e, t] : pairs) {
    const Vec3& p = v.s.vertices[v.s.edges[e][0]];
    const Vec3& q = v.s.vertices[v.s.edges[e][1]];
    const TriangleIndices& tri = solid.triangles[t];
    const Vec3 &a = solid.vertices[tri[0]], &b = solid.vertices[tri[1]], &c = solid.vertices[tri[2]];
    bool exits = false;
    if (!crosses(p, q, a, b, c, v.side, exits)) continue;
    const Vec3 n = cross(b - a, c - a);
    const Real dp = dot(n, p - a), dq = dot(n, q - a);
    const Real t_on = dp == dq ? Real(0.5) : std::clamp(dp / (dp - dq), Real(0), Real(1));
    const Vec3 po = p - origin, qo = q - origin;
    v.crossings.push_back({e, t, t_on, po + t_on * (qo - po), exits});
  }
  std::sort(v.crossings.begin(), v.crossings.end(),
            [](const Crossing& x, const Crossing& y) { return x.edge < y.edge || (x.edge == y.edge && x.t < y.t); });
  v.first_crossing.assign(v.s.edges.size() + 1, 0);
  for (const Crossing& c : v.crossings) ++v.first_crossing[c.edge + 1];
  for (std::size_t e = 0; e < v.s.edges.size(); ++e) v.first_crossing[e + 1] += v.first_crossing[e];
}

// Whether vertex x of v's surface lies inside `solid`: the parity of the
// crossings of a segment from x to a point beyond the solid's box.
bool inside_by_ray(const View& v, std::uint32_t x, const Surface& solid) {
  const Vec3& p = v.s.vertices[x];
  const Vec3 far{solid.box.hi.x + std::fabs(solid.box.hi.x) + 1, p.y, p.z};
  std::vector<std::uint32_t> hits;
  query_triangle_tree(solid.tree, Aabb{p, far}, hits);
  int count = 0;
  for (const std::uint32_t t : hits) {
    const TriangleIndices& tri = solid.triangles[t];
    bool exits = false;
    count += crosses(p, far, solid.vertices[tri[0]], solid.vertices[tri[1]], solid.vertices[tri[2]], v.side, exits);
  }
  return count % 2 == 1;
}

// Every vertex's status: outside where it lies beyond the solid's box,
// carried along the edges (a crossing flips it), a ray where nothing reaches.
void find_status(View& v, const Surface& solid) {
  const Surface& s = v.s;
  v.inside.assign(s.vertices.size(), -1);
  std::vector<std::uint32_t> queue;
  for (std::uint32_t i = 0; i < s.vertices.size(); ++i) {
    const Vec3& p = s.vertices[i];
    if (p.x < solid.box.lo.x || p.y < solid.box.lo.y || p.z < solid.box.lo.z || p.x > solid.box.hi.x ||
        p.y > solid.box.hi.y || p.z > solid.box.hi.z)
      v.inside[i] = 0, queue.push_back(i);
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
  for (std::size_t e = 0; e < v.s.edges.size(); ++e) {
    bool in = v.inside[v.s.edges[e][0]];
    for (std::uint32_t c = v.first_crossing[e]; c < v.first_crossing[e + 1]; ++c) {
      if (v.crossings[c].exits != in) {
        std::uint32_t d = c + 1;  // the next crossing that fits
        while (d < v.first_crossing[e + 1] && v.crossings[d].exits != in) ++d;
        if (d == v.first_crossing[e + 1]) throw std::logic_error("surface_overlap: crossings out of step along an edge");
        std::swap(v.crossings[c], v.crossings[d]);
      }
      in = !in;
    }
    if (in != static_cast<bool>(v.inside[v.s.edges[e][1]]))
      throw std::logic_error("surface_overlap: an edge's crossings disagree with its ends");
  }
}

// The integrals of A ∩ B, summed over the segments of the cycles.
struct Sums {
  Real volume6 = 0;  // six times the volume
  Vec3 moment24;     // 24 times the first moment
  Vec3 area_a, area_b;
  void add(const Vec3& apex, const Vec3& p, const Vec3& q, Vec3& area) {
    const Real v6 = dot(apex, cross(p, q));
    volume6 += v6;
    moment24 += v6 * (apex + p + q);
    area += 0.5 * cross(p - apex, q - apex);
  }
};

// The area of the overlap of two triangles on one plane (abc's, whose
// normal is n), by clipping abc with def's three sides.
Real coplanar_overlap_area(const Vec3 (&abc)[3], const Vec3 (&def)[3], const Vec3& n) {
  std::vector<Vec3> poly(abc, abc + 3), next;
  const Vec3 m = cross(def[1] - def[0], def[2] - def[0]);  // def's own normal: its corners run ccw about it
  for (int k = 0; k < 3 && !poly.empty(); ++k) {
    const Vec3 inward = cross(m, def[(k + 1) % 3] - def[k]);
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec3 &p = poly[i], &q = poly[(i + 1) % poly.size()];
      const Real dp = dot(inward, p - def[k]), dq = dot(inward, q - def[k]);
      if (dp >= 0) next.push_back(p);
      if ((dp >= 0) != (dq >= 0)) next.push_back(p + (dp / (dp - dq)) * (q - p));
    }
    poly.swap(next);
  }
  Vec3 area;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) area += cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
  return 0.5 * std::fabs(dot(area, n)) / length(n);
}

// A segment of a triangle's cycle, and where it ends on a crossing.
struct Endpoint {
  Vec3 point;
  bool start;  // in the cycle of the first surface's triangle (A's)
};

}  // namespace

SurfaceOverlap surface_overlap(const Surface& a, const Surface& b) {
  SurfaceOverlap out;
  if (!overlaps(a.box, b.box)) return out;
  const Vec3 origin = 0.5 * (max(a.box.lo, b.box.lo) + min(a.box.hi, b.box.hi));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs, edges_a, edges_b;
  overlapping_triangles(a.tree, b.tree, [&](std::uint32_t s, std::uint32_t t) {
    pairs.emplace_back(s, t);
    for (const std::uint32_t e : a.triangle_edges[s]) edges_a.emplace_back(e, t);
    for (const std::uint32_t e : b.triangle_edges[t]) edges_b.emplace_back(e, s);
  });
  // Touching counts as intersecting: decided on the closed triangles, unmoved.
  for (const auto& [s, t] : pairs) {
    const TriangleIndices &ts = a.triangles[s], &tt = b.triangles[t];
    if (triangles_meet(a.vertices[ts[0]], a.vertices[ts[1]], a.vertices[ts[2]], b.vertices[tt[0]], b.vertices[tt[1]],
                       b.vertices[tt[2]])) {
      out.intersect = true;
      break;
    }
  }
  View va{a, Side::A, {}, {}, {}}, vb{b, Side::B, {}, {}, {}};
  find_crossings(va, b, edges_a, origin);
  find_crossings(vb, a, edges_b, origin);
  find_status(va, b);
  find_status(vb, a);
  order_crossings(va);
  order_crossings(vb);

  // The crossing segments of each pair of triangles that cross, oriented for
  // A's triangle's cycle (B's runs it the other way).
  std::unordered_map<std::uint64_t, std::vector<Endpoint>> segments;
  const auto key = [](std::uint32_t s, std::uint32_t t) { return (std::uint64_t{s} << 32) | t; };
  for (const Crossing& c : va.crossings)
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t s = a.edge_triangles[c.edge][k];  // runs the edge forward for k = 0
      const bool exits = c.exits != (k == 1);
      segments[key(s, c.triangle)].push_back({c.point, exits});
    }
  for (const Crossing& c : vb.crossings)
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t t = b.edge_triangles[c.edge][k];
      const bool exits = c.exits != (k == 1);  // in t's cycle: an exit starts the segment
      segments[key(c.triangle, t)].push_back({c.point, !exits});
    }

  Sums sums;
  std::vector<std::vector<std::pair<Vec3, Vec3>>> cross_a(a.triangles.size()), cross_b(b.triangles.size());
  for (const auto& [k, ends] : segments) {
    if (ends.size() != 2 || ends[0].start == ends[1].start)
      throw std::logic_error("surface_overlap: a crossing segment without one start and one end");
    const Vec3 &p = ends[0].start ? ends[0].point : ends[1].point, &q = ends[0].start ? ends[1].point : ends[0].point;
    cross_a[k >> 32].push_back({p, q});
    cross_b[k & 0xffffffffu].push_back({q, p});
  }

  // Each triangle's cycle: its edges' pieces inside the other solid, then its
  // crossing segments; fans from its first corner.
  const auto cycles = [&](const View& v, const std::vector<std::vector<std::pair<Vec3, Vec3>>>& crossing, Vec3& area) {
    const Surface& s = v.s;
    for (std::uint32_t t = 0; t < s.triangles.size(); ++t) {
      const TriangleIndices& tri = s.triangles[t];
      bool any = !crossing[t].empty() || v.inside[tri[0]] || v.inside[tri[1]] || v.inside[tri[2]];
      if (!any) continue;
      const Vec3 apex = s.vertices[tri[0]] - origin;
      for (const auto& [p, q] : crossing[t]) sums.add(apex, p, q, area);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t e = s.triangle_edges[t][k];
        const bool forward = s.edge_triangles[e][0] == t;
        const Vec3 lo = s.vertices[s.edges[e][0]] - origin, hi = s.vertices[s.edges[e][1]] - origin;
        bool in = v.inside[s.edges[e][0]];
        Vec3 from = lo;
        for (std::uint32_t c = v.first_crossing[e]; c < v.first_crossing[e + 1]; ++c) {
          const Crossing& x = v.crossings[c];
          if (in && x.exits) forward ? sums.add(apex, from, x.point, area) : sums.add(apex, x.point, from, area);
          in = !x.exits;
          from = x.point;
        }
        if (in) forward ? sums.add(apex, from, hi, area) : sums.add(apex, hi, from, area);
      }
    }
  };
  cycles(va, cross_a, sums.area_a);
  cycles(vb, cross_b, sums.area_b);

  // Coplanar faces: the perturbation put the one or both of them inside the
  // other solid and their cycles counted them, but they bound no volume
  // (facing each other) or lie on both surfaces (facing the same way): the
  // areas count neither (query-format-mesh.md).
  for (const auto& [s, t] : pairs) {
    const TriangleIndices &ts = a.triangles[s], &tt = b.triangles[t];
    const Vec3 pa[3] = {a.vertices[ts[0]] - origin, a.vertices[ts[1]] - origin, a.vertices[ts[2]] - origin};
    const Vec3 pb[3] = {b.vertices[tt[0]] - origin, b.vertices[tt[1]] - origin, b.vertices[tt[2]] - origin};
    const Vec3 na = cross(pa[1] - pa[0], pa[2] - pa[0]), nb = cross(pb[1] - pb[0], pb[2] - pb[0]);
    if (length(cross(na, nb)) > 1e-6 * length(na) * length(nb)) continue;  // far from parallel: never coplanar
    const Vec3 &a0 = a.vertices[ts[0]], &a1 = a.vertices[ts[1]], &a2 = a.vertices[ts[2]];
    const Vec3 &b0 = b.vertices[tt[0]], &b1 = b.vertices[tt[1]], &b2 = b.vertices[tt[2]];
    if (orient3d(a0, a1, a2, b0) || orient3d(a0, a1, a2, b1) || orient3d(a0, a1, a2, b2)) continue;
    const Real area = coplanar_overlap_area(pa, pb, na);
    if (area == 0) continue;
    if (perturbed_orient3d(b0, b1, b2, a0, Side::B) < 0) sums.area_a -= area / length(na) * na;  // a's face inside B
    if (perturbed_orient3d(a0, a1, a2, b0, Side::A) < 0) sums.area_b -= area / length(nb) * nb;  // b's face inside A
  }

  out.volume = sums.volume6 / 6;
  out.area_a = sums.area_a;
  out.area_b = sums.area_b;
  if (out.volume > 0) {
    out.centroid = origin + sums.moment24 / (24 * out.volume);
    out.intersect = true;
  } else {
    out.volume = 0;
  }
  return out;
}

}  // namespace gjkdem
