// Overlap volume of convex polytope pairs: gjkdem's clipping against CGAL's
// corefinement (Polygon_mesh_processing::corefine_and_compute_intersection on
// Surface_mesh with the exact-constructions kernel, then PMP::volume), the
// route polyhedral DEM codes take today. Same pairs, one process run; prints
// ns per pair, the ratio and the largest relative volume difference.
//   bench_cgal [--pairs N] [--repeat R]
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gjkdem/contact/overlap.hpp"
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

int main(int argc, char** argv) {
  using namespace gjkdem;
  int count = 200, repeat = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--pairs" && i + 1 < argc) count = std::atoi(argv[++i]);
    else if (a == "--repeat" && i + 1 < argc) repeat = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_cgal [--pairs N] [--repeat R]\n");
      return 2;
    }
  }
  if (count < 1 || repeat < 1) return 2;
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
