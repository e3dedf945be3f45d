#pragma once
// A convex polygon cut by a plane (Sutherland-Hodgman), the side kept given
// by a signed distance: the polygon's points where it is <= 0 and each edge's
// crossing. The measurements clip a shell's triangles by a region's planes;
// a surface overlap clips coplanar triangles by each other's sides.
#include <vector>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

/// `out` gets the part of `poly` where distance(p) <= 0 (empty: none).
template <class Distance>
void clip_polygon(const std::vector<Vec3>& poly, Distance&& distance, std::vector<Vec3>& out) {
  out.clear();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3 &p = poly[i], &q = poly[(i + 1) % poly.size()];
    const Real dp = distance(p), dq = distance(q);
    if (dp <= 0) out.push_back(p);
    if ((dp <= 0) != (dq <= 0)) out.push_back(p + (dp / (dp - dq)) * (q - p));
  }
}

}  // namespace gjkdem
