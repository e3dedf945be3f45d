// voronoi_cells (shape/voronoi.hpp) against brute force: the cells tile the
// solid (volumes add up; a random point of the solid lies in the cell of its
// nearest site, and in no other); every vertex of a cell is no farther from
// its site than from any other; the cells' surface is the solid's plus twice
// the shared faces; and a cube cut in two has the closed-form face (area a^2,
// polar moment a^4 / 6).
#include "gjkdem/shape/voronoi.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gjkdem/shape/mass_properties.hpp"

namespace gjkdem {
namespace {

Polytope cube(Real half) {
  std::vector<Vec3> v;
  for (int k = 0; k < 8; ++k) v.push_back({k & 1 ? half : -half, k & 2 ? half : -half, k & 4 ? half : -half});
  return make_polytope(v);
}

Real surface_area(const PolytopeData& d) {
  Real area = 0;
  for (const auto& t : d.triangles)
    area += 0.5 * length(cross(d.vertices[t[1]] - d.vertices[t[0]], d.vertices[t[2]] - d.vertices[t[0]]));
  return area;
}

bool contains(const PolytopeData& d, const Vec3& p, Real tol) {
  for (std::size_t f = 0; f + 1 < d.facet_begin.size(); ++f)
    if (dot(d.facet_normals[f], p - d.vertices[d.facet_vertices[d.facet_begin[f]]]) > tol) return false;
  return true;
}

TEST(Voronoi, CubeCutInTwoHasTheClosedFormFace) {
  const Polytope c = cube(0.5);
  const std::vector<Vec3> sites{{-0.25, 0.1, 0}, {0.25, 0.1, 0}};
  const VoronoiCells v = voronoi_cells(c, sites);
  ASSERT_EQ(v.cells.size(), 2u);
  ASSERT_EQ(v.faces.size(), 1u);
  const CellFace& f = v.faces[0];
  EXPECT_EQ(f.a, 0u);
  EXPECT_EQ(f.b, 1u);
  EXPECT_NEAR(f.area, 1.0, 1e-12);
  EXPECT_NEAR(f.polar_moment, 1.0 / 6, 1e-12);
  EXPECT_NEAR(f.normal.x, 1.0, 1e-15);
  EXPECT_NEAR(length(f.centroid), 0.0, 1e-12);
  EXPECT_NEAR(v.cells[0].data->volume, 0.5, 1e-12);
}

TEST(Voronoi, RandomSitesTileTheSolidAsBruteForceHasIt) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (int trial = 0; trial < 8; ++trial) {
    // A random polyhedron, and sites inside it.
    std::vector<Vec3> points;
    for (int k = 0; k < 30; ++k) points.push_back({u(rng), u(rng), u(rng)});
    const Polytope solid = make_polytope(points);
    const PolytopeData& d = *solid.data;
    std::vector<Vec3> sites;
    while (sites.size() < 5u + 5u * static_cast<unsigned>(trial)) {
      const Vec3 p{u(rng), u(rng), u(rng)};
      if (contains(d, p, -1e-3)) sites.push_back(p);
    }
    const VoronoiCells v = voronoi_cells(solid, sites);
    ASSERT_EQ(v.cells.size(), sites.size());
    Real volume = 0, area = 0, faces = 0;
    for (const Polytope& c : v.cells) volume += c.data->volume, area += surface_area(*c.data);
    for (const CellFace& f : v.faces) faces += f.area;
    EXPECT_NEAR(volume, d.volume, 1e-12 * d.volume) << "trial " << trial;
    // Faces below kSmallestCellFaceRel of the size squared are left out.
    const Real pairs = sites.size() * (sites.size() - 1) / 2.0;
    const Real left_out = area - surface_area(d) - 2 * faces;
    EXPECT_GT(left_out, -1e-9 * area) << "trial " << trial;
    EXPECT_LT(left_out, 2 * pairs * kSmallestCellFaceRel * std::cbrt(d.volume * d.volume) + 1e-9 * area)
        << "trial " << trial;
    for (std::size_t i = 0; i < sites.size(); ++i)
      for (const Vec3& corner : v.cells[i].data->vertices)
        for (std::size_t j = 0; j < sites.size(); ++j)
          EXPECT_LE(length(corner - sites[i]), length(corner - sites[j]) + 1e-9) << "cell " << i << " site " << j;
    for (int k = 0; k < 300; ++k) {
      const Vec3 p{u(rng), u(rng), u(rng)};
      if (!contains(d, p, -1e-9)) continue;
      std::size_t nearest = 0;
      for (std::size_t j = 1; j < sites.size(); ++j)
        if (length(p - sites[j]) < length(p - sites[nearest])) nearest = j;
      EXPECT_TRUE(contains(*v.cells[nearest].data, p, 1e-9));
      for (std::size_t j = 0; j < sites.size(); ++j)
        if (j != nearest && length(p - sites[j]) > length(p - sites[nearest]) + 1e-6) {
          EXPECT_FALSE(contains(*v.cells[j].data, p, -1e-9)) << "point in the cell of a farther site";
        }
    }
    // Each face lies on its bisector, between the two cells' sites.
    for (const CellFace& f : v.faces) {
      const Vec3 mid = (sites[f.a] + sites[f.b]) * 0.5;
      EXPECT_NEAR(dot(f.normal, f.centroid - mid), 0.0, 1e-9);
      EXPECT_GT(f.polar_moment, 0.0);
    }
  }
}

TEST(Voronoi, RefusesSitesOutsideOrCoinciding) {
  const Polytope c = cube(0.5);
  const std::vector<Vec3> outside{{0, 0, 0}, {0.7, 0, 0}};
  EXPECT_THROW(voronoi_cells(c, outside), std::invalid_argument);
  const std::vector<Vec3> same{{0.1, 0, 0}, {0.1, 0, 0}};
  EXPECT_THROW(voronoi_cells(c, same), std::invalid_argument);
}

}  // namespace
}  // namespace gjkdem
