#pragma once
// A tessellated sphere as coal's GJK tests build one (test/gjk_asserts.cpp):
// `steps` x `steps` latitude-longitude points computed in single precision.
// Its poles repeat one point (or, at the far pole, scatter it by 1e-7), its
// seam repeats a meridian 1e-7 off, and its quads are flat only to single
// precision: near-duplicate points and nearly coplanar faces, the inputs
// where clipping and hulls meet their tolerances.
#include <cmath>
#include <vector>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem::test {

inline std::vector<Vec3> float_sphere(double radius, int steps) {
  const float pi = 3.14159265358979f;
  const float polar = pi / static_cast<float>(steps - 1), azimuth = 2 * pi / static_cast<float>(steps - 1);
  std::vector<Vec3> pts;
  for (int p = 0; p < steps; ++p)
    for (int a = 0; a < steps; ++a) {
      const float s = std::sin(static_cast<float>(p) * polar);
      pts.push_back(Vec3{s * std::cos(static_cast<float>(a) * azimuth), s * std::sin(static_cast<float>(a) * azimuth),
                         std::cos(static_cast<float>(p) * polar)} * radius);
    }
  return pts;
}

}  // namespace gjkdem::test
