#include "gjkdem/shape/tessellate.hpp"

#include <gtest/gtest.h>

#include <random>

#include "gjkdem/contact/overlap.hpp"

namespace gjkdem {
namespace {


TEST(Tessellate, BoundIsCertifiedAndShrinks) {
  const Shape shapes[] = {make_sphere(1), Shape{Ellipsoid{{1, 0.3, 0.6}}}, Shape{Superellipsoid{{1, 1, 0.5}, 0.3, 1.7}},
                          Shape{Cylinder{0.5, 1}, 0.05}, Shape{Cone{0.7, 0.4}}};
  for (const Shape& s : shapes) {
    const Tessellation coarse = tessellate(s, 200), fine = tessellate(s, 3000);
    EXPECT_LT(fine.hausdorff_bound, coarse.hausdorff_bound);
    // Certificate: points of the shape (support points in random directions)
    // never pass a facet pushed out by the bound.
    const PolytopeData& d = *fine.polytope.data;
    std::mt19937_64 rng(5);
    std::normal_distribution<double> g;
    for (int k = 0; k < 100; ++k) {
      const Vec3 p = support(s, {g(rng), g(rng), g(rng)});
      double worst = -1e300;
      for (std::size_t f = 0; f < d.facet_normals.size(); ++f) {
        const Vec3 n = d.facet_normals[f];
        worst = std::fmax(worst, dot(n, p) - dot(n, d.vertices[d.facet_vertices[d.facet_begin[f]]]));
      }
      EXPECT_LE(worst, fine.hausdorff_bound + 1e-15);
    }
  }
  // A sphere of 3000 directions: the bound is about r * (angular spacing)^2 / 2.
  EXPECT_LT(tessellate(make_sphere(1), 3000).hausdorff_bound, 3e-3);
  // Flat faces come out exact: a box is its own tessellation.
  const Tessellation box = tessellate(Shape{Box{{1, 2, 3}}}, 100);
  EXPECT_EQ(box.polytope.data->vertices.size(), 8u);
  EXPECT_NEAR(box.hausdorff_bound, 0.0, 1e-14);
}

TEST(Tessellate, OverlapOfTessellatedSpheresBracketsTheLens) {
  // Equal unit spheres 1 apart: lens volume 5 pi / 12.
  const Tessellation t = tessellate(make_sphere(1), 4000);
  const Shape poly{t.polytope};
  OverlapWorkspace work;
  const OverlapResult r = overlap(poly, Transform::identity(), poly, Transform::from({1, 0, 0}, {}), work);
  const double lens = 5 * kPi / 12;
  const double lens_area = 2 * (2 * kPi * 1 * 0.5);  // two caps of height 0.5
  EXPECT_LE(r.volume, lens);
  EXPECT_GE(r.volume, lens - t.hausdorff_bound * lens_area * 1.01);
  EXPECT_NEAR(r.contact_normal.x, 1.0, 1e-3);
}

}  // namespace
}  // namespace gjkdem
