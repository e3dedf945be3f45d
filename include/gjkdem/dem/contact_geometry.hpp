#pragma once
// What the narrow phase finds for one candidate contact, the input of the
// force law.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

enum class GeometryStatus {
  Apart,        ///< not touching
  Touching,     ///< the fields below are set
  Unsupported,  ///< the contact model has no computation for this pair of shapes
  Through,      ///< volume law: the body lies wholly beyond a plane wall (no cut face: no force can hold it)
  Engulfed,     ///< surface grains: one lies wholly inside the other (a volume, no contact area)
  Pierced,      ///< surface grains: one passed through the other (a piece of volume, no net contact area)
};

struct ContactGeometry {
  GeometryStatus status = GeometryStatus::Apart;
  Vec3 normal;              ///< unit, a -> b
  Vec3 point;               ///< where friction and damping act, world
  Real depth = 0;           ///< penetration depth, or V / |S_A| for the volume law (m)
  Real area = 0;            ///< |S_A| (volume law and patches, m^2)
  Real volume = 0;          ///< overlap volume (volume law and patches, m^3)
  Real depth_integral = 0;  ///< plane walls, volume law and patches: integral of the depth over the overlap (m^4)
  Vec3 moment;              ///< moment about the world origin of a unit normal force on b (m)
  /// A patch of surface grains (surface_contact.hpp): volume, area, depth
  /// and (on a plane wall) depth_integral are set under every law, and the
  /// Hertz and linear laws take an energy of the volume alone (contact_force.hpp).
  bool patch = false;
};

}  // namespace gjkdem::dem
