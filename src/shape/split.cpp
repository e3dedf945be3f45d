#include "gjkdem/shape/split.hpp"

#include <cmath>
#include <array>
#include <stdexcept>
#include <vector>

#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem {
namespace {

// A side's points as a polytope, or none when they span no volume (the
// hull is not solid: make_polytope then leaves the volume 0).
std::optional<Polytope> solid_of(const std::vector<Vec3>& points) {
  if (points.size() < 4) return std::nullopt;
  Polytope p = make_polytope(points);
  if (!(p.data->volume > 0)) return std::nullopt;
  return p;
}

// The points of either side of the plane: each side's vertices and the
// crossings of the edges with their ends strictly on either side (each
// edge of the hull's triangles is met from its two triangles: taken from
// the one that runs it from the lower index; a diagonal of a facet crosses
// inside the cut polygon, so the hulls stay the same).
void side_points(const Polytope& polytope, const Vec3& normal, Real offset, std::vector<Vec3>& below,
                 std::vector<Vec3>& above) {
  const PolytopeData& d = *polytope.data;
  if (!is_finite(normal) || !(length(normal) > 0) || !std::isfinite(offset))
    throw std::invalid_argument("split_polytope: the plane's normal must be finite and not zero, its offset finite");
  if (!(d.volume > 0) || d.triangles.empty())
    throw std::invalid_argument("split_polytope: the polytope has no volume");
  // Signed distances in units of |normal|: the sign decides the side, the
  // ratio places a crossing on its edge.
  const std::size_t n = d.vertices.size();
  std::vector<Real> side(n);
  for (std::size_t i = 0; i < n; ++i) side[i] = dot(normal, d.vertices[i]) - offset;
  for (std::size_t i = 0; i < n; ++i) {
    if (side[i] <= 0) below.push_back(d.vertices[i]);
    if (side[i] >= 0) above.push_back(d.vertices[i]);
  }
  if (above.empty() || below.empty()) return;  // the plane misses the solid (or only touches it)
  for (const std::array<std::uint32_t, 3>& t : d.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[k], j = t[(k + 1) % 3];
      if (j <= i || !((side[i] < 0 && side[j] > 0) || (side[i] > 0 && side[j] < 0))) continue;
      const Real f = side[i] / (side[i] - side[j]);
      const Vec3 cross = d.vertices[i] + (d.vertices[j] - d.vertices[i]) * f;
      below.push_back(cross);
      above.push_back(cross);
    }
}

// Whether solid_of(points) holds a polytope, by its hull alone (the volume
// as make_polytope sums it).
bool spans_volume(const std::vector<Vec3>& points) {
  if (points.size() < 4) return false;
  const ConvexHull hull = convex_hull(points);
  if (hull.dimension != HullDimension::Solid) return false;
  Real vol6 = 0;
  for (const auto& t : hull.triangles) {
    const Vec3 &p0 = hull.vertices[t[0]], &p1 = hull.vertices[t[1]], &p2 = hull.vertices[t[2]];
    vol6 += dot(p0, cross(p1, p2));
  }
  return vol6 / 6 > 0;
}

}  // namespace

PolytopeSplit split_polytope(const Polytope& polytope, const Vec3& normal, Real offset) {
  std::vector<Vec3> below, above;
  side_points(polytope, normal, offset, below, above);
  if (above.empty() || below.empty()) {  // the plane misses the solid (or only touches it)
    PolytopeSplit whole;
    (above.empty() ? whole.below : whole.above) = polytope;
    return whole;
  }
  PolytopeSplit out{solid_of(below), solid_of(above)};
  if (!out.below && !out.above) throw std::logic_error("split_polytope: neither side of the cut holds volume");
  if (!out.below) out.above = polytope;  // a sliver below the hull's tolerance: no cut
  if (!out.above) out.below = polytope;
  return out;
}

std::optional<Polytope> polytope_below(const Polytope& polytope, const Vec3& normal, Real offset) {
  std::vector<Vec3> below, above;
  side_points(polytope, normal, offset, below, above);
  if (above.empty()) return polytope;
  if (below.empty()) return std::nullopt;
  std::optional<Polytope> part = solid_of(below);
  const bool above_solid = spans_volume(above);
  if (!part && !above_solid) throw std::logic_error("split_polytope: neither side of the cut holds volume");
  // A sliver above (no volume by the hull's tolerance, yet its corners may
  // stand well above the plane: a needle's tip) is pressed onto the plane,
  // not kept: a Voronoi cell keeping it pokes into its neighbour's cell.
  if (!above_solid) {
    const Real n2 = dot(normal, normal);
    for (const Vec3& p : above) below.push_back(p - normal * ((dot(normal, p) - offset) / n2));
    if (std::optional<Polytope> pressed = solid_of(below)) return pressed;
    return polytope;
  }
  return part;
}

}  // namespace gjkdem
