// Time of the surface queries on pairs of meshes (the query format's mesh
// pairs, e.g. ../shared/data/nonconvex/rocks.in.jsonl): per pair, the median
// of `repeat` timed calls of surface_overlap (and surface_distance where the
// solids are apart), surfaces built once; one line per pair, then the median
// per size (triangles of A + B) and kind.
//   build/bench/bench_surfaces --in PAIRS.jsonl [--repeat N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "gjkdem/collide/surface_distance.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "mesh_pairs.hpp"

using namespace gjkdem;

namespace {

template <class F>
double median_us(int repeat, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string in;
  int repeat = 21;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--in" && i + 1 < argc) in = argv[++i];
    else if (arg == "--repeat" && i + 1 < argc) repeat = std::max(1, std::stoi(argv[++i]));
    else {
      std::fprintf(stderr, "usage: bench_surfaces --in PAIRS.jsonl [--repeat N]\n");
      return 2;
    }
  }
  std::map<std::pair<std::size_t, bool>, std::vector<double>> by_size;  // (triangles, overlapping) -> us
  SurfaceOverlapWorkspace work;  // as a caller keeps one per thread
  std::printf("%-44s %8s %10s %12s\n", "pair", "tris", "overlap us", "distance us");
  const bool read = bench::for_each_mesh_pair(in, "bench_surfaces", [&](const std::string& id, const Surface& a,
                                                                         const Surface& b) {
    SurfaceOverlap o;
    const double t_overlap = median_us(repeat, [&] { o = surface_overlap(a, b, work); });
    double t_distance = 0;
    if (!o.intersect) t_distance = median_us(repeat, [&] { (void)surface_distance(a, b); });
    const std::size_t tris = a.triangles.size() + b.triangles.size();
    std::printf("%-44s %8zu %10.2f %12.2f\n", id.c_str(), tris, t_overlap, t_distance);
    by_size[{tris, o.volume > 0}].push_back(t_overlap + t_distance);
  });
  if (!read) return 2;
  std::printf("\n%8s %12s %6s %12s\n", "tris", "kind", "pairs", "median us");
  for (auto& [key, t] : by_size) {
    std::sort(t.begin(), t.end());
    std::printf("%8zu %12s %6zu %12.2f\n", key.first, key.second ? "overlapping" : "apart", t.size(), t[t.size() / 2]);
  }
}
