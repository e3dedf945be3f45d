#pragma once
// Numbers as text, the one way every output writes them (CSV tables, VTK
// headers, query answers, the view index): the shortest text that reads
// back to the same double, so files are exact and no longer than need be.
#include <charconv>
#include <string>

#include "gjkdem/math/real.hpp"

namespace gjkdem::io {

/// `value` appended as the shortest text that reads back to it.
inline void append_number(std::string& text, Real value) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  text.append(buf, r.ptr);
}

}  // namespace gjkdem::io
