// Recursive coordinate bisection (decomposition.hpp): every body lies in its
// part's box, the boxes tile the domain, the parts' weights are balanced
// wherever the bodies are, and the answer does not depend on input order.
#include "gjkdem/dem/decomposition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace gjkdem::dem {
namespace {

struct Bodies {
  std::vector<Vec3> centres;
  std::vector<Real> weights;
  std::vector<std::uint64_t> ids;
};

const Vec3 kLo{-1, -2, 0}, kHi{1, 2, 3};

Bodies random_bodies(int n, std::uint64_t seed, Real spread = 1) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> u(0, 1), w(0.5, 2);
  Bodies b;
  for (int i = 0; i < n; ++i) {
    b.centres.push_back({kLo.x + spread * (kHi.x - kLo.x) * u(rng), kLo.y + spread * (kHi.y - kLo.y) * u(rng),
                         kLo.z + spread * (kHi.z - kLo.z) * u(rng)});
    b.weights.push_back(w(rng));
    b.ids.push_back(1000 + 7 * static_cast<std::uint64_t>(i));
  }
  return b;
}

Real volume(const DomainBox& b) {
  const Vec3 e = b.hi - b.lo;
  return std::fmax(e.x, 0.0) * std::fmax(e.y, 0.0) * std::fmax(e.z, 0.0);
}

// Each body in its part's box, and the boxes tiling the domain: their
// volumes sum to the domain's and no two overlap.
void expect_valid(const Bodies& b, const Decomposition& d, int parts) {
  ASSERT_EQ(d.boxes.size(), static_cast<std::size_t>(parts));
  ASSERT_EQ(d.owner.size(), b.centres.size());
  for (std::size_t i = 0; i < b.centres.size(); ++i) {
    ASSERT_LT(d.owner[i], static_cast<std::uint32_t>(parts));
    EXPECT_TRUE(d.boxes[d.owner[i]].holds(b.centres[i])) << "body " << i;
  }
  Real sum = 0;
  for (std::size_t p = 0; p < d.boxes.size(); ++p) {
    sum += volume(d.boxes[p]);
    for (std::size_t q = p + 1; q < d.boxes.size(); ++q)
      EXPECT_EQ(volume({max(d.boxes[p].lo, d.boxes[q].lo), min(d.boxes[p].hi, d.boxes[q].hi)}), 0) << p << " " << q;
  }
  EXPECT_NEAR(sum, volume({kLo, kHi}), 1e-12);
}

std::vector<Real> part_weights(const Bodies& b, const Decomposition& d, int parts) {
  std::vector<Real> w(parts, 0);
  for (std::size_t i = 0; i < b.weights.size(); ++i) w[d.owner[i]] += b.weights[i];
  return w;
}

TEST(Bisection, PartsTileTheDomainAndBalanceTheirWeights) {
  const Bodies b = random_bodies(5000, 1);
  const Real total = std::accumulate(b.weights.begin(), b.weights.end(), Real(0));
  for (const int parts : {1, 2, 3, 4, 5, 7, 16}) {
    const Decomposition d = bisect(b.centres, b.weights, b.ids, parts, kLo, kHi);
    expect_valid(b, d, parts);
    // Each cut misses its share by at most one body's weight (2), and a
    // part sits under ceil(log2 parts) cuts.
    const Real slack = 2 * std::ceil(std::log2(parts));
    for (const Real w : part_weights(b, d, parts)) EXPECT_NEAR(w, total / parts, slack) << parts << " parts";
  }
}

TEST(Bisection, FollowsTheBodiesIntoACorner) {
  // A hopper emptied into one corner: the bodies fill 5% of each side.
  const Bodies b = random_bodies(4000, 2, 0.05);
  const Real total = std::accumulate(b.weights.begin(), b.weights.end(), Real(0));
  const Decomposition d = bisect(b.centres, b.weights, b.ids, 4, kLo, kHi);
  expect_valid(b, d, 4);
  for (const Real w : part_weights(b, d, 4)) EXPECT_NEAR(w, total / 4, 4);
}

TEST(Bisection, TheOrderOfTheBodiesDoesNotMatter) {
  Bodies b = random_bodies(2000, 3);
  // Ties on every axis: bodies on a coarse lattice, where only ids order them.
  for (Vec3& c : b.centres) c = {std::floor(c.x * 4) / 4, std::floor(c.y * 4) / 4, std::floor(c.z * 4) / 4};
  const Decomposition d = bisect(b.centres, b.weights, b.ids, 6, kLo, kHi);
  expect_valid(b, d, 6);
  std::vector<std::size_t> order(b.centres.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937_64(4));
  Bodies shuffled;
  for (const std::size_t i : order) {
    shuffled.centres.push_back(b.centres[i]);
    shuffled.weights.push_back(b.weights[i]);
    shuffled.ids.push_back(b.ids[i]);
  }
  const Decomposition e = bisect(shuffled.centres, shuffled.weights, shuffled.ids, 6, kLo, kHi);
  for (std::size_t k = 0; k < order.size(); ++k) ASSERT_EQ(e.owner[k], d.owner[order[k]]) << "body " << order[k];
}

TEST(Bisection, BodiesAtOnePointStayTogetherAndFewBodiesLeavePartsEmpty) {
  Bodies same;
  for (int i = 0; i < 50; ++i) same.centres.push_back({0.25, 0.5, 1}), same.weights.push_back(1), same.ids.push_back(i);
  const Decomposition d = bisect(same.centres, same.weights, same.ids, 4, kLo, kHi);
  expect_valid(same, d, 4);
  EXPECT_TRUE(std::all_of(d.owner.begin(), d.owner.end(), [&](std::uint32_t o) { return o == d.owner[0]; }));
  const Bodies few = random_bodies(3, 5);
  expect_valid(few, bisect(few.centres, few.weights, few.ids, 8, kLo, kHi), 8);
  const Bodies none;
  expect_valid(none, bisect(none.centres, none.weights, none.ids, 3, kLo, kHi), 3);
}

TEST(Bisection, RefusesWhatItCannotSplit) {
  Bodies b = random_bodies(10, 6);
  EXPECT_THROW(bisect(b.centres, b.weights, b.ids, 0, kLo, kHi), std::invalid_argument);
  b.weights.pop_back();
  EXPECT_THROW(bisect(b.centres, b.weights, b.ids, 2, kLo, kHi), std::invalid_argument);
  b = random_bodies(10, 6);
  b.centres[3].z = kHi.z;  // on the domain's upper face: outside [lo, hi)
  EXPECT_THROW(bisect(b.centres, b.weights, b.ids, 2, kLo, kHi), std::invalid_argument);
  b = random_bodies(10, 6);
  b.weights[2] = -1;
  EXPECT_THROW(bisect(b.centres, b.weights, b.ids, 2, kLo, kHi), std::invalid_argument);
}

}  // namespace
}  // namespace gjkdem::dem
