// The seed's Figure A.7: over a sweep of tiny motions the minimum-penetration
// normal jumps between two perpendicular directions, while the volume-based
// normal turns continuously.
#include <gtest/gtest.h>

#include "divergence_scenario.hpp"

namespace gjkdem {
namespace {

TEST(Divergence, EpaNormalJumpsVolumeNormalDoesNot) {
  const auto sweep = examples::divergence_sweep(1e-3, 41);  // steps of 5e-5 m
  double epa_jump = 0, vol_jump = 0;
  for (std::size_t i = 1; i < sweep.size(); ++i) {
    epa_jump = std::fmax(epa_jump, std::fabs(sweep[i].epa_deg - sweep[i - 1].epa_deg));
    vol_jump = std::fmax(vol_jump, std::fabs(sweep[i].volume_deg - sweep[i - 1].volume_deg));
  }
  EXPECT_GT(epa_jump, 89.0);  // x to y in one 5e-5 m step
  EXPECT_LT(vol_jump, 0.05);
  // Closed form of the volume normal: S_A = (w_y, w_x, 0) with w_x = 0.1 - s, w_y = 0.1 + s.
  for (const auto& s : sweep) {
    const double expected = std::atan2(0.1 - s.shift, 0.1 + s.shift) * 180 / kPi;
    EXPECT_NEAR(s.volume_deg, expected, 1e-9);
    EXPECT_NEAR(s.volume, (0.1 - s.shift) * (0.1 + s.shift), 1e-14);
  }
}

}  // namespace
}  // namespace gjkdem
