#include "gjkdem/dem/broad_phase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {
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

// A small hull's box comes from its corners placed, not six scans: the same
// bits as the supports along the rotated axes give (a resumed or re-run bed
// must find the same candidates), for hulls of 4 to 64 corners far from the
// origin, with and without a pad.
TEST(BroadPhase, SmallHullBoxHasTheSupportsBits) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 0; c < 300; ++c) {
    std::vector<Vec3> pts;
    for (int i = 0; i < 4 + c % 61; ++i) pts.push_back(Vec3{u(rng), u(rng), 0.2 * u(rng)} * (1 + c % 7));
    const Shape s{make_polytope(pts)};
    const Transform pose = Transform::from(Vec3{u(rng), u(rng), u(rng)} * std::pow(10.0, c % 6),
                                           normalized(Quat{u(rng), u(rng), u(rng), u(rng)}));
    const Real pad = c % 2 ? 0.01 : 0;
    const Aabb box = aabb(s, pose, pad);
    for (int k = 0; k < 3; ++k) {
      Vec3 axis;
      axis[k] = 1;
      const Vec3 local = apply_inverse_rotation(pose, axis);
      EXPECT_EQ(box.hi[k], apply(pose, support(s, local))[k] + pad) << c;
      EXPECT_EQ(box.lo[k], apply(pose, support(s, -local))[k] - pad) << c;
    }
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

// The static tree of fixed boxes finds what a brute-force scan finds.
TEST(BroadPhase, StaticTreeMatchesBruteForce) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (int n : {0, 1, 3, 4, 5, 17, 300}) {
    std::vector<Aabb> boxes(n);
    std::vector<std::uint32_t> ids(n);
    for (int k = 0; k < n; ++k) {
      const Vec3 c{u(rng), u(rng), u(rng)}, h{0.05 * u(rng), 0.05 * u(rng), 0.3 * u(rng)};
      boxes[k] = {c - h, c + h};
      ids[k] = static_cast<std::uint32_t>(1000 + 3 * k);
    }
    StaticTree tree;
    build_box_tree(boxes, ids, tree);
    int hits = 0;
    for (int q = 0; q < 200; ++q) {
      const Vec3 c{u(rng), u(rng), u(rng)}, h{0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng)};
      const Aabb query{c - h, c + h};
      std::vector<std::uint32_t> found, expected;
      query_box_tree(tree, query, found);
      for (int k = 0; k < n; ++k)
        if (overlaps(boxes[k], query)) expected.push_back(ids[k]);
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, expected) << "n = " << n << ", query " << q;
      hits += static_cast<int>(expected.size());
    }
    if (n == 300) {
      EXPECT_GT(hits, 200);  // the queries do meet boxes
    }
  }
}

}  // namespace
}  // namespace gjkdem::dem
