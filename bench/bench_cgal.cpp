// Overlap volume of convex polytope pairs: gjkdem's clipping against CGAL's
// corefinement (Polygon_mesh_processing::corefine_and_compute_intersection on
// Surface_mesh with the exact-constructions kernel, then PMP::volume), the
// route polyhedral DEM codes take today. Same pairs, one process run; prints
// ns per pair, the ratio and the largest relative volume difference.
//   bench_cgal [--pairs N] [--repeat R]
// With --surfaces, the same for the overlapping mesh pairs of a query-format
// file (closed surfaces, convex or not): surface_overlap against the
// corefinement, CGAL as the oracle of the volume, the centroid and the
// number of pieces (connected components of the intersection's faces), then
// the median times per size (triangles of A + B) and their ratio.
//   bench_cgal --surfaces PAIRS.jsonl [--repeat R]
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "mesh_pairs.hpp"
#include "random_pairs.hpp"

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh to_mesh(const gjkdem::Shape& s, const gjkdem::Transform& pose) {
  const auto& d = *std::get<gjkdem::Polytope>(s.core).data;
  Mesh m;
  std::vector<Mesh::Vertex_index> v;
  for (const auto& p : d.vertices) {
    const gjkdem::Vec3 w = gjkdem::apply(pose, p);
    v.push_back(m.add_vertex(Kernel::Point_3(w.x, w.y, w.z)));
  }
  for (const auto& t : d.triangles) m.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return m;
}

Mesh to_mesh(const gjkdem::Surface& s) {
  Mesh m;
  std::vector<Mesh::Vertex_index> v;
  for (const auto& p : s.vertices) v.push_back(m.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  for (const auto& t : s.triangles) m.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return m;
}

template <class F>
double median_ns(int repeat, std::size_t n, F&& pass) {
  std::vector<double> t;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    t.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / n);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

// The overlapping mesh pairs of `path` against CGAL's corefinement.
int compare_surfaces(const std::string& path, int repeat) {
  using namespace gjkdem;
  struct Row {
    std::vector<double> ours, theirs;  // us per pair
  };
  std::map<std::size_t, Row> by_size;
  SurfaceOverlapWorkspace work;
  double worst_volume = 0, worst_centroid = 0, worst_touching = 0;
  int pieces_differ = 0, compared = 0, touching = 0, refused = 0;
  std::string worst_centroid_id;
  const bool read = bench::for_each_mesh_pair(path, "bench_cgal", [&](const std::string& id, const Surface& a,
                                                                      const Surface& b) {
    SurfaceOverlap o = surface_overlap(a, b, work);
    if (!(o.volume > 0)) return;
    const Mesh ma = to_mesh(a), mb = to_mesh(b);
    Mesh out;
    bool made = false;
    const double t_ours = median_ns(repeat, 1, [&] { o = surface_overlap(a, b, work); }) / 1e3;
    const double t_cgal = median_ns(repeat, 1, [&] {
      Mesh x = ma, y = mb;  // corefinement modifies its inputs
      out.clear();
      made = PMP::corefine_and_compute_intersection(x, y, out);
    }) / 1e3;
    if (!made) {  // the intersection is not a manifold surface (pieces touching along an edge): CGAL gives none
      std::printf("%s: CGAL cannot make the intersection (not manifold); ours %.6e in %zu patches\n", id.c_str(),
                  o.volume, o.patches.size());
      ++refused;
      return;
    }
    const auto exact_volume = PMP::volume(out);
    if (CGAL::is_zero(exact_volume)) {  // the solids only touch: no centroid; ours must be round-off
      const double solid = std::min(mass_properties(a).volume, mass_properties(b).volume);
      worst_touching = std::max(worst_touching, o.volume / solid);
      ++touching;
      return;
    }
    const double volume = CGAL::to_double(exact_volume);
    const auto c = PMP::centroid(out);
    const Vec3 centroid{CGAL::to_double(c.x()), CGAL::to_double(c.y()), CGAL::to_double(c.z())};
    auto component = out.add_property_map<Mesh::Face_index, std::size_t>("f:component").first;
    const std::size_t pieces = PMP::connected_components(out, component);
    const double size = std::cbrt(volume);
    worst_volume = std::max(worst_volume, std::fabs(o.volume - volume) / volume);
    if (length(o.centroid - centroid) / size > worst_centroid) {
      worst_centroid = length(o.centroid - centroid) / size;
      worst_centroid_id = id;
    }
    ++compared;
    if (pieces != o.patches.size()) {
      ++pieces_differ;
      const double solid = std::min(mass_properties(a).volume, mass_properties(b).volume);
      std::printf("%s: %zu pieces in CGAL's intersection, %zu patches (volume %.2e of the smaller solid)\n",
                  id.c_str(), pieces, o.patches.size(), volume / solid);
    }
    Row& row = by_size[a.triangles.size() + b.triangles.size()];
    row.ours.push_back(t_ours), row.theirs.push_back(t_cgal);
  });
  if (!read) return 2;
  if (compared == 0) {
    std::printf("no overlapping pair\n");
    return 0;
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  std::printf("| triangles of A + B | overlapping pairs | gjkdem surface_overlap us | CGAL corefinement us | ratio |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const auto& [tris, row] : by_size)
    std::printf("| %zu | %zu | %.1f | %.1f | %.1f |\n", tris, row.ours.size(), median(row.ours), median(row.theirs),
                median(row.theirs) / median(row.ours));
  std::printf("\n%d pairs: largest relative volume difference %.2e, centroid difference %.2e of the overlap's "
              "size (cube root of its volume; %s), pieces differing in %d\n",
              compared, worst_volume, worst_centroid, worst_centroid_id.c_str(), pieces_differ);
  if (refused > 0) std::printf("%d pairs CGAL cannot intersect (not manifold)\n", refused);
  if (touching > 0)
    std::printf("%d pairs only touch (CGAL's exact volume 0): ours at most %.2e of the smaller solid\n", touching,
                worst_touching);
  return 0;
}

int main(int argc, char** argv) {
  using namespace gjkdem;
  int count = 200, repeat = 3;
  std::string surfaces;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--pairs" && i + 1 < argc) count = std::atoi(argv[++i]);
    else if (a == "--repeat" && i + 1 < argc) repeat = std::atoi(argv[++i]);
    else if (a == "--surfaces" && i + 1 < argc) surfaces = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_cgal [--pairs N] [--repeat R] | --surfaces PAIRS.jsonl [--repeat R]\n");
      return 2;
    }
  }
  if (count < 1 || repeat < 1) return 2;
  if (!surfaces.empty()) return compare_surfaces(surfaces, repeat);
  // Intersecting pairs only: the volume is what is compared.
  std::vector<bench::PolytopePair> pairs;
  OverlapWorkspace work;
  for (const auto& p : bench::random_pairs(3 * count, 8, 64, 21))
    if (static_cast<int>(pairs.size()) < count && overlap(p.a, p.pose_a, p.b, p.pose_b, work).volume > 0) pairs.push_back(p);
  std::vector<Mesh> ma, mb;
  for (const auto& p : pairs) { ma.push_back(to_mesh(p.a, p.pose_a)); mb.push_back(to_mesh(p.b, p.pose_b)); }

  std::vector<double> ours(pairs.size()), theirs(pairs.size());
  const double ns_ours = median_ns(repeat, pairs.size(), [&] {
    for (std::size_t i = 0; i < pairs.size(); ++i)
      ours[i] = overlap(pairs[i].a, pairs[i].pose_a, pairs[i].b, pairs[i].pose_b, work).volume;
  });
  const double ns_cgal = median_ns(repeat, pairs.size(), [&] {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      Mesh a = ma[i], b = mb[i], out;  // corefinement modifies its inputs
      PMP::corefine_and_compute_intersection(a, b, out);
      theirs[i] = CGAL::to_double(PMP::volume(out));
    }
  });
  double worst = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) worst = std::max(worst, std::fabs(ours[i] - theirs[i]) / theirs[i]);
  std::printf("| pairs | gjkdem overlap ns | CGAL corefine+volume ns | ratio | max relative volume difference |\n");
  std::printf("|---|---|---|---|---|\n| %zu | %.0f | %.0f | %.1f | %.2e |\n", pairs.size(), ns_ours, ns_cgal,
              ns_cgal / ns_ours, worst);
  return 0;
}
