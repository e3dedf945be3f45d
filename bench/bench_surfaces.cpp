// Time of the surface queries on pairs of meshes (the query format's mesh
// pairs, e.g. ../shared/data/nonconvex/rocks.in.jsonl): per pair, the median
// of `repeat` timed calls of surface_overlap (and surface_distance where the
// solids are apart), surfaces built once; one line per pair, then the median
// per size (triangles of A + B) and kind.
//   build/bench/bench_surfaces --in PAIRS.jsonl [--repeat N]
// With --hulls, the pairs of convex polytopes instead (e.g.
// ../shared/data/pairs/poly-many.in.jsonl): overlap(), what their contacts
// take (the clip, or their surfaces where big hulls lie deep in each
// other), against surface_overlap of their hull surfaces (built once,
// posed), both medians and the relative difference of the volumes, then the
// medians over the overlapping pairs.
//   build/bench/bench_surfaces --hulls --in PAIRS.jsonl [--repeat N]
// With --ellipsoid-hulls, pairs of one ellipsoid's hull (the grains of a DEM
// bed: 130, 250 and 600 support directions) at overlaps from a graze to a
// third of the volume, turned alike or not: overlap() (and the way it took)
// against the surfaces' overlap.
//   build/bench/bench_surfaces --ellipsoid-hulls [--repeat N]
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

// The convex polytope pairs of `path`: overlap() against surface_overlap.
int hulls(const std::string& path, int repeat) {
  std::ifstream file(path);
  if (!file) {
    std::fprintf(stderr, "bench_surfaces: cannot read '%s'\n", path.c_str());
    return 2;
  }
  OverlapWorkspace work;
  SurfaceOverlapWorkspace surface_work;
  std::vector<double> overlap_us, surface_us;
  std::printf("%-50s %6s %6s %11s %11s %9s\n", "pair", "tris a", "tris b", "overlap us", "surface us", "rel diff");
  std::string line;
  while (std::getline(file, line)) {
    if (io::is_skipped_line(line)) continue;
    std::string id;
    const io::PairInput p = io::parse_pair(line, id);
    const Polytope* pa = std::get_if<Polytope>(&p.a.shape.core);
    const Polytope* pb = std::get_if<Polytope>(&p.b.shape.core);
    if (!pa || !pb || p.a.shape.margin > 0 || p.b.shape.margin > 0) continue;
    const Surface a = moved(polytope_surface(*pa), p.a.pose), b = moved(polytope_surface(*pb), p.b.pose);
    OverlapResult found;
    SurfaceOverlap exact;
    const double t_overlap = median_us(repeat, [&] { found = overlap(p.a.shape, p.a.pose, p.b.shape, p.b.pose, work); });
    const double t_surface = median_us(repeat, [&] { exact = surface_overlap(a, b, surface_work); });
    const Real diff = found.volume > 0 ? std::fabs(found.volume - exact.volume) / found.volume : exact.volume;
    std::printf("%-50s %6zu %6zu %11.1f %11.1f %9.1e\n", id.c_str(), a.triangles.size(), b.triangles.size(), t_overlap,
                t_surface, diff);
    if (found.volume > 0) overlap_us.push_back(t_overlap), surface_us.push_back(t_surface);
  }
  if (overlap_us.empty()) return 0;
  std::sort(overlap_us.begin(), overlap_us.end());
  std::sort(surface_us.begin(), surface_us.end());
  std::printf("\n%zu overlapping pairs: median overlap() %.1f us (largest %.1f), surface_overlap %.1f us (largest %.1f)\n",
              overlap_us.size(), overlap_us[overlap_us.size() / 2], overlap_us.back(), surface_us[surface_us.size() / 2],
              surface_us.back());
  return 0;
}

// Two hulls of one ellipsoid (semi-axes 12, 9 and 7 mm) from `directions`
// support points on a Fibonacci sphere, B moved along x.
int ellipsoid_hulls(int repeat) {
  const Vec3 radii{0.012, 0.009, 0.007};
  std::printf("%9s %5s %4s %9s %11s %9s %11s %9s\n", "triangles", "gap", "turn", "volume/V", "overlap us", "way",
              "surface us", "rel diff");
  for (const int directions : {130, 250, 600}) {
    std::vector<Vec3> points;
    for (int i = 0; i < directions; ++i) {
      const Real z = 1 - (2 * i + 1) / Real(directions), r = std::sqrt(1 - z * z), turn = i * 2.399963229728653;
      const Vec3 d{r * std::cos(turn), r * std::sin(turn), z};
      const Vec3 rd{radii.x * d.x, radii.y * d.y, radii.z * d.z};
      points.push_back(Vec3{radii.x * rd.x, radii.y * rd.y, radii.z * rd.z} / length(rd));
    }
    Shape shape;
    shape.core = make_polytope(points);
    const Polytope& hull = std::get<Polytope>(shape.core);
    const std::shared_ptr<const Surface> surface = hull_surface(hull);
    OverlapWorkspace work;
    PosedSurfaceScratch scratch;
    for (const Real gap : {0.0235, 0.023, 0.022, 0.020, 0.017, 0.012})
      for (const bool turned : {false, true}) {
        const Transform pa = Transform::identity();
        const Transform pb = Transform::from({gap, 0.001, 0.0005}, turned ? normalized(Quat{0.9, 0.1, 0.3, 0.2}) : Quat{});
        OverlapResult found;
        SurfaceOverlap exact;
        Transform frame;
        const double t_overlap = median_us(repeat, [&] { found = overlap(shape, pa, shape, pb, work); });
        if (found.volume == 0) continue;
        const bool as_surfaces = overlap_surface(work).empty();
        const double t_surface =
            surface ? median_us(repeat, [&] { exact = posed_surface_overlap(surface, pa, surface, pb, scratch, frame); }) : 0;
        std::printf("%9zu %5.4f %4s %9.2e %11.1f %9s %11.1f %9.1e\n", hull.data->triangles.size(), gap,
                    turned ? "yes" : "no", found.volume / hull.data->volume, t_overlap, as_surfaces ? "surfaces" : "clip",
                    t_surface, std::fabs(found.volume - exact.volume) / found.volume);
      }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string in;
  int repeat = 21;
  bool hull_pairs = false, ellipsoids = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--in" && i + 1 < argc) in = argv[++i];
    else if (arg == "--repeat" && i + 1 < argc) repeat = std::max(1, std::stoi(argv[++i]));
    else if (arg == "--hulls") hull_pairs = true;
    else if (arg == "--ellipsoid-hulls") ellipsoids = true;
    else {
      std::fprintf(stderr, "usage: bench_surfaces [--hulls] --in PAIRS.jsonl [--repeat N] | --ellipsoid-hulls [--repeat N]\n");
      return 2;
    }
  }
  if (ellipsoids) return ellipsoid_hulls(repeat);
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
