#include "gjkdem/contact/surface_half_space.hpp"

#include <algorithm>
#include <tuple>

#include "gjkdem/tolerances.hpp"

namespace gjkdem {

SurfaceHalfSpace surface_half_space(const Surface& s, const Vec3& point, const Vec3& normal, HalfSpaceScratch& w) {
  SurfaceHalfSpace out;
  const std::size_t n = s.vertices.size();
  // Cones from the point of the plane nearest the box's middle: short arms.
  const Vec3 middle = 0.5 * (s.box.lo + s.box.hi);
  const Vec3 origin = middle - normal * dot(middle - point, normal);
  std::vector<Real>& depth = w.depth;
  depth.resize(n);
  std::size_t below = 0;
  for (std::uint32_t v = 0; v < n; ++v) {
    depth[v] = -dot(s.vertices[v] - origin, normal);
    below += depth[v] > 0;
  }
  if (below == 0) return out;
  out.submerged = below == n;
  // Pieces: the submerged corners of a triangle are joined.
  UnionFind& pieces = w.pieces;
  pieces.reset(n);
  for (const TriangleIndices& t : s.triangles) {
    std::uint32_t first = static_cast<std::uint32_t>(n);
    for (std::uint32_t v : t)
      if (depth[v] > 0) {
        if (first == n) first = v;
        else pieces.join(v, first);
      }
  }
  // Sums per piece root: six times the volume, 24 times the first moment
  // (cones from the origin), the cut face's area (minus the submerged vector
  // area along the normal: the piece is closed) and the depth integral.
  std::vector<HalfSpacePiece>& sums = w.sums;
  sums.assign(n, HalfSpacePiece{});
  Vec3 poly[4];
  Real d[4];
  for (const TriangleIndices& t : s.triangles) {
    // The triangle clipped to depth >= 0; a crossing point is made from its
    // edge's corners in index order, so both triangles of an edge agree.
    int m = 0;
    std::uint32_t root = static_cast<std::uint32_t>(n);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[k], j = t[(k + 1) % 3];
      if (depth[i] > 0) {
        poly[m] = s.vertices[i] - origin, d[m++] = depth[i];
        if (root == n) root = pieces.find(i);
      } else if (depth[i] == 0) {
        poly[m] = s.vertices[i] - origin, d[m++] = 0;
      }
      if ((depth[i] > 0 && depth[j] < 0) || (depth[i] < 0 && depth[j] > 0)) {
        const std::uint32_t lo = std::min(i, j), hi = std::max(i, j);
        const Real f = depth[lo] / (depth[lo] - depth[hi]);
        poly[m] = s.vertices[lo] - origin + f * (s.vertices[hi] - s.vertices[lo]);
        poly[m] -= normal * dot(poly[m], normal);  // on the plane
        d[m++] = 0;
      }
    }
    if (root == n) continue;  // nothing below the plane
    HalfSpacePiece& sum = sums[root];
    for (int k = 1; k + 1 < m; ++k) {
      const Vec3 &a = poly[0], &b = poly[k], &c = poly[k + 1];
      const Real v6 = dot(a, cross(b, c));
      sum.volume += v6;
      sum.centroid += v6 * (a + b + c);
      // Divergence theorem with F = -(depth^2 / 2) n: the integral of depth
      // over the piece is -1/12 sum (S_t . n)(d_a^2 + d_b^2 + d_c^2 + d_a d_b + d_b d_c + d_c d_a).
      const Real along = dot(0.5 * cross(b - a, c - a), normal);
      const Real da = d[0], db = d[k], dc = d[k + 1];
      sum.cut_area -= along;
      sum.depth_integral -= along * (da * da + db * db + dc * dc + da * db + db * dc + dc * da) / 12;
    }
  }
  const Real smallest = kPatchMinRelVolume * s.volume;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (!(depth[v] > 0) || pieces.find(v) != v) continue;
    HalfSpacePiece p = sums[v];
    p.volume /= 6;
    if (!(p.volume > smallest)) continue;
    p.centroid = origin + p.centroid / (24 * p.volume);
    out.pieces.push_back(p);
  }
  std::sort(out.pieces.begin(), out.pieces.end(), [](const HalfSpacePiece& x, const HalfSpacePiece& y) {
    return x.volume > y.volume || (x.volume == y.volume && std::tie(x.centroid.x, x.centroid.y, x.centroid.z) <
                                                               std::tie(y.centroid.x, y.centroid.y, y.centroid.z));
  });
  return out;
}

}  // namespace gjkdem
