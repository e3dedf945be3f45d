#include "gjkdem/math/union_find.hpp"
#include "gjkdem/contact/surface_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <tuple>
#include <stdexcept>
#include <vector>

#include "gjkdem/math/polygon_clip.hpp"
#include "gjkdem/shape/predicates.hpp"
#include "gjkdem/tolerances.hpp"
#include "surface_overlap_detail.hpp"

namespace gjkdem {
namespace surface_overlap_detail {

// Edge pq of v's surface (its lower vertex p, on side `sp` of the plane of
// triangle t = abc of the other surface, q on the other side) through that
// triangle, if it passes through it.
void add_crossing(View& v, std::uint32_t e, std::uint32_t t, const Vec3& p, const Vec3& q, int sp, const Vec3& a,
                  const Vec3& b, const Vec3& c, const Vec3& origin) {
  if (!passes_through(p, q, a, b, c, v.side)) return;
  const Vec3 n = cross(b - a, c - a);
  const Real dp = dot(n, p - a), dq = dot(n, q - a);
  const Real t_on = dp == dq ? Real(0.5) : std::clamp(dp / (dp - dq), Real(0), Real(1));
  const Vec3 po = p - origin, qo = q - origin;
  v.crossings.push_back({e, t, t_on, po + t_on * (qo - po), sp < 0});
}

// The edges of triangle s of v's surface through triangle t of `solid`,
// from the sides of the plane of t its corners lie on (`sides`); each edge
// is taken by the triangle that runs it forward only, as its other triangle
// meets the same triangles.
void edges_through(View& v, std::uint32_t s, const int (&sides)[3], const Surface& solid, std::uint32_t t,
                   const Vec3& origin) {
  if (sides[0] == sides[1] && sides[1] == sides[2]) return;
  const TriangleIndices& corners = v.s->triangles[s];
  const TriangleIndices& tri = solid.triangles[t];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t e = v.s->triangle_edges[s][k];
    if (v.s->edge_triangles[e][0] != s || sides[k] == sides[(k + 1) % 3]) continue;
    add_crossing(v, e, t, v.s->vertices[corners[k]], v.s->vertices[corners[(k + 1) % 3]], sides[k],
                 solid.vertices[tri[0]], solid.vertices[tri[1]], solid.vertices[tri[2]], origin);
  }
}

// A segment of a triangle's cycle: from point to point (ids: the surfaces'
// vertices, then their crossings), with what it adds to the integrals.
struct CycleSegment {
  std::uint32_t triangle;  // A's triangles, then B's
  std::uint32_t from, to;
  Vec3 p, q;
};

// What a set of cycle segments adds up to.
struct Sums {
  Real volume6 = 0;  // six times the volume
  Vec3 moment24;     // 24 times the first moment
  Vec3 area_a, area_b;
  Vec3 area_moment_a;  // first moment of area_a: sum of (fan centroid) x (fan's vector area)
};

// Whether point x lies inside the closed polygon of the loop's segments,
// seen down `axis` (crossings of a ray along the first remaining axis).
bool loop_holds(const std::vector<CycleSegment>& segments, std::span<const std::uint32_t> loop, const Vec3& x,
                int axis) {
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  bool in = false;
  for (const std::uint32_t g : loop) {
    const Vec3 &p = segments[g].p, &q = segments[g].q;
    if ((p[j] > x[j]) != (q[j] > x[j]) && x[i] < p[i] + (x[j] - p[j]) / (q[j] - p[j]) * (q[i] - p[i])) in = !in;
  }
  return in;
}

int dominant_axis(const Vec3& n) {
  const Vec3 m{std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
  return m.x >= m.y && m.x >= m.z ? 0 : m.y >= m.z ? 1 : 2;
}

// The area of the overlap of two triangles on one plane (abc's, whose
// normal is n), by clipping abc with def's three sides, and its centroid.
Real coplanar_overlap_area(const Vec3 (&abc)[3], const Vec3 (&def)[3], const Vec3& n, Vec3& inside) {
  std::vector<Vec3> poly(abc, abc + 3), next;
  const Vec3 m = cross(def[1] - def[0], def[2] - def[0]);  // def's own normal: its corners run ccw about it
  for (int k = 0; k < 3 && !poly.empty(); ++k) {
    const Vec3 inward = cross(m, def[(k + 1) % 3] - def[k]);
    clip_polygon(poly, [&](const Vec3& p) { return -dot(inward, p - def[k]); }, next);  // (negated exactly)
    poly.swap(next);
  }
  Vec3 area, weighted;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    const Vec3 fan = cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
    area += fan;
    weighted += dot(fan, n) * (poly[0] + poly[i] + poly[i + 1]);
  }
  const Real twice = dot(area, n);
  inside = poly.empty() ? Vec3{} : twice != 0 ? weighted / (3 * twice) : poly[0];
  return 0.5 * std::fabs(twice) / length(n);
}

// An end of a crossing segment: a crossing, where A's triangle's cycle
// starts or ends it.
struct Endpoint {
  std::uint32_t id;
  bool start;
};


}  // namespace surface_overlap_detail

using namespace surface_overlap_detail;

struct SurfaceOverlapWorkspace::Scratch {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs, coplanar, links, same_point;
  View va, vb;
  std::vector<std::pair<std::uint64_t, Endpoint>> crossing_ends;
  std::vector<CycleSegment> segments;
  UnionFind joined;
  std::vector<std::uint32_t> near, order, loop_members, loop_begin, loop_segment, lobe;
  std::vector<Real> loop_area;
  std::vector<std::uint8_t> seen, cut;  // cut: per triangle (A's, then B's), set for those in cut_list
  std::vector<std::uint32_t> cut_list;
  std::vector<std::uint32_t> whole;       // per triangle: its number when wholly inside, else kNoNode
  std::vector<std::uint32_t> whole_list;  // the whole triangles inside, by number
  std::vector<Sums> pieces;
};

SurfaceOverlapWorkspace::SurfaceOverlapWorkspace() : scratch(std::make_unique<Scratch>()) {}
SurfaceOverlapWorkspace::~SurfaceOverlapWorkspace() = default;
SurfaceOverlapWorkspace::SurfaceOverlapWorkspace(const SurfaceOverlapWorkspace&)
    : scratch(std::make_unique<Scratch>()) {}
SurfaceOverlapWorkspace& SurfaceOverlapWorkspace::operator=(const SurfaceOverlapWorkspace&) { return *this; }
SurfaceOverlapWorkspace::SurfaceOverlapWorkspace(SurfaceOverlapWorkspace&&) noexcept = default;
SurfaceOverlapWorkspace& SurfaceOverlapWorkspace::operator=(SurfaceOverlapWorkspace&&) noexcept = default;

SurfaceOverlap posed_surface_overlap(const std::shared_ptr<const Surface>& a, const Transform& pose_a,
                                     const std::shared_ptr<const Surface>& b, const Transform& pose_b,
                                     PosedSurfaceScratch& s, Transform& frame) {
  const bool move_a = a->vertices.size() < b->vertices.size();
  frame = move_a ? pose_b : pose_a;
  const std::shared_ptr<const Surface>& mover = move_a ? a : b;
  const Transform pose = move_a ? relative(pose_b, pose_a) : relative(pose_a, pose_b);
  if (s.moved_from == mover) {
    repose(*mover, pose, s.moved);  // the same surface as last time: its topology is there
  } else {
    move_into(*mover, pose, s.moved);
    s.moved_from = mover;
  }
  return move_a ? surface_overlap(s.moved, *b, s.overlap) : surface_overlap(*a, s.moved, s.overlap);
}

SurfaceOverlap surface_overlap(const Surface& a, const Surface& b) {
  SurfaceOverlapWorkspace work;
  return surface_overlap(a, b, work);
}

SurfaceOverlap surface_overlap(const Surface& a, const Surface& b, SurfaceOverlapWorkspace& work) {
  SurfaceOverlap out;
  if (!overlaps(a.box, b.box)) return out;
  SurfaceOverlapWorkspace::Scratch& w = *work.scratch;
  const Vec3 origin = 0.5 * (max(a.box.lo, b.box.lo) + min(a.box.hi, b.box.hi));
  // Triangle pairs whose own boxes meet, and the edges of each through the
  // other, from the sides of the other's plane their corners lie on.
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs = w.pairs;
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& coplanar = w.coplanar;
  pairs.clear(), coplanar.clear();
  View& va = w.va;
  View& vb = w.vb;
  va.reset(a, Side::A), vb.reset(b, Side::B);
  overlapping_items(a.tree, b.tree, [&](std::uint32_t s, std::uint32_t t) {
    pairs.emplace_back(s, t);
    const TriangleIndices &ts = a.triangles[s], &tt = b.triangles[t];
    const Vec3 &a0 = a.vertices[ts[0]], &a1 = a.vertices[ts[1]], &a2 = a.vertices[ts[2]];
    const Vec3 &b0 = b.vertices[tt[0]], &b1 = b.vertices[tt[1]], &b2 = b.vertices[tt[2]];
    bool on_a[3], on_b[3];  // corners on the other's plane exactly: edges there may lie along the other's edges
    int sides_a[3], sides_b[3];
    perturbed_orient3d_three(b0, b1, b2, {a0, a1, a2}, Side::B, sides_a, on_a);
    for (int k = 0; k < 3; ++k)
      if (on_a[k] && on_a[(k + 1) % 3]) {  // an edge of s in t's plane: t's edges may lie along it
        va.in_plane.push_back(a.triangle_edges[s][k]);
        vb.in_plane.insert(vb.in_plane.end(), b.triangle_edges[t].begin(), b.triangle_edges[t].end());
      }
    if (on_a[0] && on_a[1] && on_a[2]) coplanar.emplace_back(s, t);
    if (sides_a[0] == sides_a[1] && sides_a[1] == sides_a[2]) return;  // s wholly on one side of t's plane
    perturbed_orient3d_three(a0, a1, a2, {b0, b1, b2}, Side::A, sides_b, on_b);
    for (int k = 0; k < 3; ++k)
      if (on_b[k] && on_b[(k + 1) % 3]) vb.in_plane.push_back(b.triangle_edges[t][k]);
    if (sides_b[0] == sides_b[1] && sides_b[1] == sides_b[2]) return;  // t wholly on one side of s's plane
    edges_through(va, s, sides_a, b, t, origin);
    edges_through(vb, t, sides_b, a, s, origin);
  });
  index_crossings(va);
  index_crossings(vb);
  for (View* v : {&va, &vb}) {
    std::sort(v->in_plane.begin(), v->in_plane.end());
    v->in_plane.erase(std::unique(v->in_plane.begin(), v->in_plane.end()), v->in_plane.end());
  }
  find_status(va, b);
  find_status(vb, a);
  order_crossings(va);
  order_crossings(vb);

  // Point ids: A's vertices, B's, A's crossings, B's.
  const std::uint32_t base_b = static_cast<std::uint32_t>(a.vertices.size());
  const std::uint32_t base_ca = base_b + static_cast<std::uint32_t>(b.vertices.size());
  const std::uint32_t base_cb = base_ca + static_cast<std::uint32_t>(va.crossings.size());
  const std::uint32_t triangles_a = static_cast<std::uint32_t>(a.triangles.size());
  const auto point_of = [&](std::uint32_t id) {
    if (id < base_b) return a.vertices[id] - origin;
    if (id < base_ca) return b.vertices[id - base_b] - origin;
    if (id < base_cb) return va.crossings[id - base_ca].point;
    return vb.crossings[id - base_cb].point;
  };

  // The crossing segments of each pair of triangles that cross, oriented for
  // A's triangle's cycle (B's runs it the other way).
  std::vector<std::pair<std::uint64_t, Endpoint>>& crossing_ends = w.crossing_ends;  // by pair of triangles
  crossing_ends.clear();
  const auto key = [](std::uint32_t s, std::uint32_t t) { return (std::uint64_t{s} << 32) | t; };
  for (std::uint32_t k = 0; k < va.crossings.size(); ++k)
    for (int side = 0; side < 2; ++side) {
      const Crossing& c = va.crossings[k];
      const std::uint32_t s = a.edge_triangles[c.edge][side];  // runs the edge forward for side 0
      crossing_ends.push_back({key(s, c.triangle), {base_ca + k, c.exits != (side == 1)}});
    }
  for (std::uint32_t k = 0; k < vb.crossings.size(); ++k)
    for (int side = 0; side < 2; ++side) {
      const Crossing& c = vb.crossings[k];
      const std::uint32_t t = b.edge_triangles[c.edge][side];
      const bool exits = c.exits != (side == 1);  // in t's cycle: an exit starts the segment
      crossing_ends.push_back({key(c.triangle, t), {base_cb + k, !exits}});
    }

  // Triangles that need a cycle ("cut"): an edge of theirs crosses the other
  // surface, an edge of the other's crosses them, or they touch the other's
  // plane exactly. Any other triangle lies wholly inside or wholly outside
  // (its corners' status says which) and counts whole, with no segments: in
  // a deep overlap most triangles are whole.
  // The per-triangle marks are kept all clear between calls, cleared where
  // the last call set them: a shallow overlap of big surfaces touches few.
  std::vector<std::uint8_t>& cut = w.cut;
  std::vector<std::uint32_t>& cut_list = w.cut_list;
  for (const std::uint32_t t : cut_list) cut[t] = 0;
  cut_list.clear();
  const std::size_t triangles = triangles_a + b.triangles.size();
  if (cut.size() < triangles) cut.resize(triangles, 0);
  const auto mark = [&](std::uint32_t t) {
    if (!cut[t]) cut[t] = 1, cut_list.push_back(t);
  };
  for (const Crossing& c : va.crossings)
    mark(a.edge_triangles[c.edge][0]), mark(a.edge_triangles[c.edge][1]), mark(triangles_a + c.triangle);
  for (const Crossing& c : vb.crossings)
    mark(triangles_a + b.edge_triangles[c.edge][0]), mark(triangles_a + b.edge_triangles[c.edge][1]), mark(c.triangle);
  for (const std::uint32_t e : va.in_plane) mark(a.edge_triangles[e][0]), mark(a.edge_triangles[e][1]);
  for (const std::uint32_t e : vb.in_plane) mark(triangles_a + b.edge_triangles[e][0]), mark(triangles_a + b.edge_triangles[e][1]);
  for (const auto& [s, t] : coplanar) mark(s), mark(triangles_a + t);
  // Whole triangles inside the other solid, numbered.
  constexpr std::uint32_t kNoNode = ~std::uint32_t{0};
  std::vector<std::uint32_t>& whole = w.whole;
  std::vector<std::uint32_t>& whole_list = w.whole_list;  // by number
  for (const std::uint32_t t : whole_list) whole[t] = kNoNode;
  whole_list.clear();
  if (whole.size() < triangles) whole.resize(triangles, kNoNode);
  for (const std::uint32_t t : va.near)
    if (!cut[t] && va.inside[a.triangles[t][0]]) whole[t] = static_cast<std::uint32_t>(whole_list.size()), whole_list.push_back(t);
  for (const std::uint32_t t : vb.near)
    if (!cut[triangles_a + t] && vb.inside[b.triangles[t][0]])
      whole[triangles_a + t] = static_cast<std::uint32_t>(whole_list.size()), whole_list.push_back(triangles_a + t);

  std::vector<CycleSegment>& segments = w.segments;
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& links = w.links;  // one boundary segment of two faces
  UnionFind& joined = w.joined;
  segments.clear(), links.clear(), joined.parent.clear();
  const auto add = [&](std::uint32_t triangle, std::uint32_t from, std::uint32_t to) {
    segments.push_back({triangle, from, to, point_of(from), point_of(to)});
    joined.add();
    return static_cast<std::uint32_t>(segments.size() - 1);
  };
  // A crossing segment bounds a face of A and a face of B: one piece.
  std::sort(crossing_ends.begin(), crossing_ends.end(),
            [](const auto& x, const auto& y) { return x.first < y.first || (x.first == y.first && x.second.id < y.second.id); });
  for (std::size_t i = 0; i < crossing_ends.size(); i += 2) {
    const std::uint64_t k = crossing_ends[i].first;
    if (i + 1 == crossing_ends.size() || crossing_ends[i + 1].first != k || (i + 2 < crossing_ends.size() && crossing_ends[i + 2].first == k) ||
        crossing_ends[i].second.start == crossing_ends[i + 1].second.start)
      throw std::logic_error("surface_overlap: a crossing segment without one start and one end");
    const Endpoint ends[2] = {crossing_ends[i].second, crossing_ends[i + 1].second};
    const std::uint32_t p = ends[0].start ? ends[0].id : ends[1].id, q = ends[0].start ? ends[1].id : ends[0].id;
    links.emplace_back(add(static_cast<std::uint32_t>(k >> 32), p, q), add(triangles_a + static_cast<std::uint32_t>(k), q, p));
  }
  // An edge's pieces inside the other solid bound both its triangles' faces.
  // Where the edge lies along an edge of the other surface and the two
  // solids' wedges there pinch (two pieces touching along the line), its
  // pieces do not join its faces. A whole triangle takes no segment: the
  // edge (then wholly inside) joins it to its neighbour's face. Links to a
  // whole triangle's node are tagged (kWholeTag | its number) until the
  // nodes exist.
  constexpr std::uint32_t kWholeTag = std::uint32_t{1} << 31;
  std::vector<std::uint32_t>& pinch_near = w.near;  // pinched's scratch
  const auto edge_pieces = [&](const View& v, const Surface& solid, std::uint32_t base_v, std::uint32_t base_c,
                               std::uint32_t base_t) {
    const Surface& s = *v.s;
    // An edge inside or crossed has both its triangles near: each such edge
    // is met once, from the triangle that runs it forward.
    for (const std::uint32_t near_triangle : v.near)
      for (const std::uint32_t e : s.triangle_edges[near_triangle]) {
        if (s.edge_triangles[e][0] != near_triangle) continue;
        const std::uint32_t forward = base_t + s.edge_triangles[e][0], backward = base_t + s.edge_triangles[e][1];
        bool in = v.inside[s.edges[e][0]];
        if (!cut[forward] || !cut[backward]) {  // no crossings along e: wholly inside or outside
          if (in != static_cast<bool>(v.inside[s.edges[e][1]]))
            throw std::logic_error("surface_overlap: an edge without crossings has ends inside and outside");
          if (!in) continue;
          const std::uint32_t from = base_v + s.edges[e][0], to = base_v + s.edges[e][1];
          const std::uint32_t g = cut[forward] ? add(forward, from, to) : kWholeTag | whole[forward];
          const std::uint32_t h = cut[backward] ? add(backward, to, from) : kWholeTag | whole[backward];
          links.emplace_back(g, h);
          continue;
        }
        std::uint32_t from = base_v + s.edges[e][0];
        int join = -1;  // decided at the first piece
        const auto piece = [&](std::uint32_t to) {
          const std::uint32_t g = add(forward, from, to), h = add(backward, to, from);
          if (join < 0)
            join = !std::binary_search(v.in_plane.begin(), v.in_plane.end(), e) || !pinched(s, e, solid, pinch_near);
          if (join) links.emplace_back(g, h);
        };
        for (std::uint32_t c = v.edge_crossings[e][0]; c < v.edge_crossings[e][1]; ++c) {
          if (in) piece(base_c + c);
          in = !in;
          from = base_c + c;
        }
        if (in) piece(base_v + s.edges[e][1]);
      }
  };
  edge_pieces(va, b, 0, base_ca, 0);
  edge_pieces(vb, a, base_b, base_cb, triangles_a);

  // Each triangle's segments close into loops; the loops of one face (an
  // outer loop and its holes) are one piece, and faces that share a segment
  // are.
  std::vector<std::uint32_t>& order = w.order;
  order.resize(segments.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return std::tie(segments[x].triangle, segments[x].from) < std::tie(segments[y].triangle, segments[y].from);
  });
  const auto normal_of = [&](std::uint32_t triangle) {
    const Surface& s = triangle < triangles_a ? a : b;
    const TriangleIndices& t = s.triangles[triangle < triangles_a ? triangle : triangle - triangles_a];
    return cross(s.vertices[t[1]] - s.vertices[t[0]], s.vertices[t[2]] - s.vertices[t[0]]);
  };
  // Loop l is loop_members[loop_begin[l] .. loop_begin[l + 1]).
  std::vector<std::uint32_t>& loop_members = w.loop_members;
  std::vector<std::uint32_t>& loop_begin = w.loop_begin;
  std::vector<std::uint32_t>& loop_segment = w.loop_segment;  // a segment of each loop
  std::vector<Real>& loop_area = w.loop_area;
  std::vector<std::uint8_t>& seen = w.seen;
  loop_members.clear(), loop_begin.assign(1, 0), loop_segment.clear(), loop_area.clear();
  seen.assign(segments.size(), 0);
  const auto loop = [&](std::size_t l) {
    return std::span<const std::uint32_t>(loop_members).subspan(loop_begin[l], loop_begin[l + 1] - loop_begin[l]);
  };
  // A loop can pass twice through one point under two ids: a corner of its
  // triangle through which an edge of the other surface passes (where two
  // pieces touch along that edge, an L's inner edge at the other's inner
  // corner). Its lobes there are faces that meet at a point only, not one
  // piece: each lobe is joined on its own. The corner lies on the edge
  // exactly when it is collinear with the edge's ends and none of them, the
  // edge not in the triangle's plane (exact predicates).
  constexpr std::uint32_t kNoCorner = ~std::uint32_t{0};
  const auto corner_on_crossing = [&](std::uint32_t triangle, std::uint32_t id) -> std::uint32_t {
    const bool of_a = triangle < triangles_a;
    const Crossing* c = nullptr;
    if (of_a && id >= base_cb) c = &vb.crossings[id - base_cb];
    if (!of_a && id >= base_ca && id < base_cb) c = &va.crossings[id - base_ca];
    if (!c) return kNoCorner;
    const Surface& own = of_a ? a : b;
    const Surface& other = of_a ? b : a;
    const Vec3& p = other.vertices[other.edges[c->edge][0]];
    const Vec3& q = other.vertices[other.edges[c->edge][1]];
    const TriangleIndices& corners = own.triangles[of_a ? triangle : triangle - triangles_a];
    const Vec3 &t0 = own.vertices[corners[0]], &t1 = own.vertices[corners[1]], &t2 = own.vertices[corners[2]];
    for (const std::uint32_t corner : corners) {
      const Vec3& v = own.vertices[corner];
      if (v == p || v == q) continue;  // vertex on vertex: the perturbation parts them
      // Only a crossing rounded near the corner can be at it (the exact test decides).
      const Vec3 off = c->point - (v - origin);
      if (dot(off, off) > 1e-12 * dot(q - p, q - p)) continue;
      // An edge in the triangle's plane meets it where the perturbation says.
      if (orient3d(t0, t1, t2, p) == 0 && orient3d(t0, t1, t2, q) == 0) return kNoCorner;
      if (orient2d(p, q, v, 0) == 0 && orient2d(p, q, v, 1) == 0 && orient2d(p, q, v, 2) == 0)
        return (of_a ? 0 : base_b) + corner;
    }
    return kNoCorner;
  };
  std::vector<std::uint32_t>& lobe = w.lobe;
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& same_point = w.same_point;  // (crossing id, corner id)
  const auto join_loop = [&](std::uint32_t triangle, std::span<const std::uint32_t> members) {
    same_point.clear();
    for (const std::uint32_t g : members)
      if (const std::uint32_t corner = corner_on_crossing(triangle, segments[g].from); corner != kNoCorner)
        same_point.emplace_back(segments[g].from, corner);
    if (same_point.empty()) {
      for (const std::uint32_t g : members) joined.join(g, members[0]);
      return;
    }
    const auto same = [&](std::uint32_t x, std::uint32_t y) {
      if (x == y) return true;
      for (const auto& [crossing, corner] : same_point)
        if ((x == crossing && y == corner) || (x == corner && y == crossing)) return true;
      return false;
    };
    lobe.clear();
    for (const std::uint32_t g : members) {
      std::size_t j = 0;
      while (j < lobe.size() && !same(segments[lobe[j]].from, segments[g].from)) ++j;
      if (j < lobe.size()) {  // the lobe from lobe[j] closes where g starts
        for (std::size_t i = j; i < lobe.size(); ++i) joined.join(lobe[i], lobe[j]);
        lobe.resize(j);
      }
      lobe.push_back(g);
    }
    for (const std::uint32_t g : lobe) joined.join(g, lobe[0]);
  };
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin;
    const std::uint32_t triangle = segments[order[begin]].triangle;
    while (end < order.size() && segments[order[end]].triangle == triangle) ++end;
    const auto next = [&](std::uint32_t at) {  // the segment that starts where `at` ends
      const auto it = std::lower_bound(order.begin() + begin, order.begin() + end, segments[at].to,
                                       [&](std::uint32_t x, std::uint32_t id) { return segments[x].from < id; });
      if (it == order.begin() + end || segments[*it].from != segments[at].to)
        throw std::logic_error("surface_overlap: a cycle does not close");
      return *it;
    };
    const Vec3 n = normal_of(triangle);
    const std::size_t first_loop = loop_segment.size();
    for (std::size_t k = begin; k < end; ++k) {
      if (seen[order[k]]) continue;
      loop_segment.push_back(order[k]);
      Vec3 area;
      for (std::uint32_t at = order[k]; !seen[at]; at = next(at)) {
        seen[at] = 1;
        loop_members.push_back(at);
        area += cross(segments[at].p, segments[at].q);
      }
      join_loop(triangle, std::span<const std::uint32_t>(loop_members).subspan(loop_begin.back()));
      loop_begin.push_back(static_cast<std::uint32_t>(loop_members.size()));
      loop_area.push_back(dot(area, n));
    }
    // Holes (loops turning the other way) belong to the smallest outer loop
    // holding them.
    const int axis = dominant_axis(n);
    std::size_t outer = 0, last_outer = first_loop;
    for (std::size_t l = first_loop; l < loop_segment.size(); ++l)
      if (loop_area[l] > 0) ++outer, last_outer = l;
    for (std::size_t l = first_loop; l < loop_segment.size(); ++l) {
      if (loop_area[l] > 0) continue;
      std::size_t home = last_outer;
      if (outer > 1) {
        Real smallest = std::numeric_limits<Real>::infinity();
        for (std::size_t m = first_loop; m < loop_segment.size(); ++m)
          if (loop_area[m] > 0 && loop_area[m] < smallest && loop_holds(segments, loop(m), segments[loop(l)[0]].p, axis))
            smallest = loop_area[m], home = m;
      }
      if (outer > 0) joined.join(loop_segment[l], loop_segment[home]);
    }
    begin = end;
  }
  // Whole triangles' nodes follow the segments'. A segment of no length (its
  // ends the same point) joins nothing: faces that meet at a point only are
  // not one piece.
  const std::uint32_t base_whole = static_cast<std::uint32_t>(segments.size());
  for (std::size_t k = 0; k < whole_list.size(); ++k) joined.add();
  const auto node = [&](std::uint32_t x) { return x & kWholeTag ? base_whole + (x & ~kWholeTag) : x; };
  for (const auto& [g, h] : links)
    if ((g & kWholeTag) || !(segments[g].p == segments[g].q)) joined.join(node(g), node(h));

  // Sums per piece, with the triangle's first corner as the fans' apex (a
  // whole triangle: one fan, over its far side).
  std::vector<Sums>& pieces = w.pieces;  // by the piece's root node
  pieces.assign(joined.parent.size(), Sums{});
  const auto add_fan = [&](std::uint32_t t, std::uint32_t at, const Vec3& p, const Vec3& q) {
    const Surface& s = t < triangles_a ? a : b;
    const Vec3 apex = s.vertices[s.triangles[t < triangles_a ? t : t - triangles_a][0]] - origin;
    Sums& sum = pieces[joined.find(at)];
    const Real v6 = dot(apex, cross(p, q));
    sum.volume6 += v6;
    sum.moment24 += v6 * (apex + p + q);
    const Vec3 fan = 0.5 * cross(p - apex, q - apex);
    if (t < triangles_a) {
      sum.area_a += fan;
      sum.area_moment_a += cross((apex + p + q) / 3, fan);
    } else {
      sum.area_b += fan;
    }
  };
  for (std::uint32_t k = 0; k < segments.size(); ++k) add_fan(segments[k].triangle, k, segments[k].p, segments[k].q);
  for (std::uint32_t k = 0; k < whole_list.size(); ++k) {
    const std::uint32_t t = whole_list[k];
    const Surface& s = t < triangles_a ? a : b;
    const TriangleIndices& corners = s.triangles[t < triangles_a ? t : t - triangles_a];
    add_fan(t, base_whole + k, s.vertices[corners[1]] - origin, s.vertices[corners[2]] - origin);
  }

  // Coplanar faces: the perturbation put one or both of them inside the
  // other solid and their cycles counted them, but they bound no volume
  // (facing each other) or lie on both surfaces (facing the same way): the
  // areas count neither (query-format-mesh.md).
  const auto piece_at = [&](std::uint32_t triangle, const Vec3& x) -> Sums* {
    const int axis = dominant_axis(normal_of(triangle));
    Sums* found = nullptr;
    for (std::size_t l = 0; l < loop_segment.size(); ++l)
      if (segments[loop_segment[l]].triangle == triangle) {
        Sums* sum = &pieces[joined.find(loop_segment[l])];
        if (!found || (loop_area[l] > 0 && loop_holds(segments, loop(l), x, axis))) found = sum;
      }
    return found;
  };
  for (const auto& [s, t] : coplanar) {  // (found exactly on the walk)
    const TriangleIndices &ts = a.triangles[s], &tt = b.triangles[t];
    const Vec3 pa[3] = {a.vertices[ts[0]] - origin, a.vertices[ts[1]] - origin, a.vertices[ts[2]] - origin};
    const Vec3 pb[3] = {b.vertices[tt[0]] - origin, b.vertices[tt[1]] - origin, b.vertices[tt[2]] - origin};
    const Vec3 na = cross(pa[1] - pa[0], pa[2] - pa[0]), nb = cross(pb[1] - pb[0], pb[2] - pb[0]);
    const Vec3 &a0 = a.vertices[ts[0]], &a1 = a.vertices[ts[1]], &a2 = a.vertices[ts[2]];
    const Vec3 &b0 = b.vertices[tt[0]], &b1 = b.vertices[tt[1]], &b2 = b.vertices[tt[2]];
    Vec3 middle;
    const Real area = coplanar_overlap_area(pa, pb, na, middle);
    if (area == 0) continue;
    if (perturbed_orient3d(b0, b1, b2, a0, Side::B) < 0)  // a's face inside B
      if (Sums* sum = piece_at(s, middle)) {
        sum->area_a -= area / length(na) * na;
        sum->area_moment_a -= cross(middle, area / length(na) * na);
      }
    if (perturbed_orient3d(a0, a1, a2, b0, Side::A) < 0)  // b's face inside A
      if (Sums* sum = piece_at(triangles_a + t, middle)) sum->area_b -= area / length(nb) * nb;
  }

  // Pieces without volume (the slivers of faces that only touch) are no
  // patches, and count in no total: the totals are the patches'.
  const Real smallest = kPatchMinRelVolume * std::fmin(a.volume, b.volume);
  const auto kept = [&](std::uint32_t root) { return joined.find(root) == root && pieces[root].volume6 / 6 > smallest; };
  Sums total;
  for (std::uint32_t root = 0; root < pieces.size(); ++root) {
    if (!kept(root)) continue;
    const Sums& sum = pieces[root];
    total.volume6 += sum.volume6;
    total.moment24 += sum.moment24;
    total.area_a += sum.area_a;
    total.area_b += sum.area_b;
    total.area_moment_a += sum.area_moment_a;
  }
  out.volume = total.volume6 / 6;
  out.area_a = total.area_a;
  out.area_b = total.area_b;
  out.area_moment_a = total.area_moment_a + cross(origin, total.area_a);
  if (out.volume > 0) out.centroid = origin + total.moment24 / (24 * out.volume);
  else out.volume = 0;
  // Touching counts as intersecting: an edge through a triangle of the moved
  // pair meets it in the unmoved one too; without any, decided on the closed
  // triangles (exact, unmoved).
  out.intersect = !va.crossings.empty() || !vb.crossings.empty() || out.volume > 0;
  for (std::size_t k = 0; k < pairs.size() && !out.intersect; ++k) {
    const TriangleIndices &ts = a.triangles[pairs[k].first], &tt = b.triangles[pairs[k].second];
    out.intersect = triangles_meet(a.vertices[ts[0]], a.vertices[ts[1]], a.vertices[ts[2]], b.vertices[tt[0]],
                                   b.vertices[tt[1]], b.vertices[tt[2]]);
  }
  for (std::uint32_t root = 0; root < pieces.size(); ++root) {
    if (!kept(root)) continue;
    const Sums& sum = pieces[root];
    SurfacePatch patch;
    patch.volume = sum.volume6 / 6;
    patch.centroid = origin + sum.moment24 / (24 * patch.volume);
    patch.area_a = sum.area_a;
    patch.area_b = sum.area_b;
    patch.area_moment_a = sum.area_moment_a + cross(origin, sum.area_a);
    out.patches.push_back(patch);
  }
  std::sort(out.patches.begin(), out.patches.end(), [](const SurfacePatch& x, const SurfacePatch& y) {
    return x.volume > y.volume || (x.volume == y.volume && std::tie(x.centroid.x, x.centroid.y, x.centroid.z) <
                                                               std::tie(y.centroid.x, y.centroid.y, y.centroid.z));
  });
  return out;
}

}  // namespace gjkdem
