#pragma once
// A convex shape against a half-space (a plane wall: material on the side
// opposite to the normal). The deepest point comes from one support call; the
// part of the body below the plane is found exactly for polytope and box cores
// without margin (triangle clipping) and for spheres (a spherical cap).
//
// For the volume law the force k V acts along the wall normal through the
// centroid of the cut face: the overlap changes only by sweeping that face, so
// dV = A (n . v + (c x n) . w) dt for a body moving with v and spinning with w,
// and the force through the cut face's centroid c is the energy-conserving one.
#include "gjkdem/shape/shape.hpp"

namespace gjkdem::dem {

struct HalfSpaceContact {
  bool touching = false;  ///< some point of the body lies on or below the plane
  Real depth = 0;         ///< of the deepest point below the plane (m)
  Vec3 deepest;           ///< that point, world
  bool has_volume = false;  ///< volume, area and face_centroid are set
  Real volume = 0;          ///< of the body below the plane (m^3)
  Real area = 0;            ///< of the cut face (m^2)
  Vec3 face_centroid;       ///< centroid of the cut face (on the plane), world
};

/// The placed shape against the half-space through `point` whose outward unit
/// normal is `normal`.
HalfSpaceContact half_space_contact(const Shape& shape, const Transform& pose, const Vec3& point,
                                    const Vec3& normal);

}  // namespace gjkdem::dem
