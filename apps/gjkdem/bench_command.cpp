// gjkdem bench: load every pair, then time only the queries (contact = the
// overlap region: volume, centroid, area-weighted normal; for mesh pairs the
// surface overlap with its patches, and distance the surfaces'): one untimed warm-up
// pass, then `repeat` timed passes over all pairs; prints one JSON object with
// the median, min and max time per query over the passes. Distance on a file of
// triangle pairs only (no margins) times the batched closed-form kernel
// (triangle_distances), the pairs laid out in its blocks before the clock starts.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gjkdem/collide/triangle_contact.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "input_lines.hpp"

namespace gjkdem::app {
namespace {

// Keeps results observable so the optimiser cannot drop the queries.
volatile double g_sink = 0;

// Every pair two bare triangles: the batched kernel's input, else nothing.
bool triangle_pairs_of(const std::vector<io::PairInput>& pairs, TrianglePairs& out) {
  for (const io::PairInput& p : pairs) {
    const auto* ta = std::get_if<Triangle>(&p.a.shape.core);
    const auto* tb = std::get_if<Triangle>(&p.b.shape.core);
    if (p.a.surface || !ta || !tb || p.a.shape.margin > 0 || p.b.shape.margin > 0) {
      out.clear();
      return false;
    }
    out.push_back(apply(p.a.pose, ta->v[0]), apply(p.a.pose, ta->v[1]), apply(p.a.pose, ta->v[2]),
                  apply(p.b.pose, tb->v[0]), apply(p.b.pose, tb->v[1]), apply(p.b.pose, tb->v[2]));
  }
  return true;
}

}  // namespace

int run_bench(const BenchOptions& opt) {
  const std::string& q = opt.query;
  if (q != "intersect" && q != "distance" && q != "penetration" && q != "contact") {
    std::cerr << "gjkdem bench: unknown --query '" << q << "' (intersect, distance, penetration, contact)\n";
    return 2;
  }
  if (opt.repeat < 1) {
    std::cerr << "gjkdem bench: --repeat must be >= 1\n";
    return 2;
  }
  std::unique_ptr<std::ifstream> in_file;
  std::istream& in = open_input(opt.in, in_file);
  std::vector<io::PairInput> pairs;
  const int errors = for_each_pair(
      in, [&](io::PairInput p) { pairs.push_back(std::move(p)); },
      [](const std::string& id, const std::string& message) {
        std::cerr << "gjkdem bench: " << message << " (id " << id << ")\n";
      });
  if (errors > 0) {
    std::cerr << "gjkdem bench: " << errors << " bad line(s); nothing timed\n";
    return 1;
  }
  if (pairs.empty()) {
    std::cerr << "gjkdem bench: no pairs in the input\n";
    return 1;
  }
  const bool meshes = std::any_of(pairs.begin(), pairs.end(), [](const io::PairInput& p) { return p.a.surface != nullptr; });
  if (meshes && q == "penetration") {
    std::cerr << "gjkdem bench: penetration is not defined for mesh pairs (intersect, distance, contact)\n";
    return 2;
  }
  OverlapWorkspace work;
  SurfaceOverlapWorkspace surface_work;
  TrianglePairs triangles;
  std::vector<TriangleDistanceBlock> triangle_out;
  const bool batched = q == "distance" && triangle_pairs_of(pairs, triangles);
  auto pass = [&] {
    double acc = 0;
    if (batched) {
      triangle_distances(triangles, triangle_out);
      for (std::size_t i = 0; i < triangles.size; ++i) acc += triangle_out[i / kTriangleLanes].distance[i % kTriangleLanes];
      g_sink = g_sink + acc;
      return;
    }
    for (const auto& p : pairs) {
      if (p.a.surface) {  // a mesh pair (both surfaces: parse_pair)
        if (q == "distance") acc += surface_distance(*p.a.surface, *p.b.surface).distance;
        else {
          const SurfaceOverlap o = surface_overlap(*p.a.surface, *p.b.surface, surface_work);
          acc += q == "intersect" ? o.intersect : o.volume;
        }
      } else if (q == "intersect") acc += intersect(p.a.shape, p.a.pose, p.b.shape, p.b.pose);
      else if (q == "distance") acc += distance(p.a.shape, p.a.pose, p.b.shape, p.b.pose).distance;
      else if (q == "penetration") acc += penetration(p.a.shape, p.a.pose, p.b.shape, p.b.pose).depth;
      else acc += overlap(p.a.shape, p.a.pose, p.b.shape, p.b.pose, work).volume;  // contact
    }
    g_sink = g_sink + acc;
  };
  pass();  // warm-up
  std::vector<double> ns;
  for (int r = 0; r < opt.repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    const auto t1 = std::chrono::steady_clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(pairs.size()));
  }
  std::vector<double> sorted = ns;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  std::printf("{\"query\": \"%s\", \"pairs\": %zu, \"repeat\": %d, \"ns_per_query\": %.1f, \"ns_min\": %.1f, \"ns_max\": %.1f%s}\n",
              q.c_str(), pairs.size(), opt.repeat, median, sorted.front(), sorted.back(),
              batched ? (std::string(", \"kernel\": \"triangle_distances\", \"simd\": \"") +
                         triangle_simd_name(triangle_simd_best()) + "\"").c_str()
                      : "");
  return 0;
}

}  // namespace gjkdem::app
