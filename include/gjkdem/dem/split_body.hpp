#pragma once
// A moving polyhedral body cut by a plane into two fragments that carry on
// its rigid motion (issue 31, breakage): each fragment's velocity is the
// parent's rigid velocity at its centre of mass and its spin the parent's, so
// mass, linear and angular momentum and kinetic energy are kept to round-off
// (tests/dem/split_body_test.cpp). When and where to cut is the breakage
// criterion's (break_criterion.hpp).
#include <vector>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/shape/mass_properties.hpp"

namespace gjkdem::dem {

struct Fragment {
  Shape shape;               ///< the piece, a polytope about its centroid (the parent's shape axes)
  MassProperties unit_mass;  ///< per unit density, in that frame (its centroid at the origin, to round-off)
  PrincipalAxes principal;   ///< of unit_mass.inertia
  Vec3 position;             ///< centre of mass, world (m)
  Quat orientation;          ///< principal frame -> world
  Vec3 velocity;             ///< m/s
  Vec3 angular_momentum;     ///< world, about its centre of mass (kg m^2/s)
};

/// Whether split_body takes a body of template `t`: one solid polyhedron or
/// box.
bool can_split(const ShapeTemplate& t) noexcept;

/// The fragments of body `b` (of template `t`, density `density`) on either
/// side of the plane through `point` with `normal` (world): two, or none when
/// the plane leaves a side without volume. Throws std::invalid_argument for
/// a fixed body, a template that is not one solid polytope or box (curved
/// shapes, compounds and surface grains do not split yet), or a bad plane.
std::vector<Fragment> split_body(const ShapeTemplate& t, const Body& b, Real density, const Vec3& point,
                                 const Vec3& normal);

}  // namespace gjkdem::dem
