#pragma once
// A moving polyhedral body cut by a plane into two fragments that carry on
// its rigid motion (issue 31, breakage): each fragment's velocity is the
// parent's rigid velocity at its centre of mass and its spin the parent's, so
// mass, linear and angular momentum and kinetic energy are kept to round-off
// (tests/dem/split_body_test.cpp). Choosing the plane and when to cut (the
// breakage criterion) is the caller's.
#include <span>
#include <vector>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/shape/mass_properties.hpp"

namespace gjkdem::dem {

struct Fragment {
  Shape shape;               ///< the piece, a polytope in the parent's shape frame
  MassProperties unit_mass;  ///< per unit density, in that frame
  PrincipalAxes principal;   ///< of unit_mass.inertia
  Vec3 position;             ///< centre of mass, world (m)
  Quat orientation;          ///< principal frame -> world
  Vec3 velocity;             ///< m/s
  Vec3 angular_momentum;     ///< world, about its centre of mass (kg m^2/s)
};

/// The stress in a grain (Pa, compression positive) from the forces on it:
/// -1/V sum over its contacts of (x_c - x_p) (x) f_c, the symmetric part
/// (the Love-Weber average over one grain, as measure.hpp's over a region).
/// `points` and `forces` pair up: where each force acts and the force.
Mat3 grain_stress(const Vec3& centre, Real volume, std::span<const Vec3> points, std::span<const Vec3> forces);

/// Where a stressed grain breaks: the plane through its centre whose normal
/// is its most tensile (least compressed) principal direction, so that the
/// crack holds the direction of the largest compression (a disc squeezed
/// across a diameter splits along it: the Brazilian test). Yade's
/// PolyhedraSplitter (J. Elias, 2013) splits on the stress of the same
/// contact sum; its strength compares with `deviatoric`, the von Mises
/// measure sqrt(((s1-s2)^2 + (s1-s3)^2 + (s2-s3)^2) / 2).
struct BreakPlane {
  Vec3 normal;           ///< unit, world
  Real smallest = 0;     ///< principal stress along the normal (negative: tension), Pa
  Real largest = 0;      ///< the largest principal stress (compression), Pa
  Real deviatoric = 0;   ///< Pa
};
BreakPlane break_plane(const Mat3& stress);

/// The fragments of body `b` (of template `t`, density `density`) on either
/// side of the plane through `point` with `normal` (world): two, or none when
/// the plane leaves a side without volume. Throws std::invalid_argument for
/// a fixed body, a template that is not one solid polytope or box (curved
/// shapes, compounds and surface grains do not split yet), or a bad plane.
std::vector<Fragment> split_body(const ShapeTemplate& t, const Body& b, Real density, const Vec3& point,
                                 const Vec3& normal);

}  // namespace gjkdem::dem
