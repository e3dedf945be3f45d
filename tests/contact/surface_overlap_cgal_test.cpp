// surface_overlap against an independent oracle: CGAL's exact corefinement
// (Polygon_mesh_processing::corefine_and_compute_intersection with the
// exact-constructions kernel). Random non-convex pairs of the project's own
// making, not the shared samples: star-shaped rocks, tori, L and U prisms
// and bowls, turned and placed at random so that they overlap. The volume,
// centroid and number of pieces (connected components of the intersection's
// faces) must agree, and swapping A and B must not change them. Pairs whose
// intersection is not a manifold surface (pieces touching along an edge)
// CGAL cannot make; they are counted and left to the other tests.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gjkdem/contact/surface_overlap.hpp"
#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "shape/surface_shapes.hpp"

namespace gjkdem {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh to_mesh(const Surface& s) {
  Mesh m;
  std::vector<Mesh::Vertex_index> v;
  for (const Vec3& p : s.vertices) v.push_back(m.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  for (const auto& t : s.triangles) m.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return m;
}

// A star-shaped rock: the hull of `n` random directions, each corner then
// pulled in to a random radius in [0.55, 1] (dents: not convex).
test::Mesh star_rock(int n, std::mt19937_64& rng) {
  std::normal_distribution<Real> normal;
  std::uniform_real_distribution<Real> radius(0.55, 1.0);
  std::vector<Vec3> points;
  for (int k = 0; k < n; ++k) points.push_back(normalized(Vec3{normal(rng), normal(rng), normal(rng)}));
  const ConvexHull hull = convex_hull(points);
  test::Mesh m;
  for (const Vec3& p : hull.vertices) m.vertices.push_back(p * radius(rng));
  for (const auto& t : hull.triangles)
    m.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                           static_cast<std::uint32_t>(t[2])});
  return m;
}

// One of the families, about the size of a unit ball.
test::Mesh random_solid(std::mt19937_64& rng) {
  switch (std::uniform_int_distribution<int>(0, 4)(rng)) {
    case 0:
    case 1: return star_rock(std::uniform_int_distribution<int>(12, 80)(rng), rng);
    case 2: return test::torus(0.7, 0.25, 16, 8);
    case 3: {
      test::Mesh m = test::u_prism(0.6);
      for (Vec3& v : m.vertices) v = (v - Vec3{1.5, 1, 0.3}) * 0.6;
      return m;
    }
    default: {
      test::Mesh m = test::l_prism(0.6);
      for (Vec3& v : m.vertices) v = (v - Vec3{0.8, 0.8, 0.3}) * 0.8;
      return m;
    }
  }
}

test::Mesh placed(test::Mesh m, const Transform& pose) {
  for (Vec3& v : m.vertices) v = apply(pose, v);
  return m;
}

TEST(SurfaceOverlapCgal, RandomNonConvexPairsMatchTheExactCorefinement) {
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<Real> offset(-0.8, 0.8);
  SurfaceOverlapWorkspace work;
  int compared = 0, refused = 0, several = 0;
  for (int trial = 0; trial < 240; ++trial) {
    const Transform pose_a = Transform::from({offset(rng), offset(rng), offset(rng)}, random_rotation(rng));
    const Transform pose_b = Transform::from({offset(rng), offset(rng), offset(rng)}, random_rotation(rng));
    const Surface a = test::surface_of(placed(random_solid(rng), pose_a));
    const Surface b = test::surface_of(placed(random_solid(rng), pose_b));
    const SurfaceOverlap o = surface_overlap(a, b, work);
    Mesh x = to_mesh(a), y = to_mesh(b), out;
    if (!PMP::corefine_and_compute_intersection(x, y, out)) {
      ++refused;
      continue;
    }
    const auto exact_volume = PMP::volume(out);
    const Real smaller = std::fmin(a.volume, b.volume);
    if (CGAL::is_zero(exact_volume)) {
      EXPECT_LT(o.volume, 1e-12 * smaller) << "trial " << trial;
      continue;
    }
    const Real volume = CGAL::to_double(exact_volume);
    if (volume < 1e-6 * smaller) continue;  // a sliver: its centroid and pieces are round-off's
    ++compared;
    const auto c = PMP::centroid(out);
    const Vec3 centroid{CGAL::to_double(c.x()), CGAL::to_double(c.y()), CGAL::to_double(c.z())};
    auto component = out.add_property_map<Mesh::Face_index, std::size_t>("f:component").first;
    const std::size_t pieces = PMP::connected_components(out, component);
    const Real size = std::cbrt(volume);
    several += pieces > 1;
    EXPECT_NEAR(o.volume, volume, 1e-9 * volume) << "trial " << trial;
    EXPECT_LT(length(o.centroid - centroid), 1e-7 * size) << "trial " << trial;
    EXPECT_EQ(o.patches.size(), pieces) << "trial " << trial;
    const SurfaceOverlap swapped = surface_overlap(b, a, work);
    EXPECT_NEAR(swapped.volume, o.volume, 1e-12 * volume) << "trial " << trial;
    EXPECT_EQ(swapped.patches.size(), o.patches.size()) << "trial " << trial;
  }
  // Most pairs overlap, some in several pieces, and CGAL makes most intersections.
  EXPECT_GT(compared, 120);
  EXPECT_GT(several, 5);
  EXPECT_LT(refused, 10);
  std::printf("%d pairs compared (%d in several pieces), %d CGAL could not make\n", compared, several, refused);
}

}  // namespace
}  // namespace gjkdem
