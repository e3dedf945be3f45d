// The breakage criterion (dem/break_criterion.hpp): a grain's stress from
// its contact forces and the plane it breaks along (worked by hand: a disc
// squeezed across a diameter), and its strength: Weibull draws whose mean is
// the material's at the reference size, whose modulus comes back from the
// draws, and whose median falls with size as d^(-3/m).
#include "gjkdem/dem/break_criterion.hpp"
#include "gjkdem/dem/world_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem {
namespace {

// A disc-like grain squeezed across a diameter (forces F along y at +-r) and
// held a little along z: its stress is 2 r F / V along y, 2 r (F/10) / V
// along z, and it breaks across x, along the loaded diameter, however the
// whole is turned.
TEST(BreakCriterion, AGrainSqueezedAcrossADiameterBreaksAlongIt) {
  std::mt19937_64 rng(3);
  const Real r = 0.01, force = 100, volume = 2e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const Quat turn = trial == 0 ? Quat{} : random_rotation(rng);
    const Vec3 centre{0.3, -0.2, 0.1};
    std::vector<Vec3> points, forces;
    for (const Real s : {-1.0, 1.0}) {
      points.push_back(centre + rotate(turn, Vec3{0, s * r, 0}));
      forces.push_back(rotate(turn, Vec3{0, -s * force, 0}));  // pushing in
      points.push_back(centre + rotate(turn, Vec3{0, 0, s * r}));
      forces.push_back(rotate(turn, Vec3{0, 0, -s * force / 10}));
    }
    const Mat3 stress = grain_stress(centre, volume, points, forces);
    const Vec3 y = rotate(turn, Vec3{0, 1, 0});
    EXPECT_NEAR(dot(y, stress * y), 2 * r * force / volume, 1e-9 * force / volume * r);
    const BreakPlane plane = break_plane(stress);
    EXPECT_NEAR(std::fabs(dot(plane.normal, rotate(turn, Vec3{1, 0, 0}))), 1, 1e-12) << "trial " << trial;
    EXPECT_NEAR(plane.smallest, 0, 1e-9 * force / volume * r);
    EXPECT_NEAR(plane.largest, 2 * r * force / volume, 1e-9 * force / volume * r);
    const Real s1 = 2 * r * force / volume, s2 = s1 / 10;
    EXPECT_NEAR(plane.deviatoric, std::sqrt((s1 * s1 + s2 * s2 + (s1 - s2) * (s1 - s2)) / 2), 1e-9 * s1);
  }
}

// 20,000 grains at each of four sizes: the mean at the reference size, the
// median's slope against size in log-log (-3/m), and the modulus from a
// Weibull plot (ln(-ln(1 - F)) against ln(strength), slope m).
TEST(BreakCriterion, StrengthsFollowTheirWeibullDistributionAndSizeEffect) {
  const Strength s{.mean = 5e6, .weibull_modulus = 4, .reference_size = 0.01};
  const int n = 20000;
  std::vector<Real> log_size, log_median;
  for (const Real size : {0.0025, 0.005, 0.01, 0.04}) {
    std::vector<Real> draws(n);
    for (int k = 0; k < n; ++k) draws[k] = grain_strength(s, size, strength_draw(11, static_cast<std::uint64_t>(k), 0));
    std::sort(draws.begin(), draws.end());
    log_size.push_back(std::log(size));
    log_median.push_back(std::log(draws[n / 2]));
    if (size == 0.01) {
      Real mean = 0;
      for (const Real d : draws) mean += d / n;
      // The standard deviation of a Weibull of modulus 4 is about 0.28 of its mean.
      EXPECT_NEAR(mean, s.mean, 4 * 0.28 * s.mean / std::sqrt(n));
      Real sx = 0, sy = 0, sxx = 0, sxy = 0;
      int points = 0;
      for (int k = n / 100; k < n - n / 100; k += 50) {  // the middle 98%
        const Real x = std::log(draws[k]), y = std::log(-std::log(1 - (k + 0.5) / n));
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++points;
      }
      const Real modulus = (points * sxy - sx * sy) / (points * sxx - sx * sx);
      EXPECT_NEAR(modulus, 4, 0.1);
    }
  }
  Real sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < log_size.size(); ++k)
    sx += log_size[k], sy += log_median[k], sxx += log_size[k] * log_size[k], sxy += log_size[k] * log_median[k];
  const Real m = static_cast<Real>(log_size.size());
  EXPECT_NEAR((m * sxy - sx * sy) / (m * sxx - sx * sx), -3.0 / 4, 0.02);
  // The draws depend on the seed, the id and the generation alone.
  EXPECT_EQ(strength_draw(11, 7, 0), strength_draw(11, 7, 0));
  EXPECT_NE(strength_draw(11, 7, 0), strength_draw(11, 7, 1));
  EXPECT_NE(strength_draw(11, 7, 0), strength_draw(12, 7, 0));
  // A material's strength is checked with its other values, naming the key.
  Material rock{.name = "rock"};
  EXPECT_NO_THROW(check_material(rock));
  rock.strength = {.mean = 1e6, .weibull_modulus = 3, .reference_size = 0.01, .smallest = 0.002};
  EXPECT_NO_THROW(check_material(rock));
  const auto refused_key = [](const Material& bad) {
    try {
      check_material(bad);
    } catch (const BuildError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Material bad = rock;
  bad.strength.weibull_modulus = 0;
  EXPECT_NE(refused_key(bad).find("weibull_modulus"), std::string::npos) << refused_key(bad);
  bad = rock, bad.strength.reference_size = 0;
  EXPECT_NE(refused_key(bad).find("strength_size"), std::string::npos) << refused_key(bad);
  bad = rock, bad.strength.smallest = 0;
  EXPECT_NE(refused_key(bad).find("unbreakable_below"), std::string::npos) << refused_key(bad);
  bad = rock, bad.strength.mean = -1;
  EXPECT_NE(refused_key(bad).find("strength"), std::string::npos) << refused_key(bad);
}

}  // namespace
}  // namespace gjkdem::dem
