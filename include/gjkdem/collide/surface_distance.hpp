#pragma once
// The distance between two closed triangle surfaces (shape/surface.hpp) and
// a closest pair of points: the least of the triangle pairs' distances
// (the batched kernel triangle_distances), visiting only the pairs of tree
// nodes whose boxes lie closer than the best found so far. For separated solids this is the
// distance between the solids (one inside the other is an overlap:
// contact/surface_overlap.hpp tells).
#include "gjkdem/shape/surface.hpp"

namespace gjkdem {

struct SurfaceDistance {
  Real distance = 0;
  Vec3 witness_a, witness_b;  ///< on A's and on B's surface
};

/// Both surfaces in one frame.
SurfaceDistance surface_distance(const Surface& a, const Surface& b);

}  // namespace gjkdem
