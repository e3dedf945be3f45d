#pragma once
// Brute-force references for the narrow-phase tests. They share no code with
// the library's GJK/EPA: they enumerate every vertex, edge and triangle of the
// point set of all vertex differences a_i - b_j (whose hull is A - B).
#include <vector>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem::oracle {

struct PairTruth {
  bool intersect = false;
  double distance = 0;  ///< origin to hull(A - B) when outside
  double depth = 0;     ///< origin to the boundary of hull(A - B) when inside
  Vec3 closest;         ///< separated: closest point of A - B; intersecting: depth * outward normal
};

/// All differences a - b.
std::vector<Vec3> minkowski_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

/// Closest point of triangle (a, b, c) to the origin: the best of its edges and
/// of its interior projection (written independently of the library's
/// signed-volume routine).
Vec3 closest_on_triangle(const Vec3& a, const Vec3& b, const Vec3& c);

/// Exact answer by enumeration: a candidate closest point is accepted when its
/// plane supports every point; a supporting plane through three points bounds
/// the depth. O(n^4): keep n (the difference count) below ~100.
PairTruth brute_force_pair(const std::vector<Vec3>& diff, double rel_tol = 1e-12);

}  // namespace gjkdem::oracle
