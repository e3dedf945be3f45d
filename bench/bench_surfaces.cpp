// Time of the surface queries on pairs of meshes (the query format's mesh
// pairs, e.g. ../shared/data/nonconvex/rocks.in.jsonl): per pair, the median
// of `repeat` timed calls of surface_overlap (and surface_distance where the
// solids are apart), surfaces built once; one line per pair, then the median
// per size (triangles of A + B) and kind.
//   build/bench/bench_surfaces --in PAIRS.jsonl [--repeat N]
// With --hulls, the pairs of convex polytopes instead (e.g.
// ../shared/data/pairs/poly-many.in.jsonl): the overlap by clipping
// (overlap, what their contacts take) against surface_overlap of their hull
// surfaces (built once), both medians and the relative difference of the
// volumes, then the medians over the overlapping pairs.
//   build/bench/bench_surfaces --hulls --in PAIRS.jsonl [--repeat N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "gjkdem/collide/surface_distance.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "gjkdem/shape/surface.hpp"
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

// The convex polytope pairs of `path`: clipping against surface_overlap.
int hulls(const std::string& path, int repeat) {
  std::ifstream file(path);
  if (!file) {
    std::fprintf(stderr, "bench_surfaces: cannot read '%s'\n", path.c_str());
    return 2;
  }
  OverlapWorkspace clip_work;
  SurfaceOverlapWorkspace surface_work;
  std::vector<double> clip_us, surface_us;
  std::printf("%-50s %6s %6s %11s %11s %9s\n", "pair", "tris a", "tris b", "clip us", "surface us", "rel diff");
  std::string line;
  while (std::getline(file, line)) {
    if (io::is_skipped_line(line)) continue;
    std::string id;
    const io::PairInput p = io::parse_pair(line, id);
    const Polytope* pa = std::get_if<Polytope>(&p.a.shape.core);
    const Polytope* pb = std::get_if<Polytope>(&p.b.shape.core);
    if (!pa || !pb || p.a.shape.margin > 0 || p.b.shape.margin > 0) continue;
    const Surface a = moved(polytope_surface(*pa), p.a.pose), b = moved(polytope_surface(*pb), p.b.pose);
    OverlapResult clipped;
    SurfaceOverlap exact;
    const double t_clip = median_us(repeat, [&] { clipped = overlap(p.a.shape, p.a.pose, p.b.shape, p.b.pose, clip_work); });
    const double t_surface = median_us(repeat, [&] { exact = surface_overlap(a, b, surface_work); });
    const Real diff = clipped.volume > 0 ? std::fabs(clipped.volume - exact.volume) / clipped.volume : exact.volume;
    std::printf("%-50s %6zu %6zu %11.1f %11.1f %9.1e\n", id.c_str(), a.triangles.size(), b.triangles.size(), t_clip,
                t_surface, diff);
    if (clipped.volume > 0) clip_us.push_back(t_clip), surface_us.push_back(t_surface);
  }
  if (clip_us.empty()) return 0;
  std::sort(clip_us.begin(), clip_us.end());
  std::sort(surface_us.begin(), surface_us.end());
  std::printf("\n%zu overlapping pairs: median clip %.1f us (largest %.1f), surface_overlap %.1f us (largest %.1f)\n",
              clip_us.size(), clip_us[clip_us.size() / 2], clip_us.back(), surface_us[surface_us.size() / 2],
              surface_us.back());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string in;
  int repeat = 21;
  bool hull_pairs = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--in" && i + 1 < argc) in = argv[++i];
    else if (arg == "--repeat" && i + 1 < argc) repeat = std::max(1, std::stoi(argv[++i]));
    else if (arg == "--hulls") hull_pairs = true;
    else {
      std::fprintf(stderr, "usage: bench_surfaces [--hulls] --in PAIRS.jsonl [--repeat N]\n");
      return 2;
    }
  }
  if (hull_pairs) return hulls(in, repeat);
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
