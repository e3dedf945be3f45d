// Google Benchmark micro-benchmarks of the narrow phase: support (scan against
// hill climbing), and the three queries cold and warm-started, on random
// polytope pairs of 8-64 and 200-2000 vertices. Items per second = queries/s.
#include <benchmark/benchmark.h>

#include "gjkdem/collide/query.hpp"
#include "random_pairs.hpp"

namespace gjkdem::bench {
namespace {

const std::vector<PolytopePair>& pairs_for(int big) {
  static const std::vector<PolytopePair> small = random_pairs(256, 8, 64, 1);
  static const std::vector<PolytopePair> large = random_pairs(64, 200, 2000, 2);
  return big ? large : small;
}

void BM_Support(benchmark::State& state) {
  std::vector<Vec3> pts = random_rock(*std::make_unique<std::mt19937_64>(3), static_cast<int>(state.range(0)));
  const Polytope p = make_polytope(pts);
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g;
  std::vector<Vec3> dirs(1024);
  for (Vec3& d : dirs) d = {g(rng), g(rng), g(rng)};
  int hint = 0;
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(support(p, dirs[k++ & 1023], hint));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hill_climb"] = p.data->adj.empty() ? 0 : 1;
}
BENCHMARK(BM_Support)->Arg(16)->Arg(64)->Arg(256)->Arg(2000);

template <class Query>
void run_pairs(benchmark::State& state, Query&& query) {
  const auto& pairs = pairs_for(static_cast<int>(state.range(0)));
  std::size_t k = 0;
  for (auto _ : state) {
    const PolytopePair& p = pairs[k++ % pairs.size()];
    benchmark::DoNotOptimize(query(p));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Intersect(benchmark::State& state) {
  run_pairs(state, [](const PolytopePair& p) { return intersect(p.a, p.pose_a, p.b, p.pose_b); });
}
void BM_Distance(benchmark::State& state) {
  run_pairs(state, [](const PolytopePair& p) { return distance(p.a, p.pose_a, p.b, p.pose_b).distance; });
}
void BM_Penetration(benchmark::State& state) {
  run_pairs(state, [](const PolytopePair& p) { return penetration(p.a, p.pose_a, p.b, p.pose_b).depth; });
}
BENCHMARK(BM_Intersect)->Arg(0)->Arg(1);
BENCHMARK(BM_Distance)->Arg(0)->Arg(1);
BENCHMARK(BM_Penetration)->Arg(0)->Arg(1);

// Temporal coherence: one pair queried every "time step" while B moves by a
// small step (arg 1: 1e-3 of the size per step), cold against warm-started.
template <bool kWarm>
void BM_DistanceCoherent(benchmark::State& state) {
  const PolytopePair& p = pairs_for(static_cast<int>(state.range(0)))[0];
  GjkCache cache;
  std::size_t step = 0;
  for (auto _ : state) {
    const double t = 1e-3 * static_cast<double>(step++ % 2000);
    const Transform pb = Transform::from(p.pose_a.translation + Vec3{2.8 * std::cos(t), 2.8 * std::sin(t), 0.1},
                                         quat_from_axis_angle({0, 0, 1}, t));
    benchmark::DoNotOptimize(distance(p.a, p.pose_a, p.b, pb, kWarm ? &cache : nullptr).distance);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DistanceCoherent<false>)->Name("BM_DistanceCoherent/cold")->Arg(0)->Arg(1);
BENCHMARK(BM_DistanceCoherent<true>)->Name("BM_DistanceCoherent/warm")->Arg(0)->Arg(1);

}  // namespace
}  // namespace gjkdem::bench

BENCHMARK_MAIN();
