#include "gjkdem/dem/body.hpp"

#include <cmath>
#include <limits>

namespace gjkdem::dem {

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

Quat shape_orientation(const ShapeTemplate& t, const Body& b) noexcept {
  return b.orientation * conjugate(t.principal.rotation);
}

Transform shape_pose(const ShapeTemplate& t, const Body& b) noexcept {
  const Quat world_from_local = shape_orientation(t, b);
  return Transform::from(b.position - rotate(world_from_local, t.unit_mass.centroid), world_from_local);
}

}  // namespace gjkdem::dem
