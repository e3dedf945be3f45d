#pragma once
// Warm-start data for repeated queries on the same pair (the DEM engine asks
// about each pair every time step). Owned by the caller, passed by reference,
// never hidden inside a shape: inputs stay read-only.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct GjkCache {
  Vec3 direction;     ///< last closest point of A - B, in A's local frame; zero: none
  int hint_a = 0;     ///< last support vertex of A (polytopes hill-climb from it)
  int hint_b = 0;     ///< last support vertex of B
  bool valid = false; ///< false: start cold
};

}  // namespace gjkdem
