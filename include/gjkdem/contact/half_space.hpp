#pragma once
// A convex shape against a half-space (a plane wall: material on the side
// opposite to the normal). The deepest point comes from one support call; the
// part of the body below the plane is found exactly for polytope and box cores
// without margin (triangle clipping) and for spheres (a spherical cap).
//
// For the volume law the force k V acts along the wall normal through the
// centroid of the part below the plane. It derives from the potential
// U = k * (integral of the depth below the plane over that part), as buoyancy
// does: for a body moving with v and spinning with w about x0,
// dU/dt = -k V (n . v + ((x_c - x0) x n) . w), the power of k V n at x_c.
// (Through the cut face's centroid instead, the power is (k V / A) dV/dt,
// exact only while the cut area A stays constant: a tilted polyhedron lost up
// to 4% of its energy in one bounce.)
#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

struct HalfSpaceContact {
  bool touching = false;  ///< some point of the body lies on or below the plane
  Real depth = 0;         ///< of the deepest point below the plane (m)
  Vec3 deepest;           ///< that point, world
  bool has_volume = false;  ///< volume, centroid, depth_integral, area and face_centroid are set
  Real volume = 0;          ///< of the body below the plane (m^3)
  Vec3 centroid;            ///< of the body below the plane, world
  Real depth_integral = 0;  ///< integral of the depth below the plane over that part (m^4)
  Real area = 0;            ///< of the cut face (m^2)
  Vec3 face_centroid;       ///< centroid of the cut face (on the plane), world
};

/// The placed shape against the half-space through `point` whose outward unit
/// normal is `normal`.
HalfSpaceContact half_space_contact(const Shape& shape, const Transform& pose, const Vec3& point,
                                    const Vec3& normal);

}  // namespace gjkdem
