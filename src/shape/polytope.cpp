#include "gjkdem/shape/polytope.hpp"

#include <stdexcept>

#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

Polytope make_polytope(std::span<const Vec3> points) {
  if (points.empty()) throw std::invalid_argument("polytope needs at least one point");
  for (const Vec3& q : points)
    if (!is_finite(q)) throw std::invalid_argument("polytope point is not finite");
  ConvexHull hull = convex_hull(points);
  auto data = std::make_shared<PolytopeData>();
  data->vertices = std::move(hull.vertices);
  for (const Vec3& v : data->vertices) data->radius = std::fmax(data->radius, length(v));
  const auto n = data->vertices.size();
  if (hull.dimension == HullDimension::Solid && hull.manifold && n > static_cast<std::size_t>(kHillClimbMinVertices)) {
    std::vector<std::vector<std::uint32_t>> nbr(n);
    for (const auto& t : hull.triangles)
      for (int k = 0; k < 3; ++k) nbr[t[k]].push_back(static_cast<std::uint32_t>(t[(k + 1) % 3]));
    data->adj_begin.reserve(n + 1);
    data->adj_begin.push_back(0);
    for (const auto& list : nbr) {
      data->adj.insert(data->adj.end(), list.begin(), list.end());
      data->adj_begin.push_back(static_cast<std::uint32_t>(data->adj.size()));
    }
  }
  return Polytope{std::move(data)};
}

}  // namespace gjkdem
