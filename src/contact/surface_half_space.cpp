#include "gjkdem/contact/surface_half_space.hpp"

#include <algorithm>
#include <tuple>

#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

struct Sums {
  Real volume6 = 0;   // six times the volume
  Vec3 moment24;      // 24 times the first moment (cones from the origin)
  Vec3 area;          // vector area of the submerged surface
  Real depth12 = 0;   // -12 times the depth integral, before the dot with the normal
};

}  // namespace

SurfaceHalfSpace surface_half_space(const Surface& s, const Vec3& point, const Vec3& normal,
                                    std::vector<Real>& depth, std::vector<std::uint32_t>& parent) {
  SurfaceHalfSpace out;
  const std::size_t n = s.vertices.size();
  // Cones from the point of the plane nearest the box's middle: short arms.
  const Vec3 middle = 0.5 * (s.box.lo + s.box.hi);
  const Vec3 origin = middle - normal * dot(middle - point, normal);
  depth.resize(n);
  parent.resize(n);
  std::size_t below = 0;
  for (std::uint32_t v = 0; v < n; ++v) {
    depth[v] = -dot(s.vertices[v] - origin, normal);
    parent[v] = v;
    below += depth[v] > 0;
  }
  if (below == 0) return out;
  out.submerged = below == n;
  // Pieces: the submerged corners of a triangle are joined.
  for (const TriangleIndices& t : s.triangles) {
    std::uint32_t first = n;
    for (std::uint32_t v : t)
      if (depth[v] > 0) {
        if (first == n) first = v;
        else parent[find_root(parent, v)] = find_root(parent, first);
      }
  }
  std::vector<Sums> sums(n);
  Vec3 poly[4];
  Real d[4];
  for (const TriangleIndices& t : s.triangles) {
    // The triangle clipped to depth >= 0; a crossing point is made from its
    // edge's corners in index order, so both triangles of an edge agree.
    int m = 0;
    std::uint32_t root = n;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[k], j = t[(k + 1) % 3];
      if (depth[i] > 0) {
        poly[m] = s.vertices[i] - origin, d[m++] = depth[i];
        if (root == n) root = find_root(parent, i);
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
    Sums& sum = sums[root];
    for (int k = 1; k + 1 < m; ++k) {
      const Vec3 &a = poly[0], &b = poly[k], &c = poly[k + 1];
      const Real v6 = dot(a, cross(b, c));
      sum.volume6 += v6;
      sum.moment24 += v6 * (a + b + c);
      const Vec3 area = 0.5 * cross(b - a, c - a);
      sum.area += area;
      const Real da = d[0], db = d[k], dc = d[k + 1];
      sum.depth12 += dot(area, normal) * (da * da + db * db + dc * dc + da * db + db * dc + dc * da);
    }
  }
  const Real smallest = kPatchMinRelVolume * s.volume;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (!(depth[v] > 0) || find_root(parent, v) != v) continue;
    const Sums& sum = sums[v];
    if (!(sum.volume6 / 6 > smallest)) continue;
    HalfSpacePiece p;
    p.volume = sum.volume6 / 6;
    p.centroid = origin + sum.moment24 / (24 * p.volume);
    p.cut_area = -dot(sum.area, normal);
    p.depth_integral = -sum.depth12 / 12;
    out.pieces.push_back(p);
  }
  std::sort(out.pieces.begin(), out.pieces.end(), [](const HalfSpacePiece& x, const HalfSpacePiece& y) {
    return x.volume > y.volume || (x.volume == y.volume && std::tie(x.centroid.x, x.centroid.y, x.centroid.z) <
                                                               std::tie(y.centroid.x, y.centroid.y, y.centroid.z));
  });
  return out;
}

}  // namespace gjkdem
