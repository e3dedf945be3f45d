#pragma once
// Volume, centre of mass and inertia of a shape, per unit density, computed
// exactly from the shape: polytopes by integration over their hull's
// tetrahedra, spheres, boxes, ellipsoids, cylinders, cones and capsules in
// closed form, superellipsoids by Jaklic, Leonardis and Solina's beta-function
// formulas ("Segmentation and Recovery of Superquadrics", 2000, ch. 2).
// Many particles share one template, so this runs once per shape.
#include <array>
#include <cstdint>
#include <span>

#include "gjkdem/math/quat.hpp"
#include "gjkdem/math/transform.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

struct MassProperties {
  Real volume = 0;  ///< m^3 (mass = density * volume)
  Vec3 centroid;    ///< centre of mass, local frame (m)
  Mat3 inertia;     ///< about the centroid, local axes, per unit density (m^5)
};

/// Throws std::invalid_argument for shapes without volume (points, segments,
/// triangles, flat polytopes, all without margin) and for margins on cores
/// other than points and segments (no closed form yet).
MassProperties mass_properties(const Shape& shape);

/// Of a rigid union of parts that do not overlap (their volumes add): the
/// parts' inertias turned into the compound's axes and moved to its centre
/// of mass (parallel axes). Throws as mass_properties(Shape) for a part.
MassProperties mass_properties(std::span<const PlacedShape> parts);

/// The same from each part's own mass properties (in its frame) and its
/// pose in the compound's frame: the rule both unions follow.
MassProperties union_mass_properties(std::span<const MassProperties> each, std::span<const Transform> poses);

/// The inertia about `centroid` (per unit density) of the solid a closed,
/// outward triangle surface bounds, given its volume and centroid: the
/// divergence theorem, by tetrahedra from the centroid.
MassProperties closed_surface_inertia(std::span<const Vec3> vertices,
                                      std::span<const std::array<std::uint32_t, 3>> triangles, Real volume,
                                      const Vec3& centroid);

/// Principal moments (ascending) and the rotation taking principal axes to the
/// local frame: inertia = R diag(moments) R^T, R = to_matrix(rotation).
struct PrincipalAxes {
  Vec3 moments;
  Quat rotation;
};
PrincipalAxes principal_axes(const Mat3& inertia);

}  // namespace gjkdem
