// 3D convex hull by Quickhull (Barber, Dobkin and Huhdanpaa, ACM TOMS 22(4),
// 1996): every point outside the current hull sits in the conflict list of one
// face it sees; the farthest point of a face's list (always a vertex of the final
// hull) removes the faces it sees, found by a walk over face adjacency, and is
// joined to their horizon; the orphaned points move to the new faces or, seeing
// none, are inside for good. The tolerance decides which points count as on a
// face; the result is checked to be a closed 2-manifold and says so, so callers
// can refuse to walk a broken one.
#include "gjkdem/shape/convex_hull.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {

struct Face {
  int v[3];
  Vec3 normal;               // unit, outward
  Real offset;               // normal . x for x on the face
  bool alive;
  std::vector<int> outside;  // conflict list: points that see this face
};

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Directed edges (a, b) of points 0..n-1 to a value >= 0: a flat n by n
// table for small hulls (a hash map's allocation per edge cost more than
// the hull), a hash map beyond.
class EdgeMap {
 public:
  explicit EdgeMap(std::size_t n) : n_(n) {
    if (n <= kFlatEdgePoints) flat_.assign(n * n, -1);
  }
  void set(int a, int b, int value) {
    if (flat()) {
      int& slot = flat_[index(a, b)];
      size_ += slot < 0;
      slot = value;
    } else {
      map_[edge_key(a, b)] = value;
    }
  }
  /// The value, or -1 where the edge has none.
  int find(int a, int b) const {
    if (flat()) return flat_[index(a, b)];
    const auto it = map_.find(edge_key(a, b));
    return it == map_.end() ? -1 : it->second;
  }
  /// The value of an edge that must have one.
  int at(int a, int b) const {
    const int value = find(a, b);
    if (value < 0) throw std::out_of_range("convex_hull: an edge without its twin");
    return value;
  }
  void erase(int a, int b) {
    if (flat()) {
      int& slot = flat_[index(a, b)];
      size_ -= slot >= 0;
      slot = -1;
    } else {
      map_.erase(edge_key(a, b));
    }
  }
  /// Edges with a value.
  std::size_t size() const { return flat() ? size_ : map_.size(); }

 private:
  static constexpr std::size_t kFlatEdgePoints = 128;  // at most this many points: the n by n table (64 KiB)
  bool flat() const { return n_ <= kFlatEdgePoints; }
  std::size_t index(int a, int b) const { return static_cast<std::size_t>(a) * n_ + static_cast<std::size_t>(b); }
  std::size_t n_;
  std::size_t size_ = 0;
  std::vector<int> flat_;
  std::unordered_map<std::uint64_t, int> map_;
};

Face make_face(const std::vector<Vec3>& p, int a, int b, int c) {
  const Vec3 n = normalized(cross(p[b] - p[a], p[c] - p[a]));
  return {{a, b, c}, n, dot(n, p[a]), true, {}};
}

Real distance_to_line(const Vec3& q, const Vec3& a, const Vec3& unit_dir) {
  const Vec3 r = q - a;
  return length(r - unit_dir * dot(r, unit_dir));
}

// Points of a plane (origin, in-plane axes e1, e2) in its 2D coordinates.
std::vector<int> polygon_hull(const std::vector<Vec3>& p, const Vec3& origin, const Vec3& e1, const Vec3& e2,
                              Real tol) {
  std::vector<Vec2> q;
  q.reserve(p.size());
  for (const Vec3& v : p) q.push_back({dot(v - origin, e1), dot(v - origin, e2)});
  return convex_hull_2d(q, tol);
}

constexpr std::size_t kWeldScanPoints = 64;  // at most this many: weld scans instead of hashing

// Drops each point within tol of one kept before it. Two such points both
// on the hull make a needle face whose plane is noise: the hull of a
// tessellated sphere from single precision, whose pole ring has points 3e-14
// apart, kept a face that every other point lay 4 (the diameter) beyond, and
// an overlap read it as empty. Points are hashed on a grid of cells tol wide;
// a neighbour lies in one of the 27 cells around.
void weld(std::vector<Vec3>& p, Real tol) {
  if (!(tol > 0)) return;
  // Few points: each against the kept ones, no grid (its hash map would
  // allocate more than it saves). A kept point within tol lies in a cell next
  // to the point's (up to the rounding of x / tol), so both ways keep the
  // same points.
  if (p.size() <= kWeldScanPoints) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      bool near = false;
      for (std::size_t j = 0; j < kept && !near; ++j) near = length(p[j] - p[i]) <= tol;
      if (!near) p[kept++] = p[i];
    }
    p.resize(kept);
    return;
  }
  std::unordered_map<std::uint64_t, std::vector<int>> cells;
  auto cell_of = [&](const Vec3& q, int k) { return static_cast<std::int64_t>(std::floor(q[k] / tol)); };
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto h = [](std::int64_t v) { return static_cast<std::uint64_t>(v) * 0x9E3779B97F4A7C15ull; };
    return h(x) ^ (h(y) >> 21) ^ (h(z) << 21) ^ (h(z) >> 43);
  };
  std::size_t kept = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::int64_t cx = cell_of(p[i], 0), cy = cell_of(p[i], 1), cz = cell_of(p[i], 2);
    bool near = false;
    for (std::int64_t dx = -1; dx <= 1 && !near; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && !near; ++dy)
        for (std::int64_t dz = -1; dz <= 1 && !near; ++dz) {
          const auto it = cells.find(key(cx + dx, cy + dy, cz + dz));
          if (it == cells.end()) continue;
          for (int j : it->second) near = near || length(p[j] - p[i]) <= tol;
        }
    if (near) continue;
    p[kept] = p[i];
    cells[key(cx, cy, cz)].push_back(static_cast<int>(kept));
    ++kept;
  }
  p.resize(kept);
}

// Whether directed edges form one loop through distinct corners: sorted by
// their first corner, no corner starts two, and the walk from one corner
// returns to it after every edge.
bool simple_loop(std::vector<std::pair<int, int>> edges) {
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 1; k < edges.size(); ++k)
    if (edges[k].first == edges[k - 1].first) return false;
  const int first = edges.front().first;
  int at = first;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const auto it = std::lower_bound(edges.begin(), edges.end(), std::pair<int, int>(at, INT_MIN));
    if (it == edges.end() || it->first != at) return false;
    at = it->second;
  }
  return at == first;
}

}  // namespace

std::size_t convex_hull_2d(std::span<const Vec2> points, Real tol, std::span<int> scratch) noexcept {
  // Andrew's monotone chain: sort by x then y, build the lower and upper
  // chains. scratch: the sorted order (n), then the chains (2n).
  const std::size_t n = points.size();
  int* order = scratch.data();
  int* h = scratch.data() + n;
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<int>(i);
  const auto before = [&](int a, int b) {
    return points[a].x < points[b].x || (points[a].x == points[b].x && points[a].y < points[b].y);
  };
  // The cuts an overlap closes by its hull hold a few points each: sorted
  // by insertion below 32 points (no calls).
  if (n < 32) {
    for (std::size_t i = 1; i < n; ++i) {
      const int v = order[i];
      std::size_t j = i;
      for (; j > 0 && before(v, order[j - 1]); --j) order[j] = order[j - 1];
      order[j] = v;
    }
  } else {
    std::sort(order, order + n, before);
  }
  const std::size_t m =
      static_cast<std::size_t>(std::unique(order, order + n, [&](int a, int b) { return points[a] == points[b]; }) - order);
  if (m < 3) return m;  // order is the start of scratch
  // c makes a strict left turn after a -> b when it lies more than tol (a length) left of a -> c:
  // cross(ab, ac) > tol |ac|, compared squared (no square root per turn).
  const Real tol_sq = tol * tol;
  auto left_turn = [&](int a, int b, int c) {
    const Vec2 ab = points[b] - points[a], ac = points[c] - points[a];
    const Real turn = cross(ab, ac);
    return turn > 0 && (tol_sq == 0 || turn * turn > tol_sq * dot(ac, ac));
  };
  std::size_t k = 0;
  for (std::size_t i = 0; i < m; ++i) {
    while (k >= 2 && !left_turn(h[k - 2], h[k - 1], order[i])) --k;
    h[k++] = order[i];
  }
  for (std::size_t i = m - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && !left_turn(h[k - 2], h[k - 1], order[i])) --k;
    h[k++] = order[i];
  }
  std::copy(h, h + k - 1, scratch.data());  // the last point repeats the first
  return k - 1;
}

std::vector<int> convex_hull_2d(std::span<const Vec2> points, Real tol) {
  std::vector<int> scratch(3 * points.size());
  scratch.resize(convex_hull_2d(points, tol, scratch));
  return scratch;
}

ConvexHull convex_hull(std::span<const Vec3> points) {
  ConvexHull hull;
  std::vector<Vec3> p(points.begin(), points.end());
  std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.empty()) return hull;

  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& q : p)
    for (int k = 0; k < 3; ++k) { lo[k] = std::fmin(lo[k], q[k]); hi[k] = std::fmax(hi[k], q[k]); }
  const Real diag = length(hi - lo);
  const Real tol = kHullRelTol * diag;
  weld(p, tol);
  if (p.size() == 1 || !(diag > 0)) {
    hull.dimension = HullDimension::Point;
    hull.vertices = {p[0]};
    return hull;
  }

  // Initial simplex: the extremes of the widest axis, then the points farthest
  // from their line and from their plane.
  const Vec3 ext = hi - lo;
  const int axis = ext.x >= ext.y ? (ext.x >= ext.z ? 0 : 2) : (ext.y >= ext.z ? 1 : 2);
  int i0 = 0, i1 = 0;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    if (p[i][axis] < p[i0][axis]) i0 = i;
    if (p[i][axis] > p[i1][axis]) i1 = i;
  }
  const Vec3 u = normalized(p[i1] - p[i0]);
  int i2 = -1;
  Real best = tol;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    const Real d = distance_to_line(p[i], p[i0], u);
    if (d > best) { best = d; i2 = i; }
  }
  if (i2 < 0) {
    hull.dimension = HullDimension::Segment;
    int a = 0, b = 0;
    for (int i = 0; i < static_cast<int>(p.size()); ++i) {
      if (dot(p[i], u) < dot(p[a], u)) a = i;
      if (dot(p[i], u) > dot(p[b], u)) b = i;
    }
    hull.vertices = {p[a], p[b]};
    return hull;
  }
  const Vec3 plane_n = normalized(cross(p[i1] - p[i0], p[i2] - p[i0]));
  int i3 = -1;
  best = tol;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    const Real d = std::fabs(dot(plane_n, p[i] - p[i0]));
    if (d > best) { best = d; i3 = i; }
  }
  if (i3 < 0) {
    hull.dimension = HullDimension::Polygon;
    for (int i : polygon_hull(p, p[i0], u, cross(plane_n, u), tol)) hull.vertices.push_back(p[i]);
    return hull;
  }

  // Solid: start from the tetrahedron, oriented outward.
  std::vector<Face> faces;
  EdgeMap edge_face(p.size());  // directed edge -> face holding it
  auto add_face = [&](int a, int b, int c) {
    faces.push_back(make_face(p, a, b, c));
    const int f = static_cast<int>(faces.size()) - 1;
    edge_face.set(a, b, f);
    edge_face.set(b, c, f);
    edge_face.set(c, a, f);
  };
  if (dot(plane_n, p[i3] - p[i0]) > 0) std::swap(i1, i2);
  add_face(i0, i1, i2);
  add_face(i0, i3, i1);
  add_face(i1, i3, i2);
  add_face(i2, i3, i0);

  auto height = [&](int f, int q) { return dot(faces[f].normal, p[q]) - faces[f].offset; };
  auto assign = [&](int q, int first_face) {
    for (int f = first_face; f < static_cast<int>(faces.size()); ++f)
      if (faces[f].alive && height(f, q) > tol) { faces[f].outside.push_back(q); return; }
  };
  for (int q = 0; q < static_cast<int>(p.size()); ++q)
    if (q != i0 && q != i1 && q != i2 && q != i3) assign(q, 0);

  std::vector<int> visible, stack, orphans;
  std::vector<std::pair<int, int>> horizon;
  std::vector<char> is_visible;
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    if (!faces[f].alive || faces[f].outside.empty()) continue;
    int apex = faces[f].outside[0];
    for (int q : faces[f].outside)
      if (height(f, q) > height(f, apex)) apex = q;
    // Faces the apex sees, connected to f.
    is_visible.assign(faces.size(), 0);
    visible.clear();
    stack.assign(1, f);
    is_visible[f] = 1;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      visible.push_back(g);
      for (int k = 0; k < 3; ++k) {
        const int h = edge_face.find(faces[g].v[(k + 1) % 3], faces[g].v[k]);
        if (h < 0) continue;
        if (!is_visible[h] && height(h, apex) > tol) { is_visible[h] = 1; stack.push_back(h); }
      }
    }
    // A face beyond the horizon that the apex sees by less than tol stays,
    // and the new face on their edge may fold against it. A needle (the apex
    // within kHullNeedleRel of the edge's line: corners 1e-7 apart) turns a
    // fold of tol into one of 1e-9, later walks stop at it, and a hull once
    // kept points 0.0095 outside: so the face beyond a needle that folds by
    // more than tol is taken too, unless the apex lies clearly below it.
    // The apex lies within kHullNeedleRel * diag of the line a b (compared squared).
    auto needle = [&](int a, int b, int q) {
      const Real limit = kHullNeedleRel * diag;
      return length_sq(cross(p[b] - p[a], p[q] - p[a])) < limit * limit * length_sq(p[b] - p[a]);
    };
    // The new face a b q folds against `beyond` (across a b) by more than tol.
    auto folds = [&](int a, int b, int q, const Face& beyond) {
      const int far = beyond.v[0] + beyond.v[1] + beyond.v[2] - a - b;
      const Face fresh = make_face(p, a, b, q);
      return dot(fresh.normal, p[far]) - fresh.offset > tol;
    };
    const std::size_t seen = visible.size();
    for (bool grew = true, grow = true; grew;) {
      grew = false;
      horizon.clear();
      for (std::size_t i = 0; i < visible.size(); ++i) {
        const int g = visible[i];
        for (int k = 0; k < 3; ++k) {
          const int a = faces[g].v[k], b = faces[g].v[(k + 1) % 3];
          const int twin = edge_face.find(b, a);
          if (twin < 0 || is_visible[twin]) continue;
          if (grow && needle(a, b, apex) && height(twin, apex) > -tol && folds(a, b, apex, faces[twin])) {
            is_visible[twin] = 1;
            visible.push_back(twin);
            grew = true;
          } else {
            horizon.emplace_back(a, b);
          }
        }
      }
      // Grown, the region must still be a disc: its rim one loop through
      // distinct corners. Else it is taken as first seen.
      if (!grew && visible.size() > seen && !simple_loop(horizon)) {
        for (std::size_t i = seen; i < visible.size(); ++i) is_visible[visible[i]] = 0;
        visible.resize(seen);
        grew = true;
        grow = false;
      }
    }
    orphans.clear();
    for (int g : visible) {
      for (int q : faces[g].outside)
        if (q != apex) orphans.push_back(q);
      faces[g].alive = false;
      faces[g].outside = {};
    }
    for (int g : visible)
      for (int k = 0; k < 3; ++k) {
        const int a = faces[g].v[k], b = faces[g].v[(k + 1) % 3];
        if (edge_face.find(a, b) == g) edge_face.erase(a, b);
      }
    const int first_new = static_cast<int>(faces.size());
    for (const auto& [a, b] : horizon) add_face(a, b, apex);
    for (int q : orphans) assign(q, first_new);
    // Faces are only appended, so the outer loop reaches the new ones later.
  }

  // Compact the surviving faces and vertices.
  std::vector<int> remap(p.size(), -1);
  for (const Face& f : faces) {
    if (!f.alive) continue;
    std::array<int, 3> t;
    for (int k = 0; k < 3; ++k) {
      if (remap[f.v[k]] < 0) {
        remap[f.v[k]] = static_cast<int>(hull.vertices.size());
        hull.vertices.push_back(p[f.v[k]]);
      }
      t[k] = remap[f.v[k]];
    }
    hull.triangles.push_back(t);
  }
  hull.dimension = HullDimension::Solid;

  // Closed 2-manifold: every directed edge once, its twin present, V - E + F = 2.
  EdgeMap count(hull.vertices.size());
  for (const auto& t : hull.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      count.set(a, b, std::max(count.find(a, b), 0) + 1);
    }
  bool ok = true;
  for (const auto& t : hull.triangles)
    for (int k = 0; k < 3 && ok; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (count.find(a, b) != 1 || count.find(b, a) < 0) ok = false;
    }
  const long v = static_cast<long>(hull.vertices.size()), f = static_cast<long>(hull.triangles.size());
  const long e = static_cast<long>(count.size()) / 2;
  hull.manifold = ok && v - e + f == 2;
  if (hull.manifold) merge_coplanar_facets(hull);
  return hull;
}

void merge_coplanar_facets(ConvexHull& hull) {
  const auto& v = hull.vertices;
  const int nt = static_cast<int>(hull.triangles.size());
  Vec3 lo = v[0], hi = v[0];
  for (const Vec3& q : v)
    for (int k = 0; k < 3; ++k) { lo[k] = std::fmin(lo[k], q[k]); hi[k] = std::fmax(hi[k], q[k]); }
  const Real tol = kHullRelTol * length(hi - lo);
  std::vector<Vec3> normal(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& tri = hull.triangles[t];
    normal[t] = normalized(cross(v[tri[1]] - v[tri[0]], v[tri[2]] - v[tri[0]]));
  }
  EdgeMap edge_tri(v.size());
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) edge_tri.set(hull.triangles[t][k], hull.triangles[t][(k + 1) % 3], t);
  // Flood fill over edges between coplanar neighbours.
  std::vector<int> group(nt, -1), stack;
  int groups = 0;
  for (int seed = 0; seed < nt; ++seed) {
    if (group[seed] >= 0) continue;
    group[seed] = groups;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int a = hull.triangles[t][k], b = hull.triangles[t][(k + 1) % 3];
        const int u = edge_tri.at(b, a);
        if (group[u] >= 0) continue;
        const int far = hull.triangles[u][0] + hull.triangles[u][1] + hull.triangles[u][2] - a - b;
        if (length(normal[u] - normal[seed]) <= kHullParallelTol &&
            std::fabs(dot(normal[seed], v[far] - v[hull.triangles[seed][0]])) <= tol) {
          group[u] = groups;
          stack.push_back(u);
        }
      }
    }
    ++groups;
  }
  // Each group's boundary: its directed edges whose reverse lies outside the
  // group, chained head to tail.
  hull.facets.assign(groups, {});
  hull.facet_normals.assign(groups, Vec3{});
  std::vector<std::unordered_map<int, int>> next(groups);
  std::vector<Vec3> area(groups);
  bool simple = true;  // every boundary a single loop through distinct vertices
  for (int t = 0; t < nt; ++t) {
    const auto& tri = hull.triangles[t];
    area[group[t]] += cross(v[tri[1]] - v[tri[0]], v[tri[2]] - v[tri[0]]);
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      if (group[edge_tri.at(b, a)] != group[t]) simple &= next[group[t]].emplace(a, b).second;
    }
  }
  for (int g = 0; g < groups && simple; ++g) {
    hull.facet_normals[g] = normalized(area[g]);
    const int start = next[g].begin()->first;
    int cur = start;
    do {
      hull.facets[g].push_back(cur);
      cur = next[g].at(cur);
    } while (cur != start && hull.facets[g].size() <= next[g].size());
    simple &= cur == start && hull.facets[g].size() == next[g].size();
  }
  if (!simple) {  // round-off made a group pinch or split: keep the plain triangles
    hull.facets.clear();
    hull.facet_normals.clear();
    for (int t = 0; t < nt; ++t) {
      hull.facets.push_back({hull.triangles[t][0], hull.triangles[t][1], hull.triangles[t][2]});
      hull.facet_normals.push_back(normal[t]);
    }
  }
  // Facet adjacency: the facet across each boundary edge.
  EdgeMap edge_facet(v.size());
  for (int f = 0; f < static_cast<int>(hull.facets.size()); ++f) {
    const auto& poly = hull.facets[f];
    for (std::size_t k = 0; k < poly.size(); ++k) edge_facet.set(poly[k], poly[(k + 1) % poly.size()], f);
  }
  hull.facet_neighbors.assign(hull.facets.size(), {});
  for (int f = 0; f < static_cast<int>(hull.facets.size()); ++f) {
    const auto& poly = hull.facets[f];
    for (std::size_t k = 0; k < poly.size(); ++k) {
      hull.facet_neighbors[f].push_back(edge_facet.find(poly[(k + 1) % poly.size()], poly[k]));
    }
  }
}

}  // namespace gjkdem
