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

// The Hertz law's radius of curvature of a shape without one of its own:
// that of the sphere of equal volume.
Real equivalent_sphere_radius(Real volume) { return std::cbrt(3 * volume / (4 * kPi)); }

// A surface grain's surface, and a compound's surface part, is one closed
// shell: a hollow grain's cavity or a detached piece would be left out of
// its contacts (a piece's overlap is taken from its outer shell).
void check_one_shell(const Surface& surface, const std::string& what) {
  UnionFind vertices;
  vertices.reset(surface.vertices.size());
  std::size_t shells = surface.vertices.size();
  for (const auto& [p, q] : surface.edges) shells -= vertices.join(p, q);
  if (shells != 1)
    throw std::invalid_argument(what + " is one closed shell; this surface has " + std::to_string(shells) +
                                " (a hollow, or separate pieces)");
}

}  // namespace

void make_hull_surface(const Shape& shape) {
  if (const Polytope* p = std::get_if<Polytope>(&shape.core)) static_cast<void>(hull_surface(*p));
}

ShapeTemplate make_template(const Shape& shape) {
  ShapeTemplate t;
  t.shape = shape;
  t.unit_mass = mass_properties(shape);
  t.principal = principal_axes(t.unit_mass.inertia);
  if (std::holds_alternative<Point>(shape.core) || std::holds_alternative<Segment>(shape.core)) t.curvature_radius = shape.margin;
  else t.curvature_radius = equivalent_sphere_radius(t.unit_mass.volume);
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

ShapeTemplate make_compound_template(std::span<const PlacedShape> parts, bool fixed,
                                     std::span<const PlacedSurface> surfaces) {
  std::vector<Vec3> corners;  // of every part, for the hull standing in for the compound
  for (const PlacedShape& p : parts) {
    const Tessellation tess = tessellate(p.shape, kCompoundHullDirections);
    for (const Vec3& v : tess.polytope.data->vertices) corners.push_back(apply(p.pose, v));
  }
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    check_one_shell(*surfaces[k].surface, "surface part " + std::to_string(parts.size() + k) + " of a compound");
    for (const Vec3& v : surfaces[k].surface->vertices) corners.push_back(apply(surfaces[k].pose, v));
  }
  const Shape hull{make_polytope(corners)};
  ShapeTemplate t = fixed ? make_wall_template(hull) : ShapeTemplate{};
  std::vector<MassProperties> each;
  std::vector<Transform> poses;
  if (!fixed) {
    for (const PlacedShape& p : parts) each.push_back(mass_properties(p.shape)), poses.push_back(p.pose);
    for (const PlacedSurface& p : surfaces) each.push_back(mass_properties(*p.surface)), poses.push_back(p.pose);
    t.shape = hull;
    t.unit_mass = union_mass_properties(each, poses);
    t.principal = principal_axes(t.unit_mass.inertia);
    t.curvature_radius = equivalent_sphere_radius(t.unit_mass.volume);
  }
  t.reach = 0;
  for (std::size_t k = 0; k < parts.size() + surfaces.size(); ++k) {
    TemplatePart part;
    if (k < parts.size()) {
      const PlacedShape& p = parts[k];
      part.shape = p.shape;
      part.pose = p.pose;
      part.radius = bounding_radius(p.shape);
      if (!fixed) {
        const ShapeTemplate alone = make_template(p.shape);
        part.curvature_radius = alone.curvature_radius;
        part.volume = alone.unit_mass.volume;
      }
    } else {
      const PlacedSurface& p = surfaces[k - parts.size()];
      part.shape = Shape{make_polytope(p.surface->vertices)};
      part.pose = p.pose;
      part.radius = bounding_radius(part.shape);
      part.surface = p.surface;
      part.surface_grain = true;
      if (!fixed) {
        part.volume = each[k].volume;
        part.curvature_radius = equivalent_sphere_radius(part.volume);
      }
    }
    if (fixed) part.curvature_radius = std::numeric_limits<Real>::infinity();
    t.reach = std::fmax(t.reach, length(part.pose.translation - t.unit_mass.centroid) + part.radius);
    t.parts.push_back(std::move(part));
  }
  return t;
}

ShapeTemplate make_surface_template(std::shared_ptr<const Surface> surface, bool fixed) {
  check_one_shell(*surface, "a surface grain");
  const Shape hull{make_polytope(surface->vertices)};
  ShapeTemplate t = fixed ? make_wall_template(hull) : make_template(hull);
  if (!fixed) {
    t.unit_mass = mass_properties(*surface);
    t.principal = principal_axes(t.unit_mass.inertia);
    t.curvature_radius = equivalent_sphere_radius(t.unit_mass.volume);
    t.reach = 0;
    for (const Vec3& v : surface->vertices) t.reach = std::fmax(t.reach, length(v - t.unit_mass.centroid));
  }
  t.surface_grain = true;
  t.surface = std::move(surface);
  return t;
}

ShapeTemplate make_shell_template(std::shared_ptr<const Shell> shell, bool fixed) {
  const Shape hull{make_polytope(shell->vertices), shell->margin};
  ShapeTemplate t = make_wall_template(hull);
  if (!fixed) {
    t.unit_mass = shell->mass;
    t.principal = principal_axes(t.unit_mass.inertia);
    t.curvature_radius = std::sqrt(shell->area / (4 * kPi));
    t.reach = 0;
    for (const Vec3& v : shell->vertices) t.reach = std::fmax(t.reach, length(v - t.unit_mass.centroid) + shell->margin);
  }
  t.shell = std::move(shell);
  return t;
}

bool holds_surface(const ShapeTemplate& t) noexcept {
  const std::uint32_t parts = t.parts.empty() ? 1 : static_cast<std::uint32_t>(t.parts.size());
  for (std::uint32_t k = 0; k < parts; ++k)
    if (part_kind(t, k) == PartKind::Surface || part_kind(t, k) == PartKind::Shell) return true;
  return false;
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
