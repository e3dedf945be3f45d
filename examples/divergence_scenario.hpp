#pragma once
// The contact-divergence scenario of the seed text's Figure A.7: cube B overlaps
// a corner of cube A so that the two minimum-penetration directions (x and y)
// are almost equally short. A sweep of tiny sideways motions of B makes the
// penetration (EPA) normal jump by 90 degrees where the two depths cross, while
// the volume-based normal (area-weighted normal of the overlap surface) turns
// continuously. Shared by examples/contact_divergence.cpp and its test.
#include <cmath>
#include <vector>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/contact/overlap.hpp"

namespace gjkdem::examples {

struct DivergenceSample {
  double shift;         ///< B's sideways motion (m): +shift along x, -shift along y
  double depth;         ///< EPA penetration depth
  double epa_deg;       ///< EPA normal, angle from +x in the xy-plane (degrees)
  double volume_deg;    ///< volume-based normal, same angle
  double volume;        ///< overlap volume
};

/// Unit cubes; B sits at (0.9 + s, 0.9 - s, 0): the overlap is a corner prism
/// 0.1 - s wide in x and 0.1 + s in y, and the narrower width is the EPA depth.
inline std::vector<DivergenceSample> divergence_sweep(double max_shift, int samples) {
  const Shape cube{Box{{0.5, 0.5, 0.5}}};
  OverlapWorkspace work;
  std::vector<DivergenceSample> out;
  const double deg = 180 / kPi;
  for (int i = 0; i < samples; ++i) {
    const double s = -max_shift + 2 * max_shift * i / (samples - 1);
    const Transform pa = Transform::identity(), pb = Transform::from({0.9 + s, 0.9 - s, 0}, {});
    const PenetrationResult p = penetration(cube, pa, cube, pb);
    const OverlapResult o = overlap(cube, pa, cube, pb, work);
    out.push_back({s, p.depth, std::atan2(p.normal.y, p.normal.x) * deg,
                   std::atan2(o.contact_normal.y, o.contact_normal.x) * deg, o.volume});
  }
  return out;
}

}  // namespace gjkdem::examples
