// split_polytope (shape/split.hpp): the two pieces of a polytope cut by a
// plane hold, together, its volume, first moment and second moment (the
// inertia about a common point: the parallel-axis theorem) to round-off, for
// random polyhedra cut by random planes through them, and for the
// degenerate cuts: a plane through vertices and edges, along a face, beyond
// the polytope. Each piece lies on its side of the plane.
#include "gjkdem/shape/split.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "gjkdem/shape/mass_properties.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem {
namespace {

struct Moments {
  Real volume = 0;
  Vec3 first;   // volume x centroid
  Mat3 second;  // inertia about the origin, per unit density
};

Moments moments_of(const Polytope& p) {
  const MassProperties m = mass_properties(Shape{p});
  Moments out{m.volume, m.centroid * m.volume, m.inertia};
  // Parallel axes: about the origin, I + V (|c|^2 1 - c c^T).
  const Vec3 c = m.centroid;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.second.row[i][j] += m.volume * ((i == j ? dot(c, c) : 0) - c[i] * c[j]);
  return out;
}

// The pieces together against the whole, relative to its volume, its size
// times its volume, and its size squared times its volume.
void expect_conserved(const Polytope& whole, const PolytopeSplit& s, Real size, Real tol) {
  ASSERT_TRUE(s.below && s.above);
  const Moments w = moments_of(whole), a = moments_of(*s.below), b = moments_of(*s.above);
  EXPECT_NEAR(a.volume + b.volume, w.volume, tol * w.volume);
  EXPECT_LT(length(a.first + b.first - w.first), tol * size * w.volume);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(a.second.row[i][j] + b.second.row[i][j], w.second.row[i][j], tol * size * size * w.volume);
}

void expect_on_sides(const PolytopeSplit& s, const Vec3& n, Real offset, Real size) {
  for (const Vec3& v : s.below->data->vertices) EXPECT_LE(dot(n, v) - offset, 1e-12 * size * length(n));
  for (const Vec3& v : s.above->data->vertices) EXPECT_GE(dot(n, v) - offset, -1e-12 * size * length(n));
}

TEST(Split, RandomPolyhedraCutByRandomPlanesKeepTheirMoments) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<Real> u(-1, 1);
  int cuts = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Real size = std::pow(10.0, u(rng) * 3);  // 1e-3 to 1e3
    const int vertices = 4 + static_cast<int>(rng() % 60);
    const Polytope p = std::get<Polytope>(random_polyhedron(vertices, size, rng).core);
    // A plane through a point inside (between the centroid and a vertex).
    const Vec3 n{u(rng), u(rng), u(rng)};
    const Vec3 inside = p.data->centroid + (p.data->vertices[rng() % p.data->vertices.size()] - p.data->centroid) *
                                               (0.9 * (u(rng) + 1) / 2);
    const Real offset = dot(n, inside);
    const PolytopeSplit s = split_polytope(p, n, offset);
    if (!s.below || !s.above) continue;  // a cut near a vertex can leave a sliver under the hull's tolerance
    ++cuts;
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_conserved(p, s, size, 1e-12);
    expect_on_sides(s, n, offset, size);
    // A piece's hull made again from its vertices is the piece, bit for bit:
    // how a checkpoint makes a fragment's template again (breakage.hpp).
    for (const Polytope* piece : {&*s.below, &*s.above}) {
      const Polytope again = make_polytope(piece->data->vertices);
      ASSERT_EQ(again.data->vertices.size(), piece->data->vertices.size());
      EXPECT_EQ(std::memcmp(again.data->vertices.data(), piece->data->vertices.data(),
                            piece->data->vertices.size() * sizeof(Vec3)), 0);
      EXPECT_EQ(again.data->volume, piece->data->volume);
      EXPECT_EQ(again.data->triangles.size(), piece->data->triangles.size());
    }
  }
  EXPECT_GT(cuts, 280);
}

TEST(Split, DegenerateCutsThroughVerticesEdgesAndFaces) {
  std::vector<Vec3> corners;
  for (int k = 0; k < 8; ++k) corners.push_back({k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0});
  const Polytope cube = make_polytope(corners);
  // Through two opposite edges (x = y): two triangular prisms of half the volume.
  const PolytopeSplit diagonal = split_polytope(cube, {1, -1, 0}, 0);
  expect_conserved(cube, diagonal, 2, 1e-14);
  EXPECT_NEAR(diagonal.below->data->volume, 4, 1e-14);
  EXPECT_EQ(diagonal.below->data->vertices.size(), 6u);
  // Through three vertices (x + y + z = 1): a corner tetrahedron of volume 4/3.
  const PolytopeSplit corner = split_polytope(cube, {1, 1, 1}, 1);
  expect_conserved(cube, corner, 2, 1e-14);
  EXPECT_NEAR(corner.above->data->volume, 4.0 / 3, 1e-14);
  // Along a face, and beyond the cube: one side is the cube, the other empty.
  for (const Real offset : {1.0, 1.5, -1.0, -3.0}) {
    const PolytopeSplit none = split_polytope(cube, {0, 0, 1}, offset);
    EXPECT_EQ(none.below.has_value(), offset > 0) << offset;
    EXPECT_EQ(none.above.has_value(), offset < 0) << offset;
    const Polytope& kept = none.below ? *none.below : *none.above;
    EXPECT_EQ(kept.data->volume, cube.data->volume);
  }
  // Through the middle, parallel to faces: two boxes of 1 x 2 x 2.
  const PolytopeSplit half = split_polytope(cube, {2, 0, 0}, 0);
  EXPECT_NEAR(half.below->data->volume, 4, 1e-14);
  EXPECT_NEAR(length(half.below->data->centroid - Vec3{-0.5, 0, 0}), 0, 1e-15);
  EXPECT_THROW(split_polytope(cube, {0, 0, 0}, 0), std::invalid_argument);
  EXPECT_THROW(split_polytope(cube, {0, 0, 1}, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace gjkdem
