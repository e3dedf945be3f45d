#pragma once
// Expanding Polytope Algorithm (van den Bergen 2001, "Proximity queries and
// penetration depth computation on 3D game objects"): starting from a polytope
// inside A - B that holds the origin, repeatedly push out the face closest to the
// origin to the support point along its normal, until that support point adds
// no more than the tolerance. The closest face then lies on the boundary of
// A - B and gives depth, normal and (barycentrically) the witness points.
//
// Departures: fixed-size buffers on the stack (no heap; full buffers end the
// search with the best face so far and status OutOfMemory); the horizon is
// found by a depth-first walk over face adjacency; new faces are linked to each
// other by matching shared vertices, so no particular horizon order is assumed;
// a starting simplex of fewer than four points (touching contacts) is grown by
// support points away from its affine hull, and a flat A - B is reported as
// Degenerate with depth 0.
#include <limits>

#include "gjk_impl.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::detail {

struct EpaOutput {
  EpaStatus status = EpaStatus::Converged;
  Real depth = 0;
  Vec3 normal;        ///< unit, outward normal of A - B at the closest boundary point (frame A)
  Vec3 witness_a, witness_b;
  int iterations = 0;
};

struct EpaFace {
  int v[3];
  int adj[3];       // face across edge (v[k], v[k+1])
  int adj_edge[3];  // that edge's index in the neighbour
  Vec3 normal;      // unit, outward; zero for a degenerate face
  Real dist;        // normal . v[0]; +inf for a degenerate face (never the closest)
  bool obsolete;
};

/// Fixed-capacity storage left uninitialised: EPA writes each slot before
/// reading it, and zero-filling ~60 KiB per query would cost more than EPA.
template <class T, int N>
struct RawArray {
  union { T data[N]; };
  RawArray() noexcept {}
  T& operator[](int i) noexcept { return data[i]; }
  const T& operator[](int i) const noexcept { return data[i]; }
};

struct EpaPolytope {
  RawArray<SupportPoint, kEpaMaxVertices> verts;
  RawArray<EpaFace, kEpaMaxFaces> faces;
  int num_verts = 0;
  int num_faces = 0;
  RawArray<int, kEpaMaxFaces> free_faces;
  int num_free = 0;
  struct HorizonEdge { int face, edge; };
  RawArray<HorizonEdge, kEpaMaxFaces> horizon;
  int num_horizon = 0;

  int new_face(int a, int b, int c) noexcept {
    int f;
    if (num_free > 0) f = free_faces[--num_free];
    else if (num_faces < kEpaMaxFaces) f = num_faces++;
    else return -1;
    EpaFace& face = faces[f];
    face.v[0] = a; face.v[1] = b; face.v[2] = c;
    face.obsolete = false;
    const Vec3 n = cross(verts[b].w - verts[a].w, verts[c].w - verts[a].w);
    const Real len = length(n);
    if (len > 0) {
      face.normal = n / len;
      // Average the plane offset over the three vertices: less biased by any one.
      face.dist = (dot(face.normal, verts[a].w) + dot(face.normal, verts[b].w) + dot(face.normal, verts[c].w)) / 3;
    } else {
      face.normal = {};
      face.dist = std::numeric_limits<Real>::infinity();
    }
    return f;
  }

  void link(int f, int e, int g, int h) noexcept {
    faces[f].adj[e] = g; faces[f].adj_edge[e] = h;
    faces[g].adj[h] = f; faces[g].adj_edge[h] = e;
  }

  bool sees(const EpaFace& face, const Vec3& w) const noexcept {
    if (!(face.dist < std::numeric_limits<Real>::infinity())) {
      // Degenerate face: visible when w lies off the line of its longest edge side.
      return true;
    }
    return dot(face.normal, w) - face.dist > 0;
  }

  // Depth-first walk from face f (entered across edge e): visible faces become
  // obsolete; the first invisible face on each path contributes a horizon edge.
  bool silhouette(int f, int e, const Vec3& w) noexcept {
    EpaFace& face = faces[f];
    if (face.obsolete) return true;
    if (!sees(face, w)) {
      if (num_horizon >= kEpaMaxFaces) return false;
      horizon[num_horizon++] = {f, e};
      return true;
    }
    face.obsolete = true;
    free_faces[num_free++] = f;
    return silhouette(face.adj[(e + 1) % 3], face.adj_edge[(e + 1) % 3], w) &&
           silhouette(face.adj[(e + 2) % 3], face.adj_edge[(e + 2) % 3], w);
  }

  int closest_face() const noexcept {
    int best = -1;
    Real best_dist = std::numeric_limits<Real>::infinity();
    for (int f = 0; f < num_faces; ++f)
      if (!faces[f].obsolete && faces[f].dist < best_dist) { best_dist = faces[f].dist; best = f; }
    return best;
  }
};

/// Barycentric witnesses of the point of face f closest to the origin, set
/// about their midpoint `out.depth` apart along `out.normal` (both set first).
/// Where the origin's foot falls outside the face (a curved shape's EPA faces,
/// tied within the tolerance, turn from one to the next), the nearest point
/// of the face lies off its normal: the pair leant 0.0037 rad off a shallow
/// ellipsoid contact. Each witness moves by half that gap,
/// sqrt(|w|^2 - depth^2) / 2, a small part of the depth.
inline void face_witnesses(const EpaPolytope& poly, const EpaFace& face, EpaOutput& out) noexcept {
  const Vec3 w[3] = {poly.verts[face.v[0]].w, poly.verts[face.v[1]].w, poly.verts[face.v[2]].w};
  SubSimplex r;
  closest_on_triangle(w, 0, 1, 2, r);
  Vec3 a, b;
  for (int k = 0; k < 3; ++k) {
    a += poly.verts[face.v[k]].a * r.lambda[k];
    b += poly.verts[face.v[k]].b * r.lambda[k];
  }
  const Vec3 mid = (a + b) * 0.5;
  out.witness_a = mid + out.normal * (out.depth * 0.5);
  out.witness_b = mid - out.normal * (out.depth * 0.5);
}

/// Grows the GJK simplex (which holds the origin, possibly on its boundary) to a
/// tetrahedron with support points away from its affine hull. Returns false when
/// A - B has no volume there (flat), leaving `normal` a normal of its plane.
template <class MD>
bool grow_to_tetrahedron(MD& md, Simplex& s, Real size, Vec3& flat_normal) noexcept {
  const Real eps = kEpaAbsTol * size;
  while (s.size < 4) {
    Vec3 dirs[6];
    int nd = 0;
    if (s.size == 1) {
      dirs[0] = {1, 0, 0}; dirs[1] = {-1, 0, 0}; dirs[2] = {0, 1, 0};
      dirs[3] = {0, -1, 0}; dirs[4] = {0, 0, 1}; dirs[5] = {0, 0, -1};
      nd = 6;
    } else if (s.size == 2) {
      Vec3 t1, t2;
      orthonormal_basis(normalized(s.p[1].w - s.p[0].w), t1, t2);
      dirs[0] = t1; dirs[1] = -t1; dirs[2] = t2; dirs[3] = -t2;
      nd = 4;
    } else {
      const Vec3 n = normalized(cross(s.p[1].w - s.p[0].w, s.p[2].w - s.p[0].w));
      dirs[0] = n; dirs[1] = -n;
      nd = 2;
      flat_normal = n;
    }
    Real best = eps;
    SupportPoint best_p{};
    for (int k = 0; k < nd; ++k) {
      const SupportPoint p = md.support(dirs[k]);
      Real off;  // distance of p from the affine hull of the simplex
      if (s.size == 1) off = length(p.w - s.p[0].w);
      else if (s.size == 2) {
        const Vec3 u = normalized(s.p[1].w - s.p[0].w), r = p.w - s.p[0].w;
        off = length(r - u * dot(r, u));
      } else off = std::fabs(dot(flat_normal, p.w - s.p[0].w));
      if (off > best) { best = off; best_p = p; }
    }
    if (!(best > eps)) {
      if (s.size < 3) {  // a point or segment: any normal of its line is a flat normal
        Vec3 t1, t2;
        orthonormal_basis(s.size == 2 ? normalized(s.p[1].w - s.p[0].w) : Vec3{0, 0, 1}, t1, t2);
        flat_normal = t1;
      }
      return false;
    }
    s.p[s.size] = best_p;
    s.lambda[s.size] = 0;
    ++s.size;
  }
  return true;
}

template <class MD>
EpaOutput epa(MD& md, Simplex s, Real size, const QuerySettings& st, EpaPolytope& poly) noexcept {
  EpaOutput out;
  Vec3 flat_normal{0, 0, 1};
  if (!grow_to_tetrahedron(md, s, size, flat_normal)) {
    out.status = EpaStatus::Degenerate;
    out.normal = flat_normal;
    simplex_witnesses(s, out.witness_a, out.witness_b);
    return out;
  }
  poly.num_verts = 4;
  poly.num_faces = 0;
  poly.num_free = 0;
  for (int k = 0; k < 4; ++k) poly.verts[k] = s.p[k];
  // Orient the tetrahedron: faces (0,1,2), (0,3,1), (1,3,2), (2,3,0) are outward
  // when vertex 3 lies below the plane of 0,1,2.
  if (dot(cross(poly.verts[1].w - poly.verts[0].w, poly.verts[2].w - poly.verts[0].w),
          poly.verts[3].w - poly.verts[0].w) > 0)
    std::swap(poly.verts[1], poly.verts[2]);
  poly.new_face(0, 1, 2);
  poly.new_face(0, 3, 1);
  poly.new_face(1, 3, 2);
  poly.new_face(2, 3, 0);
  poly.link(0, 0, 1, 2);
  poly.link(0, 1, 2, 2);
  poly.link(0, 2, 3, 2);
  poly.link(1, 0, 3, 1);
  poly.link(1, 1, 2, 0);
  poly.link(2, 1, 3, 0);

  int best = poly.closest_face();
  out.status = EpaStatus::MaxIterations;
  // The closest face's distance never falls as the polytope grows (it holds
  // the previous one). When round-off in sliver faces near a curved boundary
  // makes a face come out turned inside out, it does: a cylinder sunk 0.02
  // into a cone of size 4.5 converged to 1e-11 in 30 steps, then such a face
  // took over and depth 0 came out. Then the best face before it is the answer.
  // (Vertices are never removed, so a copy of that face stays valid.)
  Real floor = -std::numeric_limits<Real>::infinity();
  EpaFace before{};
  for (int it = 0; it < kMaxEpaIterations; ++it) {
    out.iterations = it + 1;  // `best` is the closest face (found before the loop and after each expansion)
    if (best < 0) break;
    const EpaFace& face = poly.faces[best];
    if (face.dist < floor - kEpaMonotoneSlack * size) {
      out.status = EpaStatus::MaxIterations;  // the best face before round-off took over
      out.depth = std::fmax(before.dist, Real(0));
      out.normal = before.normal;
      face_witnesses(poly, before, out);
      return out;
    }
    if (face.dist >= floor) {
      floor = face.dist;
      before = face;
    }
    const SupportPoint w = md.support(face.normal);
    const Real gap = dot(face.normal, w.w) - face.dist;
    if (gap <= st.epa_rel_tol * std::fabs(face.dist) + st.epa_abs_tol * size) {
      out.status = EpaStatus::Converged;
      break;
    }
    if (poly.num_verts >= kEpaMaxVertices) { out.status = EpaStatus::OutOfMemory; break; }
    const int wi = poly.num_verts++;
    poly.verts[wi] = w;
    // Remove what w sees, starting from the closest face (which it sees: gap > 0).
    poly.num_horizon = 0;
    poly.faces[best].obsolete = true;
    poly.free_faces[poly.num_free++] = best;
    bool ok = true;
    for (int e = 0; e < 3 && ok; ++e) ok = poly.silhouette(poly.faces[best].adj[e], poly.faces[best].adj_edge[e], w.w);
    // Need room for the new faces and a closed horizon loop.
    if (!ok || poly.num_horizon < 3 ||
        poly.num_free + (kEpaMaxFaces - poly.num_faces) < poly.num_horizon) {
      out.status = EpaStatus::OutOfMemory;
      break;
    }
    RawArray<int, kEpaMaxFaces> first_new;
    const int h = poly.num_horizon;
    for (int k = 0; k < h; ++k) {
      const auto [g, e] = poly.horizon[k];
      const EpaFace& old = poly.faces[g];
      const int f = poly.new_face(old.v[(e + 1) % 3], old.v[e], wi);
      poly.link(f, 0, g, e);
      first_new[k] = f;
    }
    // Edge 1 of a new face (v1 -> w) meets edge 2 (w -> v0) of the face whose v0 is our v1.
    for (int k = 0; k < h; ++k) {
      const int f = first_new[k];
      for (int m = 0; m < h; ++m) {
        const int g = first_new[m];
        if (poly.faces[g].v[0] == poly.faces[f].v[1]) { poly.link(f, 1, g, 2); break; }
      }
    }
    best = poly.closest_face();
  }
  if (best < 0) {  // cannot happen with a valid start; stay defined
    out.status = EpaStatus::Degenerate;
    simplex_witnesses(s, out.witness_a, out.witness_b);
    return out;
  }
  // A boundary face of A - B may be split into coplanar triangles; the origin
  // projects inside only one of them. Among faces tied with the closest (within
  // the tolerance), take the triangle that is truly closest to the origin.
  const Real tie = poly.faces[best].dist + st.epa_rel_tol * std::fabs(poly.faces[best].dist) + st.epa_abs_tol * size;
  Real best_tri_sq = std::numeric_limits<Real>::infinity();
  for (int f = 0; f < poly.num_faces; ++f) {
    const EpaFace& cand = poly.faces[f];
    if (cand.obsolete || cand.dist > tie) continue;
    const Vec3 w[3] = {poly.verts[cand.v[0]].w, poly.verts[cand.v[1]].w, poly.verts[cand.v[2]].w};
    SubSimplex r;
    closest_on_triangle(w, 0, 1, 2, r);
    if (r.dist_sq < best_tri_sq) { best_tri_sq = r.dist_sq; best = f; }
  }
  const EpaFace& face = poly.faces[best];
  out.depth = std::fmax(face.dist, Real(0));
  out.normal = face.normal;
  face_witnesses(poly, face, out);
  if (out.status == EpaStatus::Converged && out.depth <= st.touch_tol * size) out.status = EpaStatus::Touching;
  return out;
}

}  // namespace gjkdem::detail
