#include "gjkdem/shape/surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>

#include "gjkdem/shape/deep_points.hpp"
#include "gjkdem/shape/hull_surface_slot.hpp"
#include "gjkdem/math/union_find.hpp"
#include "gjkdem/shape/predicates.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

std::string triangle_index_problem(const TriangleIndices& corners, std::size_t vertex_count) {
  for (const std::uint32_t i : corners)
    if (i >= vertex_count)
      return "refers to vertex " + std::to_string(i) + " but there are " + std::to_string(vertex_count) + " vertices";
  if (repeats_a_vertex(corners))
    return "repeats a vertex (" + std::to_string(corners[0]) + ", " + std::to_string(corners[1]) + ", " +
           std::to_string(corners[2]) + ")";
  return "";
}
namespace {

constexpr std::uint32_t kNoShell = 0xffffffffu;
constexpr std::uint32_t kNoRun = 0xffffffffu;

// Fans of this many triangles or more are taken by runs (fan_runs) rather
// than pair by pair: below it the pairs are few and cheap.
constexpr std::size_t kFanRunMinTriangles = 16;
// Corrections of the direction a fan is seen along before its runs are
// taken as they are (fan_runs).
constexpr int kFanViewPasses = 16;

// Which corner of the triangle is vertex v (one of its corners).
int corner_of(const TriangleIndices& tri, std::uint32_t v) { return tri[0] == v ? 0 : (tri[1] == v ? 1 : 2); }

std::string edge_name(std::uint32_t i, std::uint32_t j) {
  return "edge (" + std::to_string(i) + ", " + std::to_string(j) + ")";
}

// The coordinate to drop when looking at a plane with these three points
// (not collinear) flat on: one where their orientation is not 0.
int flat_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  int axes[3] = {0, 1, 2};
  std::sort(axes, axes + 3, [&](int s, int t) { return std::fabs(n[s]) > std::fabs(n[t]); });
  for (const int axis : axes)
    if (orient2d(a, b, c, axis) != 0) return axis;
  return 0;
}

// Closed segment pq against closed segment rs, all on one plane seen down `axis`.
bool segments_meet_2d(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, int axis) {
  const int d1 = orient2d(p, q, r, axis), d2 = orient2d(p, q, s, axis);
  const int d3 = orient2d(r, s, p, axis), d4 = orient2d(r, s, q, axis);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  const auto within = [&](const Vec3& u, const Vec3& v, const Vec3& x) {  // x on line uv: inside the segment?
    return std::min(u[i], v[i]) <= x[i] && x[i] <= std::max(u[i], v[i]) && std::min(u[j], v[j]) <= x[j] &&
           x[j] <= std::max(u[j], v[j]);
  };
  return (d1 == 0 && within(p, q, r)) || (d2 == 0 && within(p, q, s)) || (d3 == 0 && within(r, s, p)) ||
         (d4 == 0 && within(r, s, q));
}

// Point x in the closed triangle abc, all on one plane seen down `axis`.
bool inside_2d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x, int axis) {
  const int o = orient2d(a, b, c, axis);
  return o * orient2d(a, b, x, axis) >= 0 && o * orient2d(b, c, x, axis) >= 0 && o * orient2d(c, a, x, axis) >= 0;
}

// The closed segment pq meets the closed triangle abc.
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  if (sp * sq > 0) return false;
  if (sp == 0 && sq == 0) {
    const int axis = flat_axis(a, b, c);
    return inside_2d(a, b, c, p, axis) || inside_2d(a, b, c, q, axis) || segments_meet_2d(p, q, a, b, axis) ||
           segments_meet_2d(p, q, b, c, axis) || segments_meet_2d(p, q, c, a, axis);
  }
  const int o1 = orient3d(p, q, a, b), o2 = orient3d(p, q, b, c), o3 = orient3d(p, q, c, a);
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

// Direction x - v, on the plane of the triangle (v, c, d) seen down `axis`,
// lies in the triangle's closed corner at v.
bool in_corner(const Vec3& v, const Vec3& c, const Vec3& d, const Vec3& x, int axis) {
  const int o = orient2d(v, c, d, axis);
  return o * orient2d(v, c, x, axis) >= 0 && o * orient2d(v, x, d, axis) >= 0;
}

// Edge v->x of one triangle, lying in the plane of triangle (v, c, d) that
// shares corner v, points into that triangle's corner.
bool edge_enters_corner(const Vec3& v, const Vec3& x, const Vec3& c, const Vec3& d) {
  return orient3d(v, c, d, x) == 0 && in_corner(v, c, d, x, flat_axis(v, c, d));
}

// The boxes of the triangles and edges, where the vertices are now.
// Inline compares (coordinates are finite), where fmin and fmax are calls: a
// moved surface refits every box every step.
Vec3 lower(const Vec3& a, const Vec3& b) { return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z}; }
Vec3 upper(const Vec3& a, const Vec3& b) { return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z}; }

void fit_boxes(Surface& s) {
  s.triangle_boxes.resize(s.triangles.size());
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Vec3 &a = s.vertices[s.triangles[t][0]], &b = s.vertices[s.triangles[t][1]], &c = s.vertices[s.triangles[t][2]];
    s.triangle_boxes[t] = {lower(a, lower(b, c)), upper(a, upper(b, c))};
  }
  s.edge_boxes.resize(s.edges.size());
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const Vec3 &p = s.vertices[s.edges[e][0]], &q = s.vertices[s.edges[e][1]];
    s.edge_boxes[e] = {lower(p, q), upper(p, q)};
  }
}


// The sign of the enclosed volume, from the surface scaled (by a power of
// two: exactly) to about unit size and taken about its first vertex, so that
// neither its size nor its place decides: refuses a surface facing inward,
// and one whose volume is round-off (flat, or thinner than round-off).
void check_volume_resolved(const Surface& s) {
  const Real extent = std::fmax(max_abs(s.box.lo), max_abs(s.box.hi));
  int exponent = 0;
  std::frexp(extent, &exponent);
  const Vec3 o = s.vertices[0];
  const auto at = [&](std::uint32_t i) { return std::ldexp(Real(1), -exponent) * (s.vertices[i] - o); };
  Real volume6 = 0, scale = 0;
  for (const TriangleIndices& t : s.triangles) {
    const Vec3 a = at(t[0]), b = at(t[1]), c = at(t[2]);
    volume6 += dot(a, cross(b, c));
    scale += length(a) * length(b) * length(c);
  }
  if (!(std::fabs(volume6) > kFlatSurfaceRel * scale))
    throw SurfaceError("it encloses no volume that double precision resolves: it is flat, or thinner than 1e-12 of "
                       "its size");
  if (volume6 < 0)
    throw SurfaceError("the triangles face inward (the enclosed volume is negative): list each triangle's corners "
                       "the other way round");
}

// A surface of several shells bounds one solid when each point is inside it
// at most once: the other shells wind 0 times about a shell facing outward
// (a separate piece) and once about a shell facing inward (a cavity's). As
// the shells do not meet (checked before), one vertex of each decides.
void check_shells_nest(const Surface& s) {
  UnionFind joined;
  joined.reset(s.vertices.size());
  for (const auto& [p, q] : s.edges) joined.join(p, q);
  struct Shell {
    std::vector<TriangleIndices> triangles;
    std::uint32_t first_triangle = 0;
    Aabb box;
    Real volume6 = 0;
  };
  std::vector<Shell> shells;
  std::vector<std::uint32_t> shell_of(s.vertices.size(), kNoShell);
  for (std::uint32_t t = 0; t < s.triangles.size(); ++t) {
    const TriangleIndices& tri = s.triangles[t];
    std::uint32_t& k = shell_of[joined.find(tri[0])];
    if (k == kNoShell) {
      k = static_cast<std::uint32_t>(shells.size());
      shells.push_back({{}, t, s.triangle_boxes[t], 0});
    }
    Shell& shell = shells[k];
    shell.triangles.push_back(tri);
    shell.box = enclose(shell.box, s.triangle_boxes[t]);
    const Vec3 o = s.vertices[s.triangles[shell.first_triangle][0]];
    shell.volume6 += dot(s.vertices[tri[0]] - o, cross(s.vertices[tri[1]] - o, s.vertices[tri[2]] - o));
  }
  if (shells.size() < 2) return;
  for (const Shell& shell : shells) {
    const Vec3 p = s.vertices[shell.triangles[0][0]];
    Real winding = 0;
    for (const Shell& other : shells)
      if (&other != &shell && overlaps(other.box, {p, p})) winding += winding_number(s.vertices, other.triangles, p);
    const long inside = std::lround(winding);
    const long expected = shell.volume6 > 0 ? 0 : 1;
    if (inside == expected) continue;
    const std::string name = "the shell of triangle " + std::to_string(shell.first_triangle) + " (" +
                             std::to_string(shell.triangles.size()) + " triangles)";
    if (shell.volume6 > 0 && inside == 1)
      throw SurfaceError(name + " faces outward but lies inside the solid of another shell: a solid within a solid "
                                "(a cavity's triangles face into the cavity: list its corners the other way round)");
    if (shell.volume6 < 0 && inside == 0)
      throw SurfaceError(name + " faces inward but lies in no solid: a cavity must lie inside an outer shell (or "
                                "list its corners the other way round)");
    throw SurfaceError(name + " lies inside " + std::to_string(inside) +
                       " other shells: the shells do not bound one solid");
  }
}
}  // namespace

std::vector<std::uint32_t> fan_runs(const Surface& s, std::uint32_t v, std::span<const std::uint32_t> fan) {
  std::vector<std::uint32_t> run(fan.size());
  for (std::uint32_t i = 0; i < fan.size(); ++i) run[i] = i;  // no verdict: each its own
  if (fan.size() < 3) return run;
  // The triangle's other corners, in its turn: (v, b, c).
  const auto corners = [&](std::uint32_t t) {
    const TriangleIndices& tri = s.triangles[t];
    const int k = corner_of(tri, v);
    return std::pair{tri[(k + 1) % 3], tri[(k + 2) % 3]};
  };
  // Walked one way round (each triangle's c is the next one's b) or the other.
  bool one_way = true, other_way = true;
  for (std::size_t i = 0; i < fan.size(); ++i) {
    const TriangleIndices& tri = s.triangles[fan[i]];
    if (tri[0] != v && tri[1] != v && tri[2] != v) return run;
    const auto [b, c] = corners(fan[i]);
    const auto [nb, nc] = corners(fan[(i + 1) % fan.size()]);
    one_way = one_way && c == nb;
    other_way = other_way && b == nc;
  }
  if (!one_way && !other_way) return run;

  // Look along w: a triangle turns forward about v where its normal n has
  // n . w > 0. Begun at the mean of the unit normals, w is corrected by the
  // triangles that turn back (a perceptron's steps: it finds a w that all
  // face wherever one exists with room to spare, as a steep or uneven cone).
  const Vec3& p = s.vertices[v];
  std::vector<Vec3> unit_normal(fan.size());
  Vec3 w{0, 0, 0};
  for (std::size_t i = 0; i < fan.size(); ++i) {
    const auto [b, c] = corners(fan[i]);
    const Vec3 n = cross(s.vertices[b] - p, s.vertices[c] - p);
    const Real size = length(n);
    if (!(size > 0 && size < std::numeric_limits<Real>::infinity())) return run;
    unit_normal[i] = n / size;
    w = w + unit_normal[i];
  }
  const Real reach = length(s.vertices[corners(fan[0]).first] - p);
  if (!(reach > 0 && reach < std::numeric_limits<Real>::infinity())) return run;
  Vec3 eye;
  // Each triangle's turn about v seen from eye (exact), and whether
  // direction x lies in its corner.
  const auto turn = [&](std::uint32_t x, std::uint32_t y) { return orient3d(p, s.vertices[x], s.vertices[y], eye); };
  const auto in_corner = [&](std::uint32_t t, std::uint32_t x, int sign, bool closed) {
    const auto [b, c] = corners(t);
    return sign * turn(b, x) >= 0 && (closed ? sign * turn(x, c) >= 0 : sign * turn(x, c) > 0);
  };
  // Seen from eye, the turns; the number turning back (fan.size() + 1 where
  // eye is no view).
  std::vector<int> sign(fan.size());
  const auto look_along = [&](const Vec3& along) {
    const Real wn = length(along);
    if (!(wn > 0 && wn < std::numeric_limits<Real>::infinity())) return fan.size() + 1;
    eye = p + along * (reach / wn);  // any point off v will do: the predicates are exact
    if (!(std::isfinite(eye.x) && std::isfinite(eye.y) && std::isfinite(eye.z))) return fan.size() + 1;
    std::size_t back = 0;
    for (std::size_t i = 0; i < fan.size(); ++i) {
      sign[i] = turn(corners(fan[i]).first, corners(fan[i]).second);
      back += sign[i] <= 0;
    }
    return back;
  };
  Vec3 best = w;
  std::size_t fewest = fan.size() + 1, back = fewest;
  for (int pass = 0; pass < kFanViewPasses; ++pass) {
    back = look_along(w);
    if (back < fewest) best = w, fewest = back;
    if (back == 0 || back > fan.size()) break;
    for (std::size_t i = 0; i < fan.size(); ++i)
      if (sign[i] <= 0) w = w + unit_normal[i];
  }
  if (back != fewest && look_along(best) > fan.size()) return run;  // (the last look, where it was the best, stands)
  if (fewest > fan.size()) return run;

  // The whole fan as one run: one turn throughout, one round (counted half-open).
  const std::uint32_t start = corners(fan[0]).first;
  int rounds = 0;
  bool one_turn = sign[0] != 0;
  for (std::size_t i = 0; i < fan.size(); ++i) {
    one_turn = one_turn && sign[i] == sign[0];
    rounds += one_turn && in_corner(fan[i], start, sign[0], false);
  }
  if (one_turn && rounds == 1) {
    std::fill(run.begin(), run.end(), 0u);
    return run;
  }
  // Otherwise runs of consecutive triangles (in the walk's order) of one turn
  // that fall short of a round: a triangle whose closed corner holds its
  // run's first direction starts the next run. Begun where the turn changes,
  // so that a fold does not cut the run that passes the walk's start in two.
  const std::size_t n = fan.size();
  std::size_t begin = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (sign[i] != sign[(i + n - 1) % n]) {
      begin = i;
      break;
    }
  std::size_t first = begin;
  run[begin] = static_cast<std::uint32_t>(begin);
  for (std::size_t step = 1; step < n; ++step) {
    const std::size_t i = (begin + step) % n;
    const std::uint32_t b0 = one_way ? corners(fan[first]).first : corners(fan[first]).second;
    const bool joins = sign[i] != 0 && sign[i] == sign[first] && !in_corner(fan[i], b0, sign[i], true);
    if (!joins) first = i;
    run[i] = static_cast<std::uint32_t>(first);
  }
  return run;
}

bool triangles_meet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e, const Vec3& f) {
  // Most pairs lie wholly on one side of the other's plane: three signs each.
  const int sd = orient3d(a, b, c, d), se = orient3d(a, b, c, e), sf = orient3d(a, b, c, f);
  if ((sd > 0 && se > 0 && sf > 0) || (sd < 0 && se < 0 && sf < 0)) return false;
  const int sa = orient3d(d, e, f, a), sb = orient3d(d, e, f, b), sc = orient3d(d, e, f, c);
  if ((sa > 0 && sb > 0 && sc > 0) || (sa < 0 && sb < 0 && sc < 0)) return false;
  return segment_meets_triangle(a, b, d, e, f) || segment_meets_triangle(b, c, d, e, f) ||
         segment_meets_triangle(c, a, d, e, f) || segment_meets_triangle(d, e, a, b, c) ||
         segment_meets_triangle(e, f, a, b, c) || segment_meets_triangle(f, d, a, b, c);
}

bool triangles_clash(const Surface& surface, std::uint32_t s, std::uint32_t t) {
  const TriangleIndices& ts = surface.triangles[s];
  const TriangleIndices& tt = surface.triangles[t];
  const auto& v = surface.vertices;
  int shared = 0, ks = 0, kt = 0;  // corners of a shared vertex
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ts[i] == tt[j]) ++shared, ks = i, kt = j;
  const auto corner = [&](const TriangleIndices& tri, int k) -> const Vec3& { return v[tri[k % 3]]; };
  if (shared == 0)
    return triangles_meet(corner(ts, 0), corner(ts, 1), corner(ts, 2), corner(tt, 0), corner(tt, 1), corner(tt, 2));
  if (shared == 1) {
    const Vec3 &p = corner(ts, ks), &a = corner(ts, ks + 1), &b = corner(ts, ks + 2);
    const Vec3 &c = corner(tt, kt + 1), &d = corner(tt, kt + 2);
    // One wholly on one side of the other's plane: they meet at p only.
    const int sa = orient3d(p, c, d, a), sb = orient3d(p, c, d, b);
    if (sa * sb > 0) return false;
    const int sc = orient3d(p, a, b, c), sd = orient3d(p, a, b, d);
    if (sc * sd > 0) return false;
    if (sa == 0 && sb == 0) {  // one plane: each lies in its corner at p, so they overlap where the corners do
      const int axis = flat_axis(p, c, d);
      return in_corner(p, c, d, a, axis) || in_corner(p, c, d, b, axis) || in_corner(p, a, b, c, axis) ||
             in_corner(p, a, b, d, axis);
    }
    return segment_meets_triangle(a, b, p, c, d) || segment_meets_triangle(c, d, p, a, b) ||
           edge_enters_corner(p, a, c, d) || edge_enters_corner(p, b, c, d) || edge_enters_corner(p, c, a, b) ||
           edge_enters_corner(p, d, a, b);
  }
  if (shared == 2) {
    // Folded onto each other: the third corners on one plane with the shared
    // edge, on the same side of it.
    int a = 0, b = 0;
    for (int k = 0; k < 3; ++k) {
      if (std::find(tt.begin(), tt.end(), ts[k]) == tt.end()) a = k;
      if (std::find(ts.begin(), ts.end(), tt[k]) == ts.end()) b = k;
    }
    const Vec3 &x = corner(ts, a + 1), &y = corner(ts, a + 2), &pa = corner(ts, a), &pb = corner(tt, b);
    if (orient3d(x, y, pa, pb) != 0) return false;
    const int axis = flat_axis(x, y, pa);
    return orient2d(x, y, pa, axis) * orient2d(x, y, pb, axis) > 0;
  }
  return true;  // the same three corners
}

Surface make_surface(std::vector<Vec3> vertices, std::vector<TriangleIndices> triangles) {
  Surface s;
  s.vertices = std::move(vertices);
  s.triangles = std::move(triangles);
  const std::size_t nv = s.vertices.size(), nt = s.triangles.size();
  if (nt < 4) throw SurfaceError("a closed surface needs at least 4 triangles, not " + std::to_string(nt));
  for (std::size_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.vertices[i][k]))
        throw SurfaceError("vertex " + std::to_string(i) + " has a coordinate that is not finite");
  std::vector<std::uint8_t> used(nv, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    const TriangleIndices& tri = s.triangles[t];
    if (const std::string why = triangle_index_problem(tri, nv); !why.empty())
      throw SurfaceError("triangle " + std::to_string(t) + " " + why);
    for (const std::uint32_t i : tri) used[i] = 1;
    const Vec3 &a = s.vertices[tri[0]], &b = s.vertices[tri[1]], &c = s.vertices[tri[2]];
    if (orient2d(a, b, c, 0) == 0 && orient2d(a, b, c, 1) == 0 && orient2d(a, b, c, 2) == 0)
      throw SurfaceError("triangle " + std::to_string(t) + " has no area (its corners are collinear)");
  }
  for (std::size_t i = 0; i < nv; ++i)
    if (!used[i]) throw SurfaceError("vertex " + std::to_string(i) + " is in no triangle");

  // Edges: every side of every triangle, sorted by its vertices.
  struct EdgeSide {
    std::uint32_t lo, hi, triangle, k;
    bool forward;  // runs lo -> hi
  };
  std::vector<EdgeSide> sides;
  sides.reserve(3 * nt);
  for (std::uint32_t t = 0; t < nt; ++t)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t i = s.triangles[t][k], j = s.triangles[t][(k + 1) % 3];
      sides.push_back({std::min(i, j), std::max(i, j), t, k, i < j});
    }
  std::sort(sides.begin(), sides.end(), [](const EdgeSide& x, const EdgeSide& y) {
    return std::tie(x.lo, x.hi, x.triangle) < std::tie(y.lo, y.hi, y.triangle);
  });
  s.triangle_edges.resize(nt);
  for (std::size_t k = 0; k < sides.size();) {
    std::size_t end = k;
    while (end < sides.size() && sides[end].lo == sides[k].lo && sides[end].hi == sides[k].hi) ++end;
    const EdgeSide &x = sides[k], &y = sides[k + 1 < end ? k + 1 : k];
    const std::string name = edge_name(x.lo, x.hi);
    if (end - k == 1)
      throw SurfaceError(name + " is in only one triangle (" + std::to_string(x.triangle) + "): the surface is not closed");
    if (end - k > 2) {
      std::string list;
      for (std::size_t m = k; m < end; ++m) list += (m > k ? ", " : "") + std::to_string(sides[m].triangle);
      throw SurfaceError(name + " is in " + std::to_string(end - k) + " triangles (" + list + "): the surface is not manifold");
    }
    if (x.forward == y.forward)
      throw SurfaceError("triangles " + std::to_string(x.triangle) + " and " + std::to_string(y.triangle) + " run " + name +
                         " the same way: their orientations disagree");
    const std::uint32_t e = static_cast<std::uint32_t>(s.edges.size());
    s.edges.push_back({x.lo, x.hi});
    s.edge_triangles.push_back(x.forward ? std::array{x.triangle, y.triangle} : std::array{y.triangle, x.triangle});
    s.triangle_edges[x.triangle][x.k] = e;
    s.triangle_edges[y.triangle][y.k] = e;
    k = end;
  }

  // One fan about every vertex: walking from triangle to triangle across the
  // edges at the vertex comes back having met all of them.
  std::vector<std::uint32_t> incident(nv, 0);
  for (const TriangleIndices& tri : s.triangles)
    for (const std::uint32_t i : tri) ++incident[i];
  std::vector<std::uint8_t> walked(nv, 0);
  // Per triangle corner, the fan run it lies in (fan_runs; kNoRun: none):
  // two triangles of one run need not be checked against each other.
  using Runs = std::array<std::uint32_t, 3>;
  std::vector<Runs> corner_runs(nt, Runs{kNoRun, kNoRun, kNoRun});
  std::uint32_t runs_made = 0;
  std::vector<std::uint32_t> fan;
  for (std::uint32_t t0 = 0; t0 < nt; ++t0)
    for (int k0 = 0; k0 < 3; ++k0) {
      const std::uint32_t v = s.triangles[t0][k0];
      if (walked[v]) continue;
      walked[v] = 1;
      std::uint32_t t = t0, count = 0;
      fan.clear();
      do {
        ++count;
        if (incident[v] >= kFanRunMinTriangles) fan.push_back(t);
        // The side of t that leaves v (v -> next): its other triangle comes next.
        const int k = corner_of(s.triangles[t], v);
        const std::uint32_t e = s.triangle_edges[t][k];
        t = s.edge_triangles[e][0] == t ? s.edge_triangles[e][1] : s.edge_triangles[e][0];
      } while (t != t0 && count <= incident[v]);
      if (count != incident[v])
        throw SurfaceError("vertex " + std::to_string(v) + " joins separate fans of triangles: the surface is not manifold there");
      if (!fan.empty()) {
        const std::vector<std::uint32_t> run = fan_runs(s, v, fan);
        for (std::size_t i = 0; i < fan.size(); ++i) {
          corner_runs[fan[i]][corner_of(s.triangles[fan[i]], v)] = runs_made + run[i];
        }
        runs_made += static_cast<std::uint32_t>(fan.size());
      }
    }

  s.vertex_edge_begin.assign(nv + 1, 0);
  for (const auto& e : s.edges) ++s.vertex_edge_begin[e[0] + 1], ++s.vertex_edge_begin[e[1] + 1];
  for (std::size_t i = 0; i < nv; ++i) s.vertex_edge_begin[i + 1] += s.vertex_edge_begin[i];
  s.vertex_edges.resize(2 * s.edges.size());
  {
    std::vector<std::uint32_t> next(s.vertex_edge_begin.begin(), s.vertex_edge_begin.end() - 1);
    for (std::uint32_t e = 0; e < s.edges.size(); ++e)
      for (const std::uint32_t v : s.edges[e]) s.vertex_edges[next[v]++] = e;
  }

  fit_boxes(s);
  std::vector<std::uint32_t> ids(nt);
  for (std::uint32_t t = 0; t < nt; ++t) ids[t] = t;
  build_box_tree(s.triangle_boxes, ids, s.tree);
  s.box = s.tree.nodes[0].box;

  // No two triangles meet but as they should. Pairs in one fan run are
  // decided already, and skipped a whole node pair at a time: each node keeps
  // the runs all its triangles share (a fan of 32,000 triangles would
  // otherwise be half a billion pairs).
  const auto common = [](const Runs& a, const Runs& b) {
    Runs out{kNoRun, kNoRun, kNoRun};
    for (int k = 0; k < 3; ++k)
      if (a[k] != kNoRun && std::find(b.begin(), b.end(), a[k]) != b.end()) out[k] = a[k];
    return out;
  };
  const auto share = [](const Runs& a, const Runs& b) {
    for (const std::uint32_t x : a)
      if (x != kNoRun && std::find(b.begin(), b.end(), x) != b.end()) return true;
    return false;
  };
  std::vector<Runs> node_runs(s.tree.nodes.size());
  for (std::size_t k = s.tree.nodes.size(); k-- > 0;) {  // children come after their parent
    const BoxTree::Node& n = s.tree.nodes[k];
    if (n.count) {
      node_runs[k] = corner_runs[s.tree.items[n.first]];
      for (std::uint32_t i = n.first + 1; i < n.first + n.count; ++i)
        node_runs[k] = common(node_runs[k], corner_runs[s.tree.items[i]]);
    } else {
      node_runs[k] = common(node_runs[n.left], node_runs[n.right]);
    }
  }
  overlapping_items(
      s.tree, s.tree,
      [&](std::uint32_t i, std::uint32_t j) {
        if (i < j && !share(corner_runs[i], corner_runs[j]) && triangles_clash(s, i, j))
          throw SurfaceError("triangles " + std::to_string(i) + " and " + std::to_string(j) +
                             " intersect: the surface crosses itself");
      },
      [&](std::uint32_t n, std::uint32_t m) { return share(node_runs[n], node_runs[m]); });
  check_volume_resolved(s);
  const MassProperties m = mass_properties(s);
  s.volume = m.volume, s.centroid = m.centroid;
  if (!(s.volume > 0 && s.volume < std::numeric_limits<Real>::infinity())) {
    char size[32];
    std::snprintf(size, sizeof size, "%.3g", std::fmax(max_abs(s.box.lo), max_abs(s.box.hi)));
    throw SurfaceError(std::string("its volume is beyond the range of double precision (coordinates up to ") + size +
                       "): give the surface in other units");
  }
  check_shells_nest(s);
  s.deep = deep_points_slot(s);
  return s;
}

Surface moved(const Surface& surface, const Transform& pose) {
  Surface s;
  move_into(surface, pose, s);
  return s;
}

void move_into(const Surface& surface, const Transform& pose, Surface& s) {
  s = surface;
  s.deep.reset();  // its deep points lie in the surface's frame
  repose(surface, pose, s);
}

void repose(const Surface& surface, const Transform& pose, Surface& s) {
  for (std::size_t v = 0; v < s.vertices.size(); ++v) s.vertices[v] = apply(pose, surface.vertices[v]);
  s.centroid = apply(pose, surface.centroid);
  fit_boxes(s);
  refit_box_tree(s.tree, s.triangle_boxes);
  s.box = s.tree.nodes[0].box;
}

Surface box_surface(const Box& box) {
  const Vec3& h = box.half_extents;
  std::vector<Vec3> corners;
  for (int k = 0; k < 8; ++k) corners.push_back({k & 1 ? h.x : -h.x, k & 2 ? h.y : -h.y, k & 4 ? h.z : -h.z});
  return polytope_surface(make_polytope(corners));
}

Surface polytope_surface(const Polytope& polytope) {
  const PolytopeData& d = *polytope.data;
  if (d.triangles.empty()) throw SurfaceError("a flat polytope bounds no solid");
  return make_surface(std::vector<Vec3>(d.vertices.begin(), d.vertices.end()),
                      std::vector<TriangleIndices>(d.triangles.begin(), d.triangles.end()));
}

std::shared_ptr<const Surface> hull_surface(const Polytope& polytope) {
  HullSurfaceSlot* slot = polytope.data->surface_slot;
  if (!slot) return nullptr;
  std::call_once(slot->made, [&] {
    try {
      slot->surface = std::make_shared<const Surface>(polytope_surface(polytope));
    } catch (const SurfaceError&) {
      // (left null: its overlaps are clipped)
    }
  });
  return slot->surface;
}

Real winding_number(std::span<const Vec3> vertices, std::span<const TriangleIndices> triangles, const Vec3& p) {
  Real solid = 0;
  for (const TriangleIndices& t : triangles) {
    const Vec3 a = vertices[t[0]] - p, b = vertices[t[1]] - p, c = vertices[t[2]] - p;
    const Real la = length(a), lb = length(b), lc = length(c);
    const Real numerator = dot(a, cross(b, c));
    const Real denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    solid += 2 * std::atan2(numerator, denominator);
  }
  return solid / (4 * kPi);
}

MassProperties mass_properties(const Surface& s) {
  // Volume and first moments by tetrahedra from the middle of the box (for
  // precision far from the origin), then the inertia about the centroid.
  const Vec3 o = 0.5 * (s.box.lo + s.box.hi);
  Real volume = 0;
  Vec3 moment;
  for (const TriangleIndices& t : s.triangles) {
    const Vec3 a = s.vertices[t[0]] - o, b = s.vertices[t[1]] - o, c = s.vertices[t[2]] - o;
    const Real v = dot(a, cross(b, c)) / 6;
    volume += v;
    moment += v * (a + b + c) / 4;
  }
  const Vec3 centroid = volume > 0 ? o + moment / volume : o;
  return closed_surface_inertia(s.vertices, s.triangles, volume, centroid);
}

}  // namespace gjkdem
