// Overlap region of two convex shapes. Polytope-like cores are clipped: A's
// faces are cut by each face plane of B in turn (Sutherland-Hodgman on every
// face polygon); the points where a plane cuts A's edges, with A's vertices that
// lie on it, close the cut as a new face on B's boundary. Volume and centroid
// follow from the divergence theorem over the fan triangles of the faces, the
// area vectors from the faces' own area vectors. Everything runs in A's local
// frame and is mapped to the world once.
#include "gjkdem/contact/overlap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/shape/surface.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {


bool zero_volume(const Shape& s) {
  if (s.margin > 0) return false;
  if (std::holds_alternative<Point>(s.core) || std::holds_alternative<Segment>(s.core) ||
      std::holds_alternative<Triangle>(s.core))
    return true;
  if (const auto* p = std::get_if<Polytope>(&s.core)) return p->data->triangles.empty();
  if (const auto* b = std::get_if<Box>(&s.core))
    return !(b->half_extents.x > 0 && b->half_extents.y > 0 && b->half_extents.z > 0);
  return false;
}

/// Polytope-like shape without margin (clipped exactly when both are, and
/// neither has zero volume: overlap() tests that first).
bool clippable(const Shape& s) {
  return s.margin == 0 && (std::holds_alternative<Polytope>(s.core) || std::holds_alternative<Box>(s.core));
}

/// The part of space u . x >= from (working frame); all of it by default.
struct Beyond {
  Vec3 u;
  Real from = -std::numeric_limits<Real>::infinity();
};

/// Face polygons of a clippable core (a polytope's facets, coplanar
/// triangles merged), mapped by `to` (its local frame -> the working
/// frame): those with a corner in `keep`.
void append_faces(const Shape& s, const Transform& to, std::vector<Vec3>& pts, std::vector<int>& begin,
                  std::vector<unsigned char>& body, std::vector<Vec3>& normal, unsigned char tag,
                  const Beyond& keep = {}) {
  // `corner(k)` gives the polygon's k-th corner (local frame), `local_normal` its unit normal.
  auto add = [&](int corners, auto corner, const Vec3& local_normal) {
    const std::size_t at = pts.size();
    bool reaches = false;
    for (int k = 0; k < corners; ++k) {
      pts.push_back(apply(to, corner(k)));
      reaches = reaches || dot(keep.u, pts.back()) >= keep.from;
    }
    if (!reaches) {
      pts.resize(at);
      return;
    }
    begin.push_back(static_cast<int>(at));
    normal.push_back(apply_rotation(to, local_normal));
    body.push_back(tag);
  };
  if (const auto* p = std::get_if<Polytope>(&s.core)) {
    const PolytopeData& d = *p->data;
    for (std::size_t f = 0; f + 1 < d.facet_begin.size(); ++f) {
      const std::uint32_t* ids = d.facet_vertices.data() + d.facet_begin[f];
      add(static_cast<int>(d.facet_begin[f + 1] - d.facet_begin[f]), [&](int k) { return d.vertices[ids[k]]; },
          d.facet_normals[f]);
    }
  } else if (const auto* bx = std::get_if<Box>(&s.core)) {
    for (int axis = 0; axis < 3; ++axis)
      for (Real sign : {Real(1), Real(-1)}) {
        Vec3 c[4], n;
        box_face(*bx, axis, sign, c);
        n[axis] = sign;
        add(4, [&](int k) { return c[k]; }, n);
      }
  }
}

/// Face planes of a clippable core in the working frame. Coplanar triangles give
/// repeated planes; clipping by a repeat finds nothing outside and costs one scan.
using Plane = OverlapWorkspace::Plane;

/// Where the other body ends along a direction u (working frame): it lies
/// where u . x <= limit.
struct FarSide {
  Vec3 u;
  Real limit = std::numeric_limits<Real>::infinity();
};

/// The face planes of B (working frame `to`) that pass within `radius` of
/// `centre`: only they can cut a region inside that ball. False when the ball
/// lies wholly outside one of them (the region misses B). Polytopes are
/// tested in B's frame on unnormalised triangle normals (a triangle's plane
/// is exact, a merged facet's only within the hull's tolerance: a needle's
/// then cut 4e-12 from a pair that only touches); only the planes kept are
/// normalised. A polytope's triangles wholly beyond `far` (where
/// the other body ends) are left out too: when B meets a half-space S, B's
/// part in S is cut by the planes of the faces that reach into S alone (a
/// point of S outside B leaves B, on the way from a point of B in S,
/// through a face that reaches into S, and stays beyond that face's
/// plane). On a shallow contact that keeps the few faces at the contact, of
/// the many planes that pass near it.
bool planes_near(const Shape& s, const Transform& to, const Vec3& centre, Real radius, std::vector<Plane>& planes,
                 const FarSide& far = {}) {
  planes.clear();
  if (const auto* p = std::get_if<Polytope>(&s.core)) {
    const auto& v = p->data->vertices;
    const Vec3 c = apply_inverse(to, centre);
    const Vec3 u = apply_inverse_rotation(to, far.u);  // u . x in B's frame, less the offset below
    const Real limit = far.limit - dot(far.u, to.translation);
    for (const auto& t : p->data->triangles) {
      const Vec3 a = v[t[0]];
      const Vec3 n = cross(v[t[1]] - a, v[t[2]] - a);
      const Real side = dot(n, c - a), reach_sq = radius * radius * dot(n, n);
      if (side * side >= reach_sq) {
        if (side <= 0) continue;  // the ball is inside this plane
        return false;             // ... wholly outside it
      }
      if (dot(u, a) > limit && dot(u, v[t[1]]) > limit && dot(u, v[t[2]]) > limit) continue;
      const Vec3 nw = normalized(apply_rotation(to, n));
      planes.push_back({nw, dot(nw, apply(to, a))});
    }
    return true;
  }
  if (const auto* b = std::get_if<Box>(&s.core)) {
    for (int axis = 0; axis < 3; ++axis)
      for (Real sign : {Real(1), Real(-1)}) {
        Vec3 local;
        local[axis] = sign;
        const Vec3 n = apply_rotation(to, local);
        planes.push_back({n, dot(n, to.translation) + b->half_extents[axis]});
        if (dot(n, centre) - planes.back().d > radius) return false;
      }
  }
  return true;
}

/// Every face plane of a clippable core in the working frame.
void planes_of(const Shape& s, const Transform& to, std::vector<Plane>& planes) {
  planes_near(s, to, {}, std::numeric_limits<Real>::infinity(), planes);
}

Vec3 polygon_area_vector(const Vec3* p, int n) {
  Vec3 a;
  for (int i = 1; i + 1 < n; ++i) a += cross(p[i] - p[0], p[i + 1] - p[0]);
  return a * 0.5;
}

// Whether a face that the plane cuts (points b0..b1, their distances to the
// plane in `side`) lies within `graze` of it. Parallel to the plane (the
// caller checks), such a face joins the plane's cap whole (two planes of coplanar
// triangles, one tilted by round-off). Cut, its crossings would come from
// differences of round-off: corners 1e-9 apart that stand for one point
// moved them 3e-4 apart, the face and the cap took different ones, and the
// surface opened. The volume moves by less than graze times the face's area.
bool grazes(const std::vector<Real>& side, int b0, int b1, Real graze) {
  for (int i = b0; i < b1; ++i)
    if (std::fabs(side[i]) > graze) return false;
  return true;
}

// The band within which a grazing face joins a cut: kOverlapGrazeRelTol of
// the pair's size, but never more than 10 kOverlapGrazeRelTol times the
// smaller body's volume over size^2: on a sliver 1e-12 thick the first
// alone would be the whole overlap (a centroid 1e3 times its tolerance off).
Real graze_band(Real size, Real smaller_volume) {
  const Real band = kOverlapGrazeRelTol * size, sliver = 10 * kOverlapGrazeRelTol * smaller_volume / (size * size);
  return sliver < band ? sliver : band;  // not fmin: a call into libm
}

// A clipped face (pts[start..]) with three or more points on the plane. The
// cap is the hull of every point on the plane, and a point within tol of it
// counts as on it; so where a face meets the plane at a grazing angle, the
// cap takes in a strip of the face, which, kept in the face as well, would
// count twice (a tessellated sphere's overlap came out 1.6e-4 too large).
// The face keeps only the ends of each run of points on the plane; a face
// wholly on it, facing its way, is left to the cap. What moves lies within
// tol of the plane.
void keep_run_ends(std::vector<Vec3>& pts, int start, const OverlapWorkspace::Plane& pl, Real tol, bool facing,
                   std::vector<unsigned char>& flags) {
  const int kept = static_cast<int>(pts.size()) - start;
  flags.resize(kept);
  bool all = true;
  for (int k = 0; k < kept; ++k) {
    flags[k] = std::fabs(dot(pl.n, pts[start + k]) - pl.d) <= tol;
    all = all && flags[k];
  }
  if (all) {
    if (facing) pts.resize(start);
    return;
  }
  if (kept < 3) return;
  int out = start;
  for (int k = 0; k < kept; ++k)
    if (!(flags[k] && flags[(k + kept - 1) % kept] && flags[(k + 1) % kept])) pts[out++] = pts[start + k];
  pts.resize(out);
}

// The cut of a plane through faces that each cross it once (their
// boundary leaves the kept side once, at its exit, and comes back once, at
// its entry, each a crossing or a corner on the plane; no edge lies on the
// plane), closed by following the faces: the face across an edge has that
// edge's crossing, bit for bit (clip computes it from the end inside), or
// the corner, as its entry where this face has its exit (a face that only
// touches the plane at a corner is left out: the faces either side of it
// meet at that corner), and the cut runs from each face's entry to its
// exit. One loop through every face (A closed), or one path (A's faces
// beyond B left out, append_faces: the cut then closes from the last exit
// to the first entry, as the hull of its points would) is appended to
// `out`, counter-clockwise about the plane's normal; false for anything
// else, which the hull closes. Quadratic in the faces: long cuts (big
// hulls) go to the hull. (The hull alone cost a DEM step 3% more.)
bool chain_cut(const Vec3* entry, const Vec3* exit, int n, int* next, std::vector<Vec3>& out) {
  if (n < 2 || n > 64) return false;
  std::uint64_t has_prev = 0;
  int ends = 0, last = 0;
  for (int k = 0; k < n; ++k) {
    next[k] = -1;
    for (int j = 0; j < n; ++j)
      if (entry[j] == exit[k]) {
        next[k] = j;
        break;
      }
    if (next[k] < 0) {
      ++ends, last = k;
    } else {
      if ((has_prev >> next[k]) & 1) return false;
      has_prev |= std::uint64_t{1} << next[k];
    }
  }
  if (ends > 1) return false;
  int first = 0;
  while (ends == 1 && ((has_prev >> first) & 1)) ++first;  // the path's first face
  // Every face once: a loop that comes back early leaves others in loops of their own.
  const std::size_t start = out.size();
  int at = first, count = 0;
  do {
    out.push_back(entry[at]);
    at = next[at];
    ++count;
  } while (at >= 0 && at != first && count < n);
  if (count == n && at == (ends == 1 ? -1 : first)) {
    if (ends == 1) out.push_back(exit[last]);
    return true;
  }
  out.resize(start);
  return false;
}

/// Clips A's faces (already in work.points[0]) by every plane; returns the
/// index of the buffer holding the result, or -1 when nothing is left.
int clip(OverlapWorkspace& w, const std::vector<OverlapWorkspace::Plane>& planes, Real tol, Real graze) {
  enum : unsigned char { kInside, kOutside, kCut };
  int cur = 0;
  for (const auto& pl : planes) {
    const int nxt = 1 - cur;
    const auto& src = w.points[cur];
    const auto& sb = w.face_begin[cur];
    const int faces = static_cast<int>(sb.size()), points = static_cast<int>(src.size());
    // Each point's distance to the plane, once (every point starts one edge
    // and ends another), and each face's place: wholly inside (copied as it
    // is), wholly beyond and not within the grazing band (dropped), or to
    // be cut (or to join the cap, when it grazes the plane).
    auto& side = w.side;
    auto& place = w.face_place;
    side.resize(src.size());
    place.resize(sb.size());
    bool any_out = false, any_in = false;
    for (int f = 0; f < faces; ++f) {
      const int b0 = sb[f], b1 = f + 1 < faces ? sb[f + 1] : points;
      Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
      for (int i = b0; i < b1; ++i) {
        const Real s = dot(pl.n, src[i]) - pl.d;
        side[i] = s;
        lo = s < lo ? s : lo;  // not fmin: a call into libm
        hi = s > hi ? s : hi;
      }
      place[f] = hi < -tol ? kInside : lo > tol && hi > graze ? kOutside : kCut;
      any_out |= hi > tol;
      any_in |= lo < -tol;
    }
    if (!any_out) continue;       // the plane misses the region
    if (!any_in) return -1;       // the region lies on or beyond the plane: no volume
    auto& dst = w.points[nxt];
    auto& db = w.face_begin[nxt];
    auto& dbody = w.face_body[nxt];
    auto& dn = w.face_normal[nxt];
    const auto& snormal = w.face_normal[cur];
    dst.clear(); db.clear(); dbody.clear(); dn.clear();
    w.cap.clear();
    if (w.cut_entry.size() < sb.size()) {
      w.cut_entry.resize(sb.size()), w.cut_exit.resize(sb.size()), w.cut_next.resize(sb.size());
    }
    int cuts = 0;       // faces the plane cuts
    bool clean = true;  // every cut face crosses the plane once (chain_cut)
    for (int f = 0; f < faces; ++f) {
      if (place[f] == kOutside) continue;
      const int b0 = sb[f], b1 = f + 1 < faces ? sb[f + 1] : points;
      const int start = static_cast<int>(dst.size());
      if (place[f] == kInside) {
        dst.insert(dst.end(), src.begin() + b0, src.begin() + b1);
        db.push_back(start);
        dbody.push_back(w.face_body[cur][f]);
        dn.push_back(snormal[f]);
        continue;
      }
      const std::size_t cap_start = w.cap.size();
      int on = 0;  // points kept on the plane (within tol, or crossings)
      int entries = 0, exits = 0;  // where the boundary comes back to the kept side, and leaves it
      Vec3 entry, exit;
      bool cut = false;
      for (int i = b0; i < b1; ++i) {
        const int j = i + 1 < b1 ? i + 1 : b0;
        const Vec3& p = src[i];
        const Vec3& q = src[j];
        const Real sp = side[i], sq = side[j];
        if (sp <= tol) {
          dst.push_back(p);
          if (sp >= -tol) {
            w.cap.push_back(p), ++on;
            if (sq > tol) ++exits, exit = p;
            clean = clean && !(sq >= -tol && sq <= tol);  // an edge on the plane
          }
        } else {
          cut = true;
          if (sq >= -tol && sq <= tol) ++entries, entry = q;
        }
        if ((sp < -tol && sq > tol) || (sp > tol && sq < -tol)) {
          // From the end inside, whichever way the face runs: the face on
          // the edge's other side gets the same bits, and the cap one point.
          const Vec3 x = sp < 0 ? p + (q - p) * (sp / (sp - sq)) : q + (p - q) * (sq / (sq - sp));
          dst.push_back(x);
          w.cap.push_back(x);
          ++on;
          if (sp < 0) ++exits, exit = x;
          else ++entries, entry = x;
        }
      }
      // A face that only touches the plane at a corner (entry and exit
      // that corner, or neither) adds no edge to the cut.
      if ((entries != 0 || exits != 0) && !(entries == 1 && exits == 1 && entry == exit)) {
        clean = clean && entries == 1 && exits == 1;
        w.cut_entry[cuts] = entry, w.cut_exit[cuts] = exit, ++cuts;
      }
      const Real facing = dot(snormal[f], pl.n);
      if (cut && facing > kSharedFaceCos && grazes(side, b0, b1, graze)) {
        dst.resize(start);
        w.cap.resize(cap_start);
        w.cap.insert(w.cap.end(), src.begin() + b0, src.begin() + b1);
        clean = false;
        continue;
      }
      if (on >= 3) keep_run_ends(dst, start, pl, tol, facing > 0, w.on_plane);
      if (static_cast<int>(dst.size()) - start >= 3) {
        db.push_back(start);
        dbody.push_back(w.face_body[cur][f]);
        dn.push_back(snormal[f]);
      } else {
        dst.resize(start);
      }
    }
    // Close the cut. Where every cut face crosses the plane once, by
    // following the faces' cut edges (chain_cut). Else by the convex hull of
    // the points on the plane, counter-clockwise about n. (A sort by angle
    // about their mean put two points 1e-9 apart in either order, and the
    // faces beside the cap met it along edges that were not its own.)
    // Points within tol of one another or of a hull edge are dropped.
    auto& cap = w.cap;
    const int cut_begin = static_cast<int>(dst.size());
    if (clean && chain_cut(w.cut_entry.data(), w.cut_exit.data(), cuts, w.cut_next.data(), dst)) {
      db.push_back(cut_begin);
      dbody.push_back(1);
      dn.push_back(pl.n);
    } else if (cap.size() >= 3) {
      Vec3 t1, t2;
      orthonormal_basis(pl.n, t1, t2);
      auto& flat = w.cap_flat;
      flat.clear();
      for (const Vec3& p : cap) flat.push_back({dot(p - cap[0], t1), dot(p - cap[0], t2)});
      w.cap_order.resize(3 * cap.size());
      const std::size_t corners = convex_hull_2d(flat, tol, w.cap_order);
      if (corners >= 3) {
        db.push_back(static_cast<int>(dst.size()));
        for (std::size_t k = 0; k < corners; ++k) dst.push_back(cap[w.cap_order[k]]);
        dbody.push_back(1);
        dn.push_back(pl.n);
      }
    }
    if (db.empty()) return -1;
    cur = nxt;
  }
  return cur;
}

// Volume and centroid of inner shapes with closed forms; false when unknown.
bool volume_of(const Shape& s, const Transform& pose, Real& vol, Vec3& centroid) {
  if (std::holds_alternative<Point>(s.core)) {
    vol = 4 * kPi / 3 * s.margin * s.margin * s.margin;
    centroid = pose.translation;
    return true;
  }
  if (const auto* seg = std::get_if<Segment>(&s.core)) {
    const Real r = s.margin, len = length(seg->b - seg->a);
    vol = kPi * r * r * len + 4 * kPi / 3 * r * r * r;
    centroid = apply(pose, (seg->a + seg->b) * 0.5);
    return true;
  }
  if (s.margin > 0) return false;
  if (const auto* b = std::get_if<Box>(&s.core)) {
    vol = 8 * b->half_extents.x * b->half_extents.y * b->half_extents.z;
    centroid = pose.translation;
    return true;
  }
  if (const auto* p = std::get_if<Polytope>(&s.core)) {
    vol = p->data->volume;
    centroid = apply(pose, p->data->centroid);
    return true;
  }
  return false;
}

// Corner points of a core made of points (polytope, box, triangle, segment,
// point), in world coordinates; false for curved cores.
bool core_points(const Shape& s, const Transform& pose, std::vector<Vec3>& out) {
  out.clear();
  if (std::holds_alternative<Point>(s.core)) out.push_back(pose.translation);
  else if (const auto* g = std::get_if<Segment>(&s.core)) out = {apply(pose, g->a), apply(pose, g->b)};
  else if (const auto* t = std::get_if<Triangle>(&s.core)) out = {apply(pose, t->v[0]), apply(pose, t->v[1]), apply(pose, t->v[2])};
  else if (const auto* p = std::get_if<Polytope>(&s.core)) for (const Vec3& v : p->data->vertices) out.push_back(apply(pose, v));
  else if (const auto* b = std::get_if<Box>(&s.core)) {
    for (int k = 0; k < 8; ++k)
      out.push_back(apply(pose, hadamard(b->half_extents, Vec3{k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0})));
  } else return false;
  return true;
}

Real distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 t = b - a;
  const Real tt = dot(t, t);
  Real u = tt > 0 ? dot(p - a, t) / tt : 0;
  u = std::clamp(u, Real(0), Real(1));
  return length(p - (a + t * u));
}

/// Is `inner` entirely inside `outer`? -1 when this cannot be decided exactly.
/// Uses the workspace's plane and point buffers (free outside clipping).
int contains(const Shape& outer, const Transform& po, const Shape& inner, const Transform& pi, Real tol,
             OverlapWorkspace& w) {
  if (clippable(outer)) {
    // Inside every face plane: the inner shape's support value stays below it.
    planes_of(outer, po, w.planes);
    for (const auto& pl : w.planes) {
      const Vec3 s = apply(pi, support(inner, apply_inverse_rotation(pi, pl.n)));
      if (dot(pl.n, s) - pl.d > tol) return 0;
    }
    return 1;
  }
  const bool point_core = std::holds_alternative<Point>(outer.core), seg_core = std::holds_alternative<Segment>(outer.core);
  std::vector<Vec3>& pts = w.cap;
  if ((point_core || seg_core) && core_points(inner, pi, pts)) {
    // Distance to a convex core is convex: its maximum over the inner core is at a corner.
    Real worst = 0;
    for (const Vec3& p : pts) {
      const Real d = point_core ? length(p - po.translation)
                                : distance_to_segment(p, apply(po, std::get<Segment>(outer.core).a),
                                                      apply(po, std::get<Segment>(outer.core).b));
      worst = std::fmax(worst, d);
    }
    return worst + inner.margin <= outer.margin + tol ? 1 : 0;
  }
  return -1;
}

// The region is closed, so S_A = -S_B, but each is a sum whose error grows
// with the areas summed: when a thin plate of B crosses a face of A, S_B
// is the difference of the plate's two large faces, which nearly cancel,
// and carries their clipping errors (on a sliver of tests/data/poly-hard,
// -S_B leant 1.5e-4 rad off S_A, which is exact to 1e-10). The normal
// weighs each by the other's summed area, so the better-conditioned sum
// leads: 2 (S_A Sum_B - S_B Sum_A) / (Sum_A + Sum_B), which is S_A - S_B when
// both sums are alike, and mirrors when A and B swap.
void finish_normal(OverlapResult& r, Real total_area, Real summed_a, Real summed_b) {
  const Real summed = summed_a + summed_b;
  const Vec3 s = summed > 0 ? (r.area_a * summed_b - r.area_b * summed_a) * (2 / summed) : r.area_a - r.area_b;
  r.has_normal = length(s) > kContactNormalRelTol * total_area;
  r.contact_normal = r.has_normal ? normalized(s) : Vec3{};
}

// A big solid polytope's boundary surface (hull_surface), else null.
std::shared_ptr<const Surface> big_hull_surface(const Shape& s) {
  const auto* p = std::get_if<Polytope>(&s.core);
  return p ? hull_surface(*p) : nullptr;
}

// The overlap of two big hulls as the overlap of their surfaces: the same
// region, found exactly, in the clip's terms. Its normal is S_A - S_B, and
// it has one unless one hull lies within the other (has_contact_area, the
// surface grains' rule).
OverlapResult overlap_of_surfaces(const std::shared_ptr<const Surface>& a, const Transform& pose_a,
                                  const std::shared_ptr<const Surface>& b, const Transform& pose_b,
                                  OverlapWorkspace& w) {
  OverlapResult r;
  Transform frame;
  const SurfaceOverlap o = posed_surface_overlap(a, pose_a, b, pose_b, w.surfaces, frame);
  if (!(o.volume > 0)) return r;
  r.status = OverlapStatus::Overlapping;
  r.volume = o.volume;
  r.centroid = apply(frame, o.centroid);
  r.area_a = apply_rotation(frame, o.area_a);
  r.area_b = apply_rotation(frame, o.area_b);
  r.contact_area = length(r.area_a);
  r.moment_a = apply_rotation(frame, o.area_moment_a) + cross(frame.translation, r.area_a);
  r.has_normal = has_contact_area(r.contact_area, r.volume);
  if (r.has_normal) {
    r.contact_normal = normalized(r.area_a - r.area_b);
    r.application_point = cross(r.area_a, r.moment_a) / dot(r.area_a, r.area_a);
    r.has_application_point = true;
  }
  return r;
}

}  // namespace

bool face_planes_near(const Shape& shape, const Transform& to, const Vec3& centre, Real radius,
                      std::vector<OverlapWorkspace::Plane>& planes) {
  return planes_near(shape, to, centre, radius, planes);
}

OverlapResult overlap(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                      OverlapWorkspace& w, GjkCache* cache) {
  OverlapResult r;
  const Real radius_a = bounding_radius(a), radius_b = bounding_radius(b);
  const Real size = 2 * (radius_a > radius_b ? radius_a : radius_b);
  const Real tol = kOverlapRelTol * size;
  w.result = -1;
  if (zero_volume(a) || zero_volume(b)) return r;  // Empty
  const bool clipped = clippable(a) && clippable(b);
  // Shapes apart, or that only touch (a rounded box and a sphere at distance
  // 0), share no volume, whatever their kind: the overlap is empty, not
  // unknown. (Clipping finds a mere touch empty itself.)
  if (clipped ? !intersect(a, pose_a, b, pose_b, cache)
              : classify_depth(a, pose_a, b, pose_b, tol) != DepthClass::Beyond)
    return r;

  if (clipped) {
    for (int k = 0; k < 2; ++k) {
      w.points[k].clear(); w.face_begin[k].clear(); w.face_body[k].clear(); w.face_normal[k].clear();
    }
    const Transform b_in_a = relative(pose_a, pose_b);
    // Clipping costs the planes that cut times what they cut, and on a
    // shallow contact each of B's planes keeps most of A. Along the line u
    // between the centroids, B lies behind its supporting plane: A's faces
    // wholly short of it are outside B and are never clipped. (The caps B's
    // planes then close are the hulls of fewer points, but every point they
    // lack lies short of the plane too, outside B; A's kept faces are cut
    // exactly as before, with no new vertices from the plane.) And A ends at
    // its own supporting plane: B's faces wholly beyond it are left out
    // (planes_near says why that leaves the region as it is).
    Real vol;
    Vec3 centroid_b, centroid_a;
    Real vol_a;
    volume_of(b, b_in_a, vol, centroid_b);
    volume_of(a, Transform::identity(), vol_a, centroid_a);
    const Real graze = graze_band(size, vol < vol_a ? vol : vol_a);
    FarSide a_ends;  // A lies where u . x <= limit: B's faces wholly beyond it are left out below
    Beyond b_begins;   // B lies where u . x >= from: A's faces wholly short of it are not clipped
    if (const Vec3 d = centroid_b - centroid_a; length(d) > tol) {
      const Vec3 u = normalized(d);
      a_ends = {u, dot(u, support(a, u)) + tol};
      b_begins = {u, dot(u, apply(b_in_a, support(b, apply_inverse_rotation(b_in_a, -u)))) - tol};
    }
    append_faces(a, Transform::identity(), w.points[0], w.face_begin[0], w.face_body[0], w.face_normal[0], 0, b_begins);
    if (w.face_begin[0].empty()) return r;
    // Then only B's planes that pass near what is left.
    Vec3 centre;
    for (const Vec3& p : w.points[0]) centre += p;
    centre /= static_cast<Real>(w.points[0].size());
    Real radius_sq = 0;
    for (const Vec3& p : w.points[0]) {
      const Real r_sq = length_sq(p - centre);
      radius_sq = r_sq > radius_sq ? r_sq : radius_sq;
    }
    const Real radius = std::sqrt(radius_sq);
    if (!planes_near(b, b_in_a, centre, radius + tol, w.planes, a_ends)) return r;
    // Big hulls deep in each other: each plane that cuts rewrites every kept
    // face, work that outgrows the surfaces' overlap, which follows the
    // triangles that cross.
    if (static_cast<double>(w.planes.size()) * static_cast<double>(w.points[0].size()) > kClipWorkBeyondSurfaces)
      if (const std::shared_ptr<const Surface> sa = big_hull_surface(a))
        if (const std::shared_ptr<const Surface> sb = big_hull_surface(b))
          return overlap_of_surfaces(sa, pose_a, sb, pose_b, w);
    // Planes that merely touch A (a face of A lies in them) cut nothing but mark
    // the faces on both boundaries (aligned, stacked bodies).
    w.touching.clear();
    std::erase_if(w.planes, [&](const Plane& pl) {
      const Real excess = dot(pl.n, support(a, pl.n)) - pl.d;
      if (std::fabs(excess) <= tol) w.touching.push_back(pl);
      return excess <= tol;
    });
    const int res = clip(w, w.planes, tol, graze);
    if (res < 0) return r;
    // A face of A lying in a touching plane of B, facing the same way, is on
    // both boundaries: tagged 2, it counts in the volume but in neither area
    // vector nor in Feng's moment.
    for (std::size_t f = 0; f < w.face_begin[res].size(); ++f) {
      if (w.face_body[res][f] != 0) continue;
      const int b0 = w.face_begin[res][f];
      const int b1 = f + 1 < w.face_begin[res].size() ? w.face_begin[res][f + 1] : static_cast<int>(w.points[res].size());
      for (const Plane& pl : w.touching) {
        if (!(dot(pl.n, w.face_normal[res][f]) > kSharedFaceCos)) continue;
        bool on = true;
        for (int i = b0; i < b1 && on; ++i) on = std::fabs(dot(pl.n, w.points[res][i]) - pl.d) <= tol;
        if (on) { w.face_body[res][f] = 2; break; }
      }
    }
    w.result = res;
    w.frame = pose_a;
    const auto& pts = w.points[res];
    const auto& fb = w.face_begin[res];
    const int faces = static_cast<int>(fb.size());
    const Vec3 ref = pts[0];
    Real vol6 = 0, total_area = 0, summed_a = 0, summed_b = 0;
    Vec3 moment, sa, sb, ma;
    for (int f = 0; f < faces; ++f) {
      const int b0 = fb[f], n = (f + 1 < faces ? fb[f + 1] : static_cast<int>(pts.size())) - b0;
      const Vec3* p = &pts[b0];
      for (int i = 1; i + 1 < n; ++i) {
        const Real v6 = dot(p[0] - ref, cross(p[i] - ref, p[i + 1] - ref));
        vol6 += v6;
        moment += (p[0] + p[i] + p[i + 1] - ref * 3) * (v6 / 4);
      }
      const Vec3 area = polygon_area_vector(p, n);
      const Real magnitude = length(area);
      total_area += magnitude;
      if (w.face_body[res][f] == 0) summed_a += magnitude;
      if (w.face_body[res][f] == 1) summed_b += magnitude;
      if (w.face_body[res][f] < 2) (w.face_body[res][f] == 0 ? sa : sb) += area;
      if (w.face_body[res][f] == 0) {  // Feng's moment: face centroid x area vector
        Vec3 c;
        Real weight = 0;
        for (int i = 1; i + 1 < n; ++i) {
          const Real t = length(cross(p[i] - p[0], p[i + 1] - p[0]));
          c += (p[0] + p[i] + p[i + 1]) * (t / 3);
          weight += t;
        }
        if (weight > 0) ma += cross(c / weight, area);
      }
    }
    r.faces = faces;
    if (!(vol6 > 0)) return r;
    r.status = OverlapStatus::Overlapping;
    r.volume = vol6 / 6;
    r.centroid = apply(pose_a, ref + moment / vol6);
    r.area_a = apply_rotation(pose_a, sa);
    r.area_b = apply_rotation(pose_a, sb);
    r.contact_area = length(sa);
    // M in world: R M + t x R S_A (the moment about the world origin).
    r.moment_a = apply_rotation(pose_a, ma) + cross(pose_a.translation, r.area_a);
    finish_normal(r, total_area, summed_a, summed_b);
    if (r.has_normal) {
      r.application_point = cross(r.area_a, r.moment_a) / dot(r.area_a, r.area_a);
      r.has_application_point = true;
    }
    return r;
  }

  // Two spheres: a lens of two spherical caps, exact.
  if (std::holds_alternative<Point>(a.core) && std::holds_alternative<Point>(b.core)) {
    const Vec3 axis_vec = pose_b.translation - pose_a.translation;
    const Real d = length(axis_vec), r1 = a.margin, r2 = b.margin;
    if (d > std::fabs(r1 - r2)) {
      const Vec3 axis = axis_vec / d;
      const Real h1 = r1 - (d * d + r1 * r1 - r2 * r2) / (2 * d);  // cap of A inside B
      const Real h2 = r2 - (d * d + r2 * r2 - r1 * r1) / (2 * d);  // cap of B inside A
      auto cap_volume = [](Real rad, Real h) { return kPi * h * h * (3 * rad - h) / 3; };
      auto cap_offset = [](Real rad, Real h) { return 3 * (2 * rad - h) * (2 * rad - h) / (4 * (3 * rad - h)); };
      const Real v1 = cap_volume(r1, h1), v2 = cap_volume(r2, h2);
      if (!(v1 + v2 > 0)) return r;
      r.status = OverlapStatus::Overlapping;
      r.volume = v1 + v2;
      r.centroid = ((pose_a.translation + axis * cap_offset(r1, h1)) * v1 +
                    (pose_b.translation - axis * cap_offset(r2, h2)) * v2) / r.volume;
      // Each cap's area vector is its base disc's: pi rho^2 along the axis.
      const Real rho_sq = std::fmax(Real(0), h1 * (2 * r1 - h1));
      r.area_a = axis * (kPi * rho_sq);
      r.area_b = -r.area_a;
      r.has_normal = rho_sq > 0;
      r.contact_normal = axis;
      return r;
    }
  }

  // One shape inside the other: the inner shape is the overlap.
  for (int k = 0; k < 2; ++k) {
    const Shape& outer = k ? a : b;
    const Shape& inner = k ? b : a;
    const Transform& po = k ? pose_a : pose_b;
    const Transform& pi = k ? pose_b : pose_a;
    Real vol;
    Vec3 c;
    if (contains(outer, po, inner, pi, tol, w) == 1 && volume_of(inner, pi, vol, c)) {
      r.status = vol > 0 ? OverlapStatus::Overlapping : OverlapStatus::Empty;
      r.volume = vol;
      r.centroid = c;
      return r;  // the surface is all on one boundary: no contact normal
    }
  }
  r.status = OverlapStatus::Unsupported;
  return r;
}

std::vector<OverlapTriangle> overlap_surface(const OverlapWorkspace& w) {
  std::vector<OverlapTriangle> out;
  if (w.result < 0) return out;
  const auto& pts = w.points[w.result];
  const auto& fb = w.face_begin[w.result];
  const int faces = static_cast<int>(fb.size());
  for (int f = 0; f < faces; ++f) {
    const int b0 = fb[f], b1 = f + 1 < faces ? fb[f + 1] : static_cast<int>(pts.size());
    for (int i = b0 + 1; i + 1 < b1; ++i)
      out.push_back({{apply(w.frame, pts[b0]), apply(w.frame, pts[i]), apply(w.frame, pts[i + 1])}, w.face_body[w.result][f]});
  }
  return out;
}

std::vector<std::pair<Vec3, Vec3>> intersection_line(const OverlapWorkspace& w, Real tol) {
  std::vector<std::pair<Vec3, Vec3>> out;
  if (w.result < 0) return out;
  const auto& pts = w.points[w.result];
  const auto& fb = w.face_begin[w.result];
  const auto& body = w.face_body[w.result];
  const int faces = static_cast<int>(fb.size());
  struct Edge { Vec3 p, q; int body; };
  std::vector<Edge> edges;
  for (int f = 0; f < faces; ++f) {
    const int b0 = fb[f], b1 = f + 1 < faces ? fb[f + 1] : static_cast<int>(pts.size());
    for (int i = b0; i < b1; ++i) {
      const Vec3 p = pts[i], q = pts[i + 1 < b1 ? i + 1 : b0];
      if (length(q - p) > tol) edges.push_back({p, q, body[f]});
    }
  }
  // An A edge whose reverse belongs to a B face lies on both surfaces.
  for (const Edge& e : edges) {
    if (e.body != 0) continue;
    for (const Edge& g : edges)
      if (g.body == 1 && length(g.p - e.q) <= tol && length(g.q - e.p) <= tol) {
        out.emplace_back(apply(w.frame, e.p), apply(w.frame, e.q));
        break;
      }
  }
  return out;
}

}  // namespace gjkdem
