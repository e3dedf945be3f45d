#pragma once
// Regions that are not boxes, for generators and inflows: a cylinder or a
// ball, their bounding boxes, whether a ball lies inside, and a point drawn
// uniformly in their volume.
#include <string>

#include "gjkdem/math/transform.hpp"
#include "gjkdem/math/vec3.hpp"
#include "gjkdem/shape/aabb.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem::dem {

/// A cylinder from `base` along `axis` (made unit) of `radius` and `height`,
/// or a ball about `base` of `radius`.
struct RoundRegion {
  enum class Kind { Cylinder, Ball } kind = Kind::Cylinder;
  Vec3 base{};
  Vec3 axis{0, 0, 1};
  Real radius = 0, height = 0;
  friend bool operator==(const RoundRegion&, const RoundRegion&) = default;
};

/// Throws BuildError (naming `label`) unless base and axis are finite, the
/// axis is not zero, the radius is finite and > 0, and a cylinder's height is
/// finite and > 0 (>= 0 where `flat` is allowed: an inflow's disc).
void check_round_region(const RoundRegion& region, const std::string& label, bool flat);

Aabb round_box(const RoundRegion& region);

/// Whether a ball of radius r about c lies inside.
bool ball_inside(const RoundRegion& region, const Vec3& c, Real r);

/// Distance from p to the region (0 inside), and from p inside to its boundary.
Real distance_to(const RoundRegion& region, const Vec3& p);
Real depth_in(const RoundRegion& region, const Vec3& p);

/// m^3: pi R^2 H, or 4/3 pi R^3.
Real round_volume(const RoundRegion& region);

/// The region as a shape (a Cylinder along its local z, or a sphere) and
/// where that shape's frame lies: its centre, local z along the axis.
Shape round_shape(const RoundRegion& region);
Transform round_pose(const RoundRegion& region);

/// The point of the region that three uniform numbers in [0, 1) pick, so
/// that uniform numbers give points uniform in its volume (a cylinder's: in
/// its disc when its height is 0).
Vec3 round_point(const RoundRegion& region, Real u1, Real u2, Real u3);

}  // namespace gjkdem::dem
