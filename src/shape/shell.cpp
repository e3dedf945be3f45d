#include "gjkdem/shape/shell.hpp"

#include <cmath>
#include <string>

namespace gjkdem {

Shell make_shell(std::vector<Vec3> vertices, std::vector<TriangleIndices> triangles, Real thickness) {
  if (!(thickness > 0) || !std::isfinite(thickness)) throw ShellError("the thickness must be > 0 and finite");
  if (triangles.empty()) throw ShellError("a shell needs at least one triangle");
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!is_finite(vertices[i])) throw ShellError("vertex " + std::to_string(i) + " is not finite");
  Shell s;
  s.margin = thickness / 2;
  const Vec3 grow{s.margin, s.margin, s.margin};
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (const std::string why = triangle_index_problem(triangles[t], vertices.size()); !why.empty())
      throw ShellError("triangle " + std::to_string(t) + " " + why);
    const Vec3 &a = vertices[triangles[t][0]], &b = vertices[triangles[t][1]], &c = vertices[triangles[t][2]];
    const Real area = 0.5 * length(cross(b - a, c - a));
    if (!(area > 0)) throw ShellError("triangle " + std::to_string(t) + " has no area");
    s.area += area;
    s.triangle_boxes.push_back({min(min(a, b), c) - grow, max(max(a, b), c) + grow});
  }
  std::vector<std::uint32_t> ids(triangles.size());
  for (std::uint32_t t = 0; t < ids.size(); ++t) ids[t] = t;
  build_box_tree(s.triangle_boxes, ids, s.tree);
  // Only the vertices of triangles: a stray one would touch what no triangle does.
  constexpr std::uint32_t kUnused = ~0u;
  std::vector<std::uint32_t> index(vertices.size(), kUnused);
  for (const TriangleIndices& t : triangles)
    for (const std::uint32_t v : t) index[v] = 0;
  for (std::size_t v = 0; v < vertices.size(); ++v)
    if (index[v] != kUnused) index[v] = static_cast<std::uint32_t>(s.vertices.size()), s.vertices.push_back(vertices[v]);
  for (TriangleIndices& t : triangles)
    for (std::uint32_t& v : t) v = index[v];
  s.triangles = std::move(triangles);
  s.mass = mass_properties(s);
  return s;
}

MassProperties mass_properties(const Shell& s) {
  // About the middle of the box (for precision far from the origin): each
  // triangle's second moment of area, A/12 (a a^T + b b^T + c c^T + g g^T)
  // with g = a + b + c, times the thickness, plus its plate's own across
  // the thickness, A t^3 / 12 n n^T.
  const Aabb& box = s.tree.nodes[0].box;
  const Vec3 o = 0.5 * (box.lo + box.hi);
  const Real t = 2 * s.margin;
  MassProperties m;
  Vec3 moment;
  Real second[3][3] = {};
  for (const TriangleIndices& tri : s.triangles) {
    const Vec3 a = s.vertices[tri[0]] - o, b = s.vertices[tri[1]] - o, c = s.vertices[tri[2]] - o;
    const Vec3 n2 = cross(b - a, c - a);
    const Real area = 0.5 * length(n2);
    const Vec3 n = n2 / (2 * area), g = a + b + c;
    m.volume += area * t;
    moment += area * t * g / 3;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        second[i][j] += area * t / 12 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + g[i] * g[j]) +
                        area * t * t * t / 12 * n[i] * n[j];
  }
  const Vec3 c = moment / m.volume;
  m.centroid = o + c;
  Real trace = 0;
  for (int i = 0; i < 3; ++i) trace += second[i][i] - m.volume * c[i] * c[i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Real about_centroid = second[i][j] - m.volume * c[i] * c[j];
      m.inertia.row[i][j] = (i == j ? trace : 0) - about_centroid;
    }
  return m;
}

}  // namespace gjkdem
