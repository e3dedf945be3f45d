#pragma once
// Numbers in the engine's messages (internal to src/dem).
#include <cstdio>
#include <string>

#include "gjkdem/math/real.hpp"

namespace gjkdem::dem::detail {

/// `v` with `digits` significant digits, shortest form (%g).
inline std::string number_text(Real v, int digits = 6) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace gjkdem::dem::detail
