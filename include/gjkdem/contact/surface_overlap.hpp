#pragma once
// The overlap of two solids bounded by closed triangle surfaces
// (shape/surface.hpp), convex or not: the volume and centroid of A ∩ B and
// its vector areas, exactly up to rounding, with no decomposition.
//
// The boundary of A ∩ B is the part of A's surface inside B and the part of
// B's inside A. Each triangle's part is bounded by a cycle of segments: the
// pieces of its edges inside the other solid and the segments where it
// crosses the other surface's triangles. Where a segment starts and ends is
// decided exactly (predicates.hpp, B symbolically moved by delta), so the
// segments of a triangle close into cycles whatever the rounding of the
// points; fans over the cycles give the volume (cones from one point), the
// centroid and the vector areas S_A and S_B (the seed's area-weighted
// normal, query-format-mesh.md). Only triangle pairs whose boxes meet are
// looked at, besides a walk over the vertices near the overlap that carries
// the inside/outside status along the edges; a triangle that nothing
// crosses counts whole (one fan) when inside, with no cycle.
#include <cmath>
#include <memory>
#include <vector>

#include "gjkdem/shape/surface.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

/// The engulfed-area rule: a piece of volume V whose contact area is at most
/// kEngulfedAreaRel V^(2/3) has none (it is zero, or round-off).
inline bool has_contact_area(Real area, Real volume) { return area > kEngulfedAreaRel * std::cbrt(volume * volume); }

/// How a piece of an overlap meets, one rule for every reader (the surface
/// grains' contacts, the query's normals): by its contact area; or without
/// one, as the smaller solid (of volume `smaller_volume`) lies wholly inside
/// the other or their surfaces coincide (a mesh against itself: no normal),
/// or as one passed through the other (a cube punched through a thin plate:
/// the faces of each inside the other add up to nothing; the query still
/// writes normalize(S_A - S_B) where it is not zero, as its spec says).
enum class PieceMeeting { ByArea, WhollyInside, Through };
inline PieceMeeting piece_meeting(Real area, Real volume, Real smaller_volume) {
  if (has_contact_area(area, volume)) return PieceMeeting::ByArea;
  return volume >= (1 - kWhollyInsideVolumeRel) * smaller_volume ? PieceMeeting::WhollyInside : PieceMeeting::Through;
}

/// A connected piece of A ∩ B (pieces that touch only along an edge or at a
/// point may come out as one or two).
struct SurfacePatch {
  Real volume = 0;
  Vec3 centroid;
  Vec3 area_a, area_b;  ///< S_A(P), S_B(P): as SurfaceOverlap's, over this piece
  Vec3 area_moment_a;   ///< M_A(P): as SurfaceOverlap's, over this piece
};

struct SurfaceOverlap {
  bool intersect = false;  ///< the solids share a point (touching counts; exact)
  Real volume = 0;         ///< of A ∩ B
  Vec3 centroid;           ///< of A ∩ B (when volume > 0)
  /// Sum of the outward vector areas of the boundary of A ∩ B that lies on
  /// A's surface (area_a) and on B's (area_b); without shared faces
  /// area_a = -area_b, and normalize(area_a - area_b) is the contact normal
  /// from A towards B.
  Vec3 area_a, area_b;
  /// The first moment of area_a about the frame's origin, the integral of
  /// x cross n over A's part of the boundary: a uniform pressure on it pushes
  /// with area_a and turns with area_moment_a (Feng's line of action and
  /// twisting couple, overlap.hpp).
  Vec3 area_moment_a;
  /// The pieces of A ∩ B, largest first; pieces smaller than
  /// kPatchMinRelVolume of the smaller solid are left out (slivers of faces
  /// that only touch), and the totals above are those of the pieces kept.
  std::vector<SurfacePatch> patches;
};

/// Scratch of surface_overlap, kept between calls so that its memory is
/// reused (one per thread; nothing in it outlives a call, so a copy starts
/// empty).
struct SurfaceOverlapWorkspace {
  SurfaceOverlapWorkspace();
  ~SurfaceOverlapWorkspace();
  SurfaceOverlapWorkspace(const SurfaceOverlapWorkspace&);
  SurfaceOverlapWorkspace& operator=(const SurfaceOverlapWorkspace&);
  SurfaceOverlapWorkspace(SurfaceOverlapWorkspace&&) noexcept;
  SurfaceOverlapWorkspace& operator=(SurfaceOverlapWorkspace&&) noexcept;
  struct Scratch;
  std::unique_ptr<Scratch> scratch;
};

/// Scratch of posed_surface_overlap: one surface moved into the other's
/// frame, its memory reused (its topology too, when it is the same surface as
/// last call's), and surface_overlap's.
struct PosedSurfaceScratch {
  SurfaceOverlapWorkspace overlap;
  Surface moved;
  std::shared_ptr<const Surface> moved_from;  ///< what `moved` is a copy of
};

/// The overlap of two surfaces posed apart: the surface of fewer vertices is
/// moved into the other's frame (fewer to move, and coordinates stay near
/// that frame's origin, far from the world's); A stays the first surface.
/// The result is in that frame, whose pose `frame` receives.
SurfaceOverlap posed_surface_overlap(const std::shared_ptr<const Surface>& a, const Transform& pose_a,
                                     const std::shared_ptr<const Surface>& b, const Transform& pose_b,
                                     PosedSurfaceScratch& scratch, Transform& frame);

/// Both surfaces in one frame. Throws std::logic_error if the exact
/// decisions ever fail to close a cycle (a defect, never bad input).
SurfaceOverlap surface_overlap(const Surface& a, const Surface& b, SurfaceOverlapWorkspace& work);
/// The same with a workspace of its own.
SurfaceOverlap surface_overlap(const Surface& a, const Surface& b);

}  // namespace gjkdem
