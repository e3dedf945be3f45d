#pragma once
// Warm-start data for repeated queries on the same pair (the DEM engine asks
// about each pair every time step). Owned by the caller, passed by reference,
// never hidden inside a shape: inputs stay read-only.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

/// Box2D-style simplex cache: the search directions that produced the last
/// simplex are replayed, so a pair that moved little starts next to its answer.
struct GjkCache {
  Vec3 dirs[4];   ///< search directions of the last simplex points, A's local frame
  int size = 0;   ///< how many of dirs are set; 0: start cold
  int hint_a = 0; ///< last support vertex of A (polytopes hill-climb from it)
  int hint_b = 0; ///< last support vertex of B
};

}  // namespace gjkdem
