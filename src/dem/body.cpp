#include "gjkdem/dem/body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gjkdem/math/union_find.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/tessellate.hpp"

namespace gjkdem::dem {
namespace {

// Support directions per curved part for the hull that bounds a compound.
constexpr int kCompoundHullDirections = 96;

}  // namespace

ShapeTemplate make_template(const Shape& shape) {
  ShapeTemplate t;
  t.shape = shape;
  t.unit_mass = mass_properties(shape);
  t.principal = principal_axes(t.unit_mass.inertia);
  if (std::holds_alternative<Point>(shape.core) || std::holds_alternative<Segment>(shape.core)) t.curvature_radius = shape.margin;
  else t.curvature_radius = std::cbrt(3 * t.unit_mass.volume / (4 * kPi));
  t.reach = bounding_radius(shape) + length(t.unit_mass.centroid);
  return t;
}

ShapeTemplate make_wall_template(const Shape& shape) {
  ShapeTemplate t;
  t.shape = shape;
  t.curvature_radius = std::numeric_limits<Real>::infinity();
  t.reach = bounding_radius(shape);
  return t;
}

ShapeTemplate make_compound_template(std::span<const PlacedShape> parts, bool fixed) {
  std::vector<Vec3> corners;  // of every part, for the hull standing in for the compound
  for (const PlacedShape& p : parts) {
    const Tessellation tess = tessellate(p.shape, kCompoundHullDirections);
    for (const Vec3& v : tess.polytope.data->vertices) corners.push_back(apply(p.pose, v));
  }
  const Shape hull{make_polytope(corners)};
  ShapeTemplate t = fixed ? make_wall_template(hull) : ShapeTemplate{};
  if (!fixed) {
    t.shape = hull;
    t.unit_mass = mass_properties(parts);
    t.principal = principal_axes(t.unit_mass.inertia);
    t.curvature_radius = std::cbrt(3 * t.unit_mass.volume / (4 * kPi));
  }
  t.reach = 0;
  for (const PlacedShape& p : parts) {
    TemplatePart part;
    part.shape = p.shape;
    part.pose = p.pose;
    part.radius = bounding_radius(p.shape);
    if (fixed) {
      part.curvature_radius = std::numeric_limits<Real>::infinity();
    } else {
      const ShapeTemplate alone = make_template(p.shape);
      part.curvature_radius = alone.curvature_radius;
      part.volume = alone.unit_mass.volume;
    }
    t.reach = std::fmax(t.reach, length(p.pose.translation - t.unit_mass.centroid) + part.radius);
    t.parts.push_back(std::move(part));
  }
  return t;
}

ShapeTemplate make_surface_template(std::shared_ptr<const Surface> surface, bool fixed) {
  // One closed shell: a hollow grain's cavity or a detached piece would be
  // left out of its contacts (a piece's overlap is taken from its outer shell).
  UnionFind vertices;
  vertices.reset(surface->vertices.size());
  std::size_t shells = surface->vertices.size();
  for (const auto& [p, q] : surface->edges) shells -= vertices.join(p, q);
  if (shells != 1)
    throw std::invalid_argument("a surface grain is one closed shell; this surface has " + std::to_string(shells) +
                                " (a hollow, or separate pieces)");
  const Shape hull{make_polytope(surface->vertices)};
  ShapeTemplate t = fixed ? make_wall_template(hull) : make_template(hull);
  if (!fixed) {
    t.unit_mass = mass_properties(*surface);
    t.principal = principal_axes(t.unit_mass.inertia);
    t.curvature_radius = std::cbrt(3 * t.unit_mass.volume / (4 * kPi));
    t.reach = 0;
    for (const Vec3& v : surface->vertices) t.reach = std::fmax(t.reach, length(v - t.unit_mass.centroid));
  }
  t.surface_grain = true;
  t.surface = std::move(surface);
  return t;
}

PartPose part_pose(const ShapeTemplate& t, const Body& b, std::uint32_t part) noexcept {
  const Transform pose = shape_pose(t, b);
  if (t.parts.empty()) return {&t.shape, pose};
  return {&t.parts[part].shape, compose(pose, t.parts[part].pose)};
}

Quat shape_orientation(const ShapeTemplate& t, const Body& b) noexcept {
  return b.orientation * conjugate(t.principal.rotation);
}

Transform shape_pose(const ShapeTemplate& t, const Body& b) noexcept {
  const Quat world_from_local = shape_orientation(t, b);
  return Transform::from(b.position - rotate(world_from_local, t.unit_mass.centroid), world_from_local);
}

std::size_t index_of_body(std::span<const Body> bodies, std::uint64_t id) noexcept {
  const auto at = std::lower_bound(bodies.begin(), bodies.end(), id, [](const Body& b, std::uint64_t v) { return b.id < v; });
  return at != bodies.end() && at->id == id ? static_cast<std::size_t>(at - bodies.begin()) : bodies.size();
}

}  // namespace gjkdem::dem
