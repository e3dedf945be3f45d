#pragma once
// Convex hull of a point cloud in 3D, with the flat, collinear and single-point
// cases reported rather than failed.
#include <array>
#include <span>
#include <vector>

#include "gjkdem/math/vec2.hpp"
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

enum class HullDimension { Empty, Point, Segment, Polygon, Solid };

struct ConvexHull {
  HullDimension dimension = HullDimension::Empty;
  std::vector<Vec3> vertices;                ///< hull vertices only (interior/duplicate points dropped)
  std::vector<std::array<int, 3>> triangles; ///< outward (counter-clockwise) triangles, Solid only
  bool manifold = false;                     ///< triangles form a closed 2-manifold (Euler check passed)
  /// Coplanar triangles merged into convex polygons (vertex indices, counter-
  /// clockwise seen from outside); filled when manifold.
  std::vector<std::vector<int>> facets;
  std::vector<Vec3> facet_normals;           ///< unit, outward, one per facet
  /// facet_neighbors[f][k]: the facet across edge (facets[f][k], facets[f][k+1]).
  std::vector<std::vector<int>> facet_neighbors;
};

/// Merges the coplanar neighbours of a manifold hull's triangles into facets
/// (triangles whose normals agree within kHullParallelTol and whose planes are
/// kHullRelTol-close). Called by convex_hull.
void merge_coplanar_facets(ConvexHull& hull);

/// Hull of `points`. Points within kHullRelTol * (bounding diagonal) of a face
/// plane count as on it, and of one another as one point; no face folds
/// against its neighbour by more than that. For a Polygon the vertices are the
/// 2D hull in order; for a Segment its two ends.
ConvexHull convex_hull(std::span<const Vec3> points);

/// Planar convex hull (Andrew's monotone chain): indices of the hull vertices
/// in counter-clockwise order. Duplicates, interior points and points within
/// `tol` (a length) of a hull edge are dropped; fewer than 3 distinct points
/// come back as they are (distinct ones, sorted).
std::vector<int> convex_hull_2d(std::span<const Vec2> points, Real tol = 0);

/// The same without allocating (the narrow phase's witnesses): `scratch` holds
/// at least 3 x points.size() ints; the hull's indices are written to its
/// start, and their count returned.
std::size_t convex_hull_2d(std::span<const Vec2> points, Real tol, std::span<int> scratch) noexcept;

}  // namespace gjkdem
