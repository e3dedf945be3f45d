#include "gjkdem/shape/shape_factories.hpp"

#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

Quat random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Quat q{g(rng), g(rng), g(rng), g(rng)};
    const Real n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (n > kRandomDirectionMinNorm) return normalized(q);
  }
}

namespace {

Shape scaled_polytope(std::vector<Vec3> points, Real diameter) {
  Real r = 0;
  for (const Vec3& p : points) r = std::fmax(r, length(p));
  for (Vec3& p : points) p *= diameter / (2 * r);
  return Shape{make_polytope(points)};
}

}  // namespace

Shape random_polyhedron(int vertices, Real diameter, std::mt19937_64& rng) {
  if (vertices < 4) throw std::invalid_argument("a random polyhedron needs at least 4 vertices");
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> stretch(0.7, 1.0);
  const Vec3 axis_scale{stretch(rng), stretch(rng), stretch(rng)};
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < vertices) {
    const Vec3 d{g(rng), g(rng), g(rng)};
    if (length(d) < kRandomDirectionMinNorm) continue;
    const Vec3 p = normalized(d);
    points.push_back({p.x * axis_scale.x, p.y * axis_scale.y, p.z * axis_scale.z});
  }
  return scaled_polytope(points, diameter);
}

Polytope box_polytope(const Box& box) {
  const Vec3 h = box.half_extents;
  std::vector<Vec3> corners;
  for (int k = 0; k < 8; ++k) corners.push_back({k & 1 ? h.x : -h.x, k & 2 ? h.y : -h.y, k & 4 ? h.z : -h.z});
  return make_polytope(corners);
}

Shape scaled(const Shape& shape, Real k) {
  Shape out = shape;
  out.margin = shape.margin * k;
  std::visit(
      [&](auto& core) {
        using T = std::decay_t<decltype(core)>;
        if constexpr (std::is_same_v<T, Segment>) {
          core.a *= k, core.b *= k;
        } else if constexpr (std::is_same_v<T, Triangle>) {
          for (Vec3& v : core.v) v *= k;
        } else if constexpr (std::is_same_v<T, Box>) {
          core.half_extents *= k;
        } else if constexpr (std::is_same_v<T, Ellipsoid> || std::is_same_v<T, Superellipsoid>) {
          core.radii *= k;
        } else if constexpr (std::is_same_v<T, Cylinder> || std::is_same_v<T, Cone>) {
          core.radius *= k, core.half_height *= k;
        } else if constexpr (std::is_same_v<T, Polytope>) {
          std::vector<Vec3> points(core.data->vertices.begin(), core.data->vertices.end());
          for (Vec3& p : points) p *= k;
          core = make_polytope(points);
        }  // Point: nothing but the margin
      },
      out.core);
  return out;
}

Shape platonic(const std::string& name, Real diameter) {
  const Real phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> p;
  if (name == "tetrahedron") {
    p = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  } else if (name == "cube") {
    for (int i = 0; i < 8; ++i) p.push_back({(i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0});
  } else if (name == "octahedron") {
    p = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  } else if (name == "icosahedron" || name == "dodecahedron") {
    for (int s1 : {-1, 1})
      for (int s2 : {-1, 1})
        if (name == "icosahedron") {
          p.push_back({0, Real(s1), s2 * phi});
          p.push_back({Real(s1), s2 * phi, 0});
          p.push_back({s2 * phi, 0, Real(s1)});
        } else {
          p.push_back({0, s1 / phi, s2 * phi});
          p.push_back({s1 / phi, s2 * phi, 0});
          p.push_back({s2 * phi, 0, s1 / phi});
        }
    if (name == "dodecahedron")
      for (int i = 0; i < 8; ++i) p.push_back({(i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0});
  } else {
    throw std::invalid_argument("unknown platonic solid '" + name +
                                "' (tetrahedron, cube, octahedron, dodecahedron or icosahedron)");
  }
  return scaled_polytope(p, diameter);
}

}  // namespace gjkdem
