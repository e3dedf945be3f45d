#include "gjkdem/shape/tessellate.hpp"

#include <stdexcept>
#include <vector>

namespace gjkdem {

Tessellation tessellate(const Shape& shape, int directions) {
  if (directions < 8) throw std::invalid_argument("tessellate: need at least 8 directions");
  std::vector<Vec3> pts;
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& d : axes) pts.push_back(support(shape, d));
  const Real golden = kPi * (3 - std::sqrt(Real(5)));
  for (int i = 0; i < directions; ++i) {
    const Real z = 1 - 2 * (i + Real(0.5)) / directions;
    const Real r = std::sqrt(1 - z * z);
    pts.push_back(support(shape, {r * std::cos(golden * i), r * std::sin(golden * i), z}));
  }
  Tessellation t;
  t.polytope = make_polytope(pts);
  const PolytopeData& d = *t.polytope.data;
  for (std::size_t f = 0; f < d.facet_normals.size(); ++f) {
    const Vec3 n = d.facet_normals[f];
    const Real offset = dot(n, d.vertices[d.facet_vertices[d.facet_begin[f]]]);
    t.hausdorff_bound = std::fmax(t.hausdorff_bound, dot(n, support(shape, n)) - offset);
  }
  return t;
}

}  // namespace gjkdem
