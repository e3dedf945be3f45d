#pragma once
// A convex solid cut into the Voronoi cells of sites inside it: the pieces of
// a bonded assembly (issue 31, docs/breakage.md). Cell i holds the points of
// the solid nearer to site i than to any other, the solid cut by the
// bisector planes of i and its neighbours (split.hpp), so the cells tile the
// solid: their volumes add up to its volume to round-off. Two cells that
// share a face of area get a CellFace: where the bond between them sits.
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/math/vec3.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem {

/// The face two cells share.
struct CellFace {
  std::uint32_t a = 0, b = 0;  ///< the cells, a < b
  Vec3 centroid;               ///< of the face (the solid's frame)
  Vec3 normal;                 ///< unit, from a towards b
  Real area = 0;               ///< m^2
  /// The face's polar second moment of area about its centroid (m^4):
  /// sum over its points of |r - centroid|^2 dA.
  Real polar_moment = 0;
};

struct VoronoiCells {
  std::vector<Polytope> cells;  ///< one per site, in the solid's frame
  std::vector<CellFace> faces;  ///< sorted by (a, b)
};

/// Faces smaller than this fraction of the solid's size squared are left
/// out (a corner two cells touch at, or a face cut to a sliver): no bond.
inline constexpr Real kSmallestCellFaceRel = 1e-6;

/// The cells of `sites` (inside `solid`, distinct) and the faces they share.
/// Throws std::invalid_argument for a solid without volume, a site outside
/// it or two sites closer than 1e-9 of its size.
VoronoiCells voronoi_cells(const Polytope& solid, std::span<const Vec3> sites);

}  // namespace gjkdem
