#pragma once
// Points deep inside a closed surface's solid, each with its depth (its
// distance to the surface): where a body passing through another is seen
// (dem/contacts/body_crossing.cpp). A convex body's centre does that job
// for it; a non-convex solid's centre may lie outside it (a torus, a U) or
// near its surface, and one point cannot stand for a ring.
#include <memory>
#include <mutex>
#include <vector>

#include "gjkdem/shape/surface.hpp"
#include "gjkdem/shape/triangle.hpp"

namespace gjkdem {

struct DeepPoint {
  Vec3 point;      ///< in the surface's frame
  Real depth = 0;  ///< distance to the surface (m)
};

/// Up to kDeepPointsMax points of the solid, deepest first, each at least
/// kDeepPointRel of the deepest one's depth and none within another's
/// depth: from the centroid and the centres of a grid of kDeepPointGrid^3
/// cells over the surface's box that lie inside (winding number above 1/2),
/// a spread of them deepened by a compass search toward the middle of its
/// part of the solid. Empty for a solid no candidate lies in.
std::vector<DeepPoint> deep_points(const Surface& surface);

/// Where a surface keeps its deep points (Surface::deep, from make_surface):
/// made on the first call of the overload below, by whichever thread asks
/// first (0.05 s for a thousand triangles, 5 s for a million: a run makes
/// them only once a patch is deep, beyond reach_bound).
struct DeepPointsSlot {
  /// kDeepReachRel kDeepPointRel V / S of the solid (volume V, area S): a
  /// convex solid's inradius is at most 3 V / S and a ball's, a cube's or a
  /// plate's V / S to 3 V / S, so patches shallower than this reach no deep
  /// point that is kept.
  Real reach_bound = 0;
  std::once_flag made;
  std::vector<DeepPoint> points;
};
/// A slot for the surface's deep points, its reach_bound set.
std::shared_ptr<DeepPointsSlot> deep_points_slot(const Surface& surface);
const std::vector<DeepPoint>& deep_points(const Surface& surface, DeepPointsSlot& slot);

/// The distance from p to the surface's triangles.
Real distance_to_surface(const Surface& surface, const Vec3& p);

}  // namespace gjkdem
