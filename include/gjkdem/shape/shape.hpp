#pragma once
// A convex shape = a core (one of the types below, in its local frame) plus a
// margin: the shape is the Minkowski sum of the core with a ball of that radius.
// Queries run GJK/EPA on the cores and add the margins afterwards, which is
// exact (the Minkowski difference of rounded shapes is the cores' difference
// grown by the summed margins) and cheaper. A sphere is a point with a margin,
// a capsule a segment with a margin.
#include <variant>

#include "gjkdem/shape/box.hpp"
#include "gjkdem/shape/cone.hpp"
#include "gjkdem/shape/cylinder.hpp"
#include "gjkdem/shape/ellipsoid.hpp"
#include "gjkdem/shape/point.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/segment.hpp"
#include "gjkdem/shape/superellipsoid.hpp"
#include "gjkdem/shape/triangle.hpp"
#include "gjkdem/math/transform.hpp"

namespace gjkdem {

using ShapeCore = std::variant<Point, Segment, Triangle, Box, Ellipsoid, Cylinder, Cone, Superellipsoid, Polytope>;

struct Shape {
  ShapeCore core;
  Real margin = 0;  ///< >= 0, same length unit as the core
};

inline Shape make_sphere(Real radius) { return {Point{}, radius}; }
inline Shape make_capsule(const Vec3& p0, const Vec3& p1, Real radius) { return {Segment{p0, p1}, radius}; }

/// Support of the whole shape (core + margin) in local direction d.
inline Vec3 support(const Shape& s, const Vec3& d) noexcept {
  int hint = 0;
  const Vec3 core = std::visit([&](const auto& c) { return support(c, d, hint); }, s.core);
  return s.margin > 0 ? core + normalized(d) * s.margin : core;
}
/// Radius of a ball about the local origin that holds the whole shape.
inline Real bounding_radius(const Shape& s) noexcept {
  return std::visit([](const auto& c) { return bounding_radius(c); }, s.core) + s.margin;
}

/// A shape placed in a parent frame: a part of a compound, a shape in a scene.
struct PlacedShape {
  Shape shape;
  Transform pose;  ///< shape frame -> parent frame
};

}  // namespace gjkdem
