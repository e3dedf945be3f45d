#include "oracle/overlap_oracle.hpp"

#include <cmath>

#include "gjkdem/shape/convex_hull.hpp"

namespace gjkdem::oracle {
namespace {

using Tris = std::vector<std::array<std::uint32_t, 3>>;

bool inside(const Vec3& p, const std::vector<Vec3>& v, const Tris& t, double tol) {
  for (const auto& f : t) {
    const Vec3 n = normalized(cross(v[f[1]] - v[f[0]], v[f[2]] - v[f[0]]));
    if (dot(n, p - v[f[0]]) > tol) return false;
  }
  return true;
}

// Points where the edges of (va, ta) cross the triangles of (vb, tb).
void edge_face_points(const std::vector<Vec3>& va, const Tris& ta, const std::vector<Vec3>& vb, const Tris& tb,
                      std::vector<Vec3>& out) {
  for (const auto& f : ta)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = va[f[k]], q = va[f[(k + 1) % 3]];
      for (const auto& g : tb) {
        const Vec3 a = vb[g[0]], b = vb[g[1]], c = vb[g[2]];
        const Vec3 n = cross(b - a, c - a);
        const double sp = dot(n, p - a), sq = dot(n, q - a);
        if ((sp > 0) == (sq > 0) || sp == sq) continue;
        const Vec3 x = p + (q - p) * (sp / (sp - sq));
        // Inside the triangle: same side of all three edges, or beyond one by
        // round-off. (An edge through a shared edge of two triangles could
        // miss both and its corner be lost; a point taken 1e-12 outside the
        // triangle lies outside the solid by less, which the hull forgives.)
        const double e0 = dot(cross(b - a, x - a), n), e1 = dot(cross(c - b, x - b), n), e2 = dot(cross(a - c, x - c), n);
        const double slack = -1e-12 * length(n) * (length(b - a) + length(c - b) + length(a - c)) * (max_abs(x) + length(b - a));
        if (e0 >= slack && e1 >= slack && e2 >= slack) out.push_back(x);
      }
    }
}

}  // namespace

OverlapTruth brute_force_overlap(const std::vector<Vec3>& va, const Tris& ta, const std::vector<Vec3>& vb, const Tris& tb) {
  double scale = 0;
  for (const Vec3& p : va) scale = std::fmax(scale, max_abs(p));
  const double tol = 1e-12 * scale;
  std::vector<Vec3> pts;
  for (const Vec3& p : va) if (inside(p, vb, tb, tol)) pts.push_back(p);
  for (const Vec3& p : vb) if (inside(p, va, ta, tol)) pts.push_back(p);
  edge_face_points(va, ta, vb, tb, pts);
  edge_face_points(vb, tb, va, ta, pts);
  OverlapTruth t;
  const ConvexHull h = convex_hull(pts);
  if (h.dimension != HullDimension::Solid) return t;
  const Vec3 ref = h.vertices[0];
  double vol6 = 0;
  Vec3 m;
  for (const auto& f : h.triangles) {
    const Vec3 a = h.vertices[f[0]] - ref, b = h.vertices[f[1]] - ref, c = h.vertices[f[2]] - ref;
    const double v6 = dot(a, cross(b, c));
    vol6 += v6;
    m += (a + b + c) * (v6 / 4);
  }
  t.volume = vol6 / 6;
  t.centroid = ref + m / vol6;
  return t;
}

}  // namespace gjkdem::oracle
