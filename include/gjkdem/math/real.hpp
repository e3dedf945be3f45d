#pragma once
// Scalar type used throughout gjkdem. Double precision: DEM grains are
// millimetres while walls and offsets reach kilometres, and the query tolerances
// (1e-9 of a pair's size) are out of reach in single precision.
#include <numbers>

namespace gjkdem {
using Real = double;

inline constexpr Real kPi = std::numbers::pi_v<Real>;
}  // namespace gjkdem
