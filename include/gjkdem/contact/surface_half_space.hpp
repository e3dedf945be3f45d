#pragma once
// The part of a closed surface's solid (shape/surface.hpp) beyond a plane,
// piece by piece: a surface grain against a plane wall. Each triangle is
// clipped by the plane; cones from a point of the plane give each piece's
// volume and centroid (the cut face, on the plane, adds nothing to them), and
// the cut face's area is what closes the piece's vector area. Pieces are the
// connected parts of the submerged surface: two submerged corners of one
// triangle are in one piece (a triangle's part below a plane is convex).
#include <vector>

#include "gjkdem/math/union_find.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem {

/// One connected piece of the solid beyond the plane.
struct HalfSpacePiece {
  Real volume = 0;
  Vec3 centroid;
  Real cut_area = 0;        ///< of the piece's face on the plane
  Real depth_integral = 0;  ///< integral over the piece of its depth below the plane (m^4)
};

struct SurfaceHalfSpace {
  bool submerged = false;  ///< every vertex lies beyond the plane (no cut face can hold it back)
  /// The pieces, largest first; pieces smaller than kPatchMinRelVolume of
  /// the solid are left out (as for two surfaces).
  std::vector<HalfSpacePiece> pieces;
};

/// Per-vertex scratch of surface_half_space, kept between calls so that its
/// memory is reused (one per thread).
struct HalfSpaceScratch {
  std::vector<Real> depth;            ///< below the plane, per vertex
  UnionFind pieces;                   ///< of the submerged vertices
  std::vector<HalfSpacePiece> sums;   ///< per piece root, as it is summed
};

/// The solid of `surface` on the side of the plane through `point` opposite
/// to unit `normal`, everything in the surface's frame.
SurfaceHalfSpace surface_half_space(const Surface& surface, const Vec3& point, const Vec3& normal,
                                    HalfSpaceScratch& scratch);

}  // namespace gjkdem
