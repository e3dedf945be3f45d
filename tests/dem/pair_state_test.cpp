// The pair store: entries follow their keys from step to step, and a damaged
// store cannot make the alignment index out of range.
#include "gjkdem/dem/pair_state.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

namespace gjkdem::dem {
namespace {

// The pair store follows its pairs from one step's contact list to the next
// (random sorted lists of keys against a map keyed by pair).
TEST(PairState, StatesFollowTheirPairs) {
  std::mt19937_64 rng(6);
  std::vector<PairState> caches;
  std::map<PairKey, int> expected;  // pair -> the tag its cache carries
  int tag = 0;
  for (int round = 0; round < 50; ++round) {
    std::vector<PairKey> candidates;
    for (const auto& [pair, _] : expected)
      if (rng() % 4 != 0) candidates.push_back(pair);  // a quarter of the pairs end
    for (int k = static_cast<int>(rng() % 60); k > 0; --k) {  // new pairs
      const std::uint64_t i = rng() % 40, j = i + 1 + rng() % 40;
      candidates.push_back({i, j});
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    align_pair_states(candidates, caches);
    ASSERT_EQ(caches.size(), candidates.size());
    std::map<PairKey, int> next;
    for (std::size_t k = 0; k < caches.size(); ++k) {
      ASSERT_EQ(caches[k].key, candidates[k]);
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
  caches[0].key = caches[1].key = caches[3].key = {1, 2};
  caches[2].key = {0, 5};
  const std::vector<PairKey> few = {{0, 5}, {1, 2}, {3, 4}};
  align_pair_states(few, caches);
  ASSERT_EQ(caches.size(), few.size());
  for (std::size_t k = 0; k < few.size(); ++k) EXPECT_EQ(caches[k].key, few[k]);
  caches.assign(5, {});  // more entries of one pair than there are candidates
  for (PairState& c : caches) c.key = {1, 2};
  align_pair_states(std::vector<PairKey>{{1, 2}}, caches);
  ASSERT_EQ(caches.size(), 1u);
  EXPECT_EQ(caches[0].key, (PairKey{1, 2}));
}

}  // namespace
}  // namespace gjkdem::dem
