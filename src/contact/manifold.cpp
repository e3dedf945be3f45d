#include "gjkdem/contact/manifold.hpp"

#include <algorithm>

namespace gjkdem {
namespace {

constexpr int kMaxFaceVertices = 64;  // larger facets fall back to a single point

struct Face {
  Vec3 v[kMaxFaceVertices];
  int n = 0;
  Vec3 normal;
};

bool polytope_like(const Shape& s) {
  return std::holds_alternative<Box>(s.core) ||
         (std::holds_alternative<Polytope>(s.core) && !std::get<Polytope>(s.core).data->facet_begin.empty());
}

/// The face of s (world) whose outward normal is most aligned with dir.
Face best_face(const Shape& s, const Transform& pose, const Vec3& dir) {
  Face f;
  const Vec3 local = apply_inverse_rotation(pose, dir);
  if (const auto* b = std::get_if<Box>(&s.core)) {
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::fabs(local[k]) > std::fabs(local[axis])) axis = k;
    const Real sign = local[axis] >= 0 ? 1 : -1;
    Vec3 corners[4];
    box_face(*b, axis, sign, corners);
    for (const Vec3& c : corners) f.v[f.n++] = apply(pose, c);
    Vec3 n;
    n[axis] = sign;
    f.normal = apply_rotation(pose, n);
    return f;
  }
  const PolytopeData& d = *std::get<Polytope>(s.core).data;
  std::size_t best = 0;
  for (std::size_t k = 1; k < d.facet_normals.size(); ++k)
    if (dot(d.facet_normals[k], local) > dot(d.facet_normals[best], local)) best = k;
  const std::uint32_t b0 = d.facet_begin[best], b1 = d.facet_begin[best + 1];
  if (b1 - b0 > static_cast<std::uint32_t>(kMaxFaceVertices)) return f;  // n = 0: unusable
  for (std::uint32_t k = b0; k < b1; ++k) f.v[f.n++] = apply(pose, d.vertices[d.facet_vertices[k]]);
  f.normal = apply_rotation(pose, d.facet_normals[best]);
  return f;
}

ContactManifold single_point(const PenetrationResult& c) {
  ContactManifold m;
  m.count = 1;
  m.points[0] = {(c.witness_a + c.witness_b) * 0.5, c.normal, c.intersect ? c.depth : -c.distance};
  return m;
}

// Keeps the four points spanning the largest area: the deepest, the farthest
// from it, the one making the largest triangle, then the one adding most area.
int reduce_to_four(ContactPoint* p, int n, const Vec3& axis) {
  if (n <= 4) return n;
  auto take = [&](int slot, int from) { std::swap(p[slot], p[from]); };
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (p[i].depth > p[best].depth) best = i;
  take(0, best);
  best = 1;
  for (int i = 2; i < n; ++i)
    if (length_sq(p[i].point - p[0].point) > length_sq(p[best].point - p[0].point)) best = i;
  take(1, best);
  best = 2;
  auto tri_area = [&](int i) { return std::fabs(dot(cross(p[1].point - p[0].point, p[i].point - p[0].point), axis)); };
  for (int i = 3; i < n; ++i)
    if (tri_area(i) > tri_area(best)) best = i;
  take(2, best);
  // Orient the triangle counter-clockwise about the axis, then add the point
  // lying farthest outside one of its edges.
  if (dot(cross(p[1].point - p[0].point, p[2].point - p[0].point), axis) < 0) std::swap(p[1], p[2]);
  auto outside = [&](int i) {
    Real most = 0;
    for (int e = 0; e < 3; ++e) {
      const Vec3 &u = p[e].point, &v = p[(e + 1) % 3].point;
      most = std::fmax(most, -dot(cross(v - u, p[i].point - u), axis));
    }
    return most;
  };
  best = 3;
  for (int i = 4; i < n; ++i)
    if (outside(i) > outside(best)) best = i;
  take(3, best);
  return 4;
}

}  // namespace

ContactManifold contact_manifold(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                                 const PenetrationResult& c) noexcept {
  if (!polytope_like(a) || !polytope_like(b) || a.margin > 0 || b.margin > 0) return single_point(c);
  const Face fa = best_face(a, pose_a, c.normal), fb = best_face(b, pose_b, -c.normal);
  if (fa.n == 0 || fb.n == 0) return single_point(c);
  const Real align_a = dot(fa.normal, c.normal), align_b = -dot(fb.normal, c.normal);
  if (std::fmax(align_a, align_b) < kManifoldFaceCos) return single_point(c);  // edge-edge or vertex contact
  // The better aligned face is the reference (A wins near-ties: no flip-flop).
  const bool ref_is_a = align_a >= align_b - kManifoldReferenceBias;
  const Face& ref = ref_is_a ? fa : fb;
  const Face& inc = ref_is_a ? fb : fa;
  // Clip the incident polygon by the side planes of the reference face.
  Vec3 buf[2][2 * kMaxFaceVertices + 8];
  int n = inc.n, cur = 0;
  for (int k = 0; k < n; ++k) buf[0][k] = inc.v[k];
  for (int e = 0; e < ref.n && n > 0; ++e) {
    const Vec3 r0 = ref.v[e], r1 = ref.v[(e + 1) % ref.n];
    const Vec3 side = cross(r1 - r0, ref.normal);  // outward, in the face's plane
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const Vec3 p = buf[cur][k], q = buf[cur][(k + 1) % n];
      const Real sp = dot(side, p - r0), sq = dot(side, q - r0);
      if (sp <= 0) buf[1 - cur][m++] = p;
      if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) buf[1 - cur][m++] = p + (q - p) * (sp / (sp - sq));
    }
    n = m;
    cur = 1 - cur;
  }
  // Keep the points below the reference plane (or within the separation).
  ContactPoint pts[2 * kMaxFaceVertices + 8];
  int count = 0;
  const Real gap = c.intersect ? 0 : c.distance;
  const Real slack = kOverlapRelTol * 2 * std::fmax(bounding_radius(a), bounding_radius(b));
  for (int k = 0; k < n; ++k) {
    const Vec3 p = buf[cur][k];
    const Real s = dot(ref.normal, p - ref.v[0]);  // < 0: inside the reference body
    if (s > gap + slack) continue;
    pts[count++] = {p - ref.normal * (s / 2), c.normal, -s};
  }
  if (count == 0) return single_point(c);
  ContactManifold m;
  m.count = reduce_to_four(pts, count, ref.normal);
  for (int k = 0; k < m.count; ++k) m.points[k] = pts[k];
  return m;
}

std::vector<ContactPoint> cluster_contacts(std::span<const ContactPoint> contacts, Real merge_distance, Real merge_cos,
                                           std::vector<int>* cluster_of) {
  struct Cluster {
    ContactPoint deepest;  // normal and depth of the cluster
    Vec3 anchor;           // first point: the merge test is against it
    Vec3 sum_wp, sum_p;
    Real sum_w = 0;
    int count = 0;
  };
  std::vector<Cluster> clusters;
  if (cluster_of) cluster_of->clear();
  for (const ContactPoint& c : contacts) {
    Cluster* hit = nullptr;
    for (Cluster& k : clusters)
      if (length(k.anchor - c.point) <= merge_distance && dot(k.deepest.normal, c.normal) >= merge_cos) { hit = &k; break; }
    if (!hit) {
      clusters.push_back({c, c.point, {}, {}, 0, 0});
      hit = &clusters.back();
    } else if (c.depth > hit->deepest.depth) {
      hit->deepest = c;
    }
    const Real w = std::fmax(c.depth, Real(0));
    hit->sum_wp += c.point * w;
    hit->sum_w += w;
    hit->sum_p += c.point;
    ++hit->count;
    if (cluster_of) cluster_of->push_back(static_cast<int>(hit - clusters.data()));
  }
  std::vector<ContactPoint> out;
  for (const Cluster& k : clusters) {
    ContactPoint p = k.deepest;
    p.point = k.sum_w > 0 ? k.sum_wp / k.sum_w : k.sum_p / static_cast<Real>(k.count);
    out.push_back(p);
  }
  return out;
}

}  // namespace gjkdem
