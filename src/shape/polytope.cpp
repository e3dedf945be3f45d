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
  if (hull.dimension == HullDimension::Solid) {
    // Volume and centroid by the divergence theorem over tetrahedra from the
    // bounding-box centre (the local origin for the query format's shapes).
    Real vol6 = 0;
    Vec3 moment;
    for (const auto& t : hull.triangles) {
      const Vec3 &p0 = data->vertices[t[0]], &p1 = data->vertices[t[1]], &p2 = data->vertices[t[2]];
      const Real v6 = dot(p0, cross(p1, p2));
      vol6 += v6;
      moment += (p0 + p1 + p2) * (v6 / 4);
      data->triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                                 static_cast<std::uint32_t>(t[2])});
    }
    data->volume = vol6 / 6;
    data->facet_normals = hull.facet_normals;
    data->facet_begin.push_back(0);
    for (const auto& facet : hull.facets) {
      for (int i : facet) data->facet_vertices.push_back(static_cast<std::uint32_t>(i));
      data->facet_begin.push_back(static_cast<std::uint32_t>(data->facet_vertices.size()));
    }
    data->centroid = vol6 > 0 ? moment / vol6 : Vec3{};
  } else {
    for (const Vec3& v : data->vertices) data->centroid += v / static_cast<Real>(n);
  }
  data->soa_stride = static_cast<int>((n + 1) / 2 * 2);
  data->soa.resize(3 * static_cast<std::size_t>(data->soa_stride));
  for (int i = 0; i < data->soa_stride; ++i) {
    const Vec3& v = data->vertices[static_cast<std::size_t>(i) < n ? i : 0];
    data->soa[i] = v.x;
    data->soa[data->soa_stride + i] = v.y;
    data->soa[2 * data->soa_stride + i] = v.z;
  }
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
    // Start table: the exact support vertex of each cell's centre direction.
    constexpr int res = kSupportMapResolution;
    data->start.resize(6 * res * res);
    for (int face = 0; face < 6; ++face)
      for (int iu = 0; iu < res; ++iu)
        for (int iv = 0; iv < res; ++iv) {
          const int axis = face / 2;
          Vec3 d;
          d[axis] = face % 2 ? -1 : 1;
          d[(axis + 1) % 3] = (iu + Real(0.5)) * 2 / res - 1;
          d[(axis + 2) % 3] = (iv + Real(0.5)) * 2 / res - 1;
          std::uint32_t best = 0;
          for (std::uint32_t i = 1; i < n; ++i)
            if (dot(data->vertices[i], d) > dot(data->vertices[best], d)) best = i;
          data->start[detail::support_map_cell(d)] = best;
        }
  }
  return Polytope{std::move(data)};
}

}  // namespace gjkdem
