#pragma once
// Brute-force reference for the overlap of two convex polytopes, independent of
// the library's clipping: the vertices of the intersection are A's vertices
// inside B, B's inside A, and the points where an edge of one crosses a face of
// the other; its volume and centroid come from the hull of those points.
#include <array>
#include <cstdint>
#include <vector>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem::oracle {

struct OverlapTruth {
  double volume = 0;
  Vec3 centroid;
};

/// Polytopes given by their vertices (world) and outward triangles (indices).
OverlapTruth brute_force_overlap(const std::vector<Vec3>& va, const std::vector<std::array<std::uint32_t, 3>>& ta,
                                 const std::vector<Vec3>& vb, const std::vector<std::array<std::uint32_t, 3>>& tb);

}  // namespace gjkdem::oracle
