#pragma once
// Per-call settings of the narrow-phase queries; defaults from tolerances.hpp.
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

struct QuerySettings {
  Real gjk_rel_tol = kGjkRelTol;      ///< relative duality gap that ends GJK
  Real gjk_abs_tol = kGjkAbsTol;      ///< absolute gap, relative to the pair size
  Real touch_tol = kGjkTouchTol;      ///< cores closer than this * size touch
  int max_gjk_iterations = kMaxGjkIterations;
  Real epa_rel_tol = kEpaRelTol;      ///< relative gap that ends EPA
  Real epa_abs_tol = kEpaAbsTol;      ///< absolute gap, relative to the pair size
};

}  // namespace gjkdem
