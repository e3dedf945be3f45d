#pragma once
// GJK for convex polygons in the plane: the seed text's Algorithm 14 as
// written (boolean test with an optional trace of every simplex, used to
// reproduce its walk-through, Figures A.8 to A.10), distance with witness
// points, and penetration depth by a planar EPA.
//
// Conventions as in 3D (docs/conventions.md): the normal points from A to B;
// separated: witness_b - witness_a = distance * normal; intersecting:
// witness_a - witness_b = depth * normal. Touching counts as intersecting.
#include <span>
#include <vector>

#include "gjkdem/math/vec2.hpp"

namespace gjkdem {

/// Convex hull of `points` (any points, at least one); support scans them.
struct ConvexPolygon {
  std::span<const Vec2> points;
};

Vec2 support(const ConvexPolygon& p, const Vec2& d) noexcept;

/// One iteration of Algorithm 14: the direction searched, the support point
/// found, and the simplex kept afterwards (newest point last).
struct Gjk2dStep {
  Vec2 direction;
  Vec2 support;
  std::vector<Vec2> simplex;
  bool enclosed = false;  ///< the simplex contains the origin
};

/// Boolean overlap test of Algorithm 14 from `initial_direction`. When `trace`
/// is given every iteration is appended to it (this allocates; the plain call
/// does not).
bool intersect2d(const ConvexPolygon& a, const ConvexPolygon& b, Vec2 initial_direction,
                 std::vector<Gjk2dStep>* trace = nullptr);

struct Penetration2dResult {
  bool intersect = false;
  Real distance = 0;  ///< >= 0, 0 when intersecting
  Real depth = 0;     ///< >= 0, 0 when separated
  Vec2 witness_a, witness_b;
  Vec2 normal;        ///< unit, A -> B
  int iterations = 0; ///< GJK iterations (plus EPA expansions when intersecting)
};

/// Distance when separated, depth (planar EPA) when intersecting.
Penetration2dResult penetration2d(const ConvexPolygon& a, const ConvexPolygon& b) noexcept;

}  // namespace gjkdem
