#include "gjkdem/dem/broad_phase.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gjkdem::dem {

void overlapping_pairs(std::span<const Aabb> boxes, SweepWorkspace& work, std::vector<BodyPair>& pairs, int threads) {
  pairs.clear();
  const std::size_t n = boxes.size();
  if (n < 2) return;
  // Sweep axis: largest variance of the centres; strips across the second.
  Vec3 mean, sq;
  for (const Aabb& b : boxes) {
    const Vec3 c = (b.lo + b.hi) * 0.5;
    mean += c;
    sq += hadamard(c, c);
  }
  mean /= static_cast<Real>(n);
  const Vec3 var = sq / static_cast<Real>(n) - hadamard(mean, mean);
  int axes[3] = {0, 1, 2};
  std::stable_sort(axes, axes + 3, [&](int p, int q) { return var[p] > var[q]; });
  const int sweep = axes[0], across = axes[1], third = axes[2];

  std::vector<std::uint32_t>& order = work.order;
  auto key = [&](std::uint32_t i) { return boxes[i].lo[sweep]; };
  if (order.size() != n || work.axis != sweep) {  // a new order: sorted outright (insertion sort is n^2 here)
    order.resize(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) { return key(p) < key(q); });
    work.axis = sweep;
  }
  // Insertion sort: linear when the order from the last step is nearly right.
  for (std::size_t i = 1; i < n; ++i) {
    const std::uint32_t v = order[i];
    std::size_t j = i;
    for (; j > 0 && key(order[j - 1]) > key(v); --j) order[j] = order[j - 1];
    order[j] = v;
  }

  // Strips two mean box sizes wide (at most n / 8 of them).
  Real low = std::numeric_limits<Real>::infinity(), high = -low, extents = 0;
  for (const Aabb& b : boxes) {
    low = std::fmin(low, b.lo[across]);
    high = std::fmax(high, b.hi[across]);
    extents += b.hi[across] - b.lo[across];
  }
  const Real width = 2 * extents / static_cast<Real>(n);
  std::size_t strips = 1;
  if (width > 0 && high > low)
    strips = static_cast<std::size_t>(std::fmin((high - low) / width + 1, static_cast<Real>(std::max<std::size_t>(1, n / 8))));
  const Real per_length = strips > 1 ? static_cast<Real>(strips) / (high - low) : 0;
  auto strip_of = [&](Real y) -> std::size_t {
    const Real t = (y - low) * per_length;
    return t > 0 ? std::min(static_cast<std::size_t>(t), strips - 1) : 0;  // NaN: strip 0
  };

  // Each box into every strip it crosses, in sweep order (a counting sort).
  std::vector<std::uint32_t>& begin = work.strip_begin;
  begin.assign(strips + 1, 0);
  for (const std::uint32_t i : order)
    for (std::size_t t = strip_of(boxes[i].lo[across]), last = strip_of(boxes[i].hi[across]); t <= last; ++t)
      ++begin[t + 1];
  for (std::size_t t = 0; t < strips; ++t) begin[t + 1] += begin[t];
  work.cursor.assign(begin.begin(), begin.end() - 1);
  work.entries.resize(begin[strips]);
  for (const std::uint32_t i : order)
    for (std::size_t t = strip_of(boxes[i].lo[across]), last = strip_of(boxes[i].hi[across]); t <= last; ++t)
      work.entries[work.cursor[t]++] = i;

  const int team = std::max(1, threads);
  if (static_cast<int>(work.found.size()) < team) work.found.resize(team);
  const std::int64_t strip_count = static_cast<std::int64_t>(strips);
#pragma omp parallel num_threads(team) if (n >= 4096 && team > 1)
  {
#ifdef _OPENMP
    std::vector<BodyPair>& found = work.found[omp_get_thread_num()];
#else
    std::vector<BodyPair>& found = work.found[0];
#endif
    found.clear();
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t t = 0; t < strip_count; ++t) {
      const std::uint32_t* entry = work.entries.data();
      for (std::uint32_t a = begin[t]; a < begin[t + 1]; ++a) {
        const Aabb& ba = boxes[entry[a]];
        for (std::uint32_t b = a + 1; b < begin[t + 1] && key(entry[b]) <= ba.hi[sweep]; ++b) {
          const Aabb& bb = boxes[entry[b]];
          if (bb.lo[across] > ba.hi[across] || bb.hi[across] < ba.lo[across] || bb.lo[third] > ba.hi[third] ||
              bb.hi[third] < ba.lo[third])
            continue;
          // Reported by the strip where their overlap on the strip axis begins.
          if (strip_of(std::fmax(ba.lo[across], bb.lo[across])) != static_cast<std::size_t>(t)) continue;
          found.emplace_back(std::min(entry[a], entry[b]), std::max(entry[a], entry[b]));
        }
      }
    }
  }
  for (int k = 0; k < team; ++k) pairs.insert(pairs.end(), work.found[k].begin(), work.found[k].end());
  std::sort(pairs.begin(), pairs.end());
}

}  // namespace gjkdem::dem
