#include "gjkdem/dem/broad_phase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "gjkdem/dem/world.hpp"

namespace gjkdem {
namespace {

TEST(BroadPhase, AabbIsTight) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const Shape shapes[] = {Shape{Box{{1, 2, 3}}}, Shape{Ellipsoid{{1, 0.5, 0.2}}, 0.1}, make_capsule({-1, 0, 0}, {1, 0, 0}, 0.3),
                          Shape{Cone{0.5, 1}}};
  for (const Shape& s : shapes)
    for (int k = 0; k < 20; ++k) {
      const Transform pose = Transform::from(Vec3{u(rng), u(rng), u(rng)} * 10, normalized(Quat{u(rng), u(rng), u(rng), u(rng)}));
      const Aabb box = aabb(s, pose, 0.01);
      // Every support point lies inside, and the faces are reached (tight).
      double reach[6] = {-1e300, -1e300, -1e300, -1e300, -1e300, -1e300};
      for (int d = 0; d < 2000; ++d) {
        const Vec3 p = apply(pose, support(s, Vec3{u(rng), u(rng), u(rng)}));
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(p[a], box.lo[a]);
          EXPECT_LE(p[a], box.hi[a]);
          reach[2 * a] = std::fmax(reach[2 * a], p[a] - box.hi[a]);
          reach[2 * a + 1] = std::fmax(reach[2 * a + 1], box.lo[a] - p[a]);
        }
      }
      for (double r : reach) EXPECT_NEAR(r, -0.01, 0.05);  // sampled supports come close to every face
    }
}

TEST(BroadPhase, SweepAndPruneMatchesBruteForce) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  SweepWorkspace work;
  for (int round = 0; round < 5; ++round) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < 800; ++i) {
      const Vec3 c{u(rng) * 20, u(rng) * 20, u(rng) * (round + 1)};
      const Vec3 h{0.2 + 0.3 * u(rng), 0.2 + 0.3 * u(rng), 0.2 + 0.3 * u(rng)};
      boxes.push_back({c - h, c + h});
    }
    boxes.push_back({boxes[0].hi, boxes[0].hi + Vec3{1, 1, 1}});  // touching at a corner counts
    std::vector<BodyPair> pairs, brute;
    overlapping_pairs(boxes, work, pairs);
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
      for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
        bool hit = true;
        for (int a = 0; a < 3; ++a) hit &= boxes[i].lo[a] <= boxes[j].hi[a] && boxes[j].lo[a] <= boxes[i].hi[a];
        if (hit) brute.emplace_back(i, j);
      }
    EXPECT_EQ(pairs, brute) << "round " << round;
    EXPECT_GT(brute.size(), 100u);
  }
}

std::vector<BodyPair> brute_force_pairs(const std::vector<Aabb>& boxes) {
  std::vector<BodyPair> brute;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
      bool hit = true;
      for (int a = 0; a < 3; ++a) hit &= boxes[i].lo[a] <= boxes[j].hi[a] && boxes[j].lo[a] <= boxes[i].hi[a];
      if (hit) brute.emplace_back(i, j);
    }
  return brute;
}

// A bed much wider than deep, where the strips matter: boxes of many sizes,
// one across the whole bed, flat ones, rows that touch exactly on the strip
// axis (where strip boundaries may fall), all against brute force, on one
// and two threads, with a workspace reused across different box counts.
TEST(BroadPhase, StripsMatchBruteForceOnAWideBedForAnyThreadCount) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  SweepWorkspace one, two;
  for (int round = 0; round < 3; ++round) {
    std::vector<Aabb> boxes;
    const int count = 4500 + 300 * round;
    for (int i = 0; i < count; ++i) {
      const Vec3 c{u(rng) * 60, u(rng) * 40, u(rng)};
      const Vec3 h{0.1 + 0.4 * u(rng), 0.1 + 0.4 * u(rng), i % 17 == 0 ? 0.0 : 0.3 * u(rng)};
      boxes.push_back({c - h, c + h});
    }
    boxes.push_back({{-1, -1, 0.2}, {61, 41, 0.3}});  // across every strip
    for (int k = 0; k < 40; ++k)  // a row along y, each box touching the next
      boxes.push_back({{30.0 + 0.01 * round, 0.5 * k, 0.5}, {30.5, 0.5 * (k + 1), 0.6}});
    std::vector<BodyPair> serial, parallel;
    overlapping_pairs(boxes, one, serial, 1);
    overlapping_pairs(boxes, two, parallel, 2);
    const std::vector<BodyPair> brute = brute_force_pairs(boxes);
    EXPECT_EQ(serial, brute) << "round " << round;
    EXPECT_EQ(parallel, brute) << "round " << round;
    EXPECT_GT(brute.size(), 4000u);
  }
}

// The warm starts follow their pairs from one step's candidate list to the
// next (random sorted lists against a map keyed by pair).
TEST(BroadPhase, PairCachesFollowTheirPairs) {
  std::mt19937_64 rng(6);
  std::vector<dem::PairCache> caches;
  std::map<BodyPair, int> expected;  // pair -> the tag its cache carries
  int tag = 0;
  for (int round = 0; round < 50; ++round) {
    std::vector<BodyPair> candidates;
    for (const auto& [pair, _] : expected)
      if (rng() % 4 != 0) candidates.push_back(pair);  // a quarter of the pairs end
    for (int k = static_cast<int>(rng() % 60); k > 0; --k) {  // new pairs
      const std::uint32_t i = rng() % 40, j = i + 1 + rng() % 40;
      candidates.emplace_back(i, j);
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    dem::align_pair_caches(candidates, caches);
    ASSERT_EQ(caches.size(), candidates.size());
    std::map<BodyPair, int> next;
    for (std::size_t k = 0; k < caches.size(); ++k) {
      ASSERT_EQ(caches[k].pair, candidates[k]);
      const auto old = expected.find(candidates[k]);
      if (old != expected.end()) {
        EXPECT_EQ(caches[k].gjk.size, 1);
        EXPECT_EQ(caches[k].gjk.hint_a, old->second) << "round " << round;
      } else {
        EXPECT_EQ(caches[k].gjk.size, 0) << "a new pair starts cold";
        caches[k].gjk.size = 1;  // what a step's narrow phase would leave
        caches[k].gjk.hint_a = ++tag;
      }
      next[candidates[k]] = caches[k].gjk.hint_a;
    }
    expected.swap(next);
  }
  EXPECT_GT(tag, 500);
  // A damaged list (from a checkpoint): unsorted, with repeats. Every
  // candidate still gets exactly one entry, of its own pair.
  caches.assign(4, {});
  caches[0].pair = caches[1].pair = caches[3].pair = {1, 2};
  caches[2].pair = {0, 5};
  const std::vector<BodyPair> few = {{0, 5}, {1, 2}, {3, 4}};
  dem::align_pair_caches(few, caches);
  ASSERT_EQ(caches.size(), few.size());
  for (std::size_t k = 0; k < few.size(); ++k) EXPECT_EQ(caches[k].pair, few[k]);
  caches.assign(5, {});  // more entries of one pair than there are candidates
  for (dem::PairCache& c : caches) c.pair = {1, 2};
  dem::align_pair_caches(std::vector<BodyPair>{{1, 2}}, caches);
  ASSERT_EQ(caches.size(), 1u);
  EXPECT_EQ(caches[0].pair, (BodyPair{1, 2}));
}

}  // namespace
}  // namespace gjkdem
