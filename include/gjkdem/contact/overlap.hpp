#pragma once
// The overlap region of two convex shapes, the heart of the volume-based
// contact model (the seed text's second stage): its volume, its centroid (the
// contact point), and the area vectors S_A, S_B of the parts of its surface
// that lie on A's and on B's boundary. The closed surface sums to zero area, so
// S_A = -S_B for a proper overlap; normalize(S_A - S_B) is the contact normal,
// pointing from A to B, and equals minus the gradient of the volume with
// respect to B's position.
//
// Polytope-like cores without margins (polytope, box, triangle) are clipped
// exactly (overlap.cpp); two big hulls deep in each other, where clipping
// costs the most, are met as closed surfaces instead (surface_overlap.hpp,
// kClipWorkBeyondSurfaces), exact too. For other shapes the closed forms that
// exist are used: empty overlaps, sphere-sphere lenses, and one shape inside
// the other. Everything else reports OverlapStatus::Unsupported (curved
// overlaps need the tessellation of the contact-generation issue).
#include <utility>
#include <vector>

#include "gjkdem/collide/gjk_cache.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "gjkdem/math/vec2.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

enum class OverlapStatus {
  Empty,        ///< no overlap, or one of zero volume (touching, flat shapes)
  Overlapping,  ///< volume > 0; centroid valid; normal valid when has_normal
  Unsupported,  ///< this pair of shapes has no exact overlap computation yet
};

struct OverlapResult {
  OverlapStatus status = OverlapStatus::Empty;
  Real volume = 0;       ///< overlap volume, >= 0
  Vec3 centroid;         ///< world frame (Overlapping only)
  Vec3 area_a;           ///< S_A: sum of area * outward normal over the faces on A's boundary, world
  Vec3 area_b;           ///< S_B: same for B
  /// Contact area: the area bounded by the intersection line (the closed curve
  /// where the two surfaces cross), as a vector area equal to S_A; this is |S_A|.
  Real contact_area = 0;
  bool has_normal = false;
  Vec3 contact_normal;   ///< unit normalize(S_A - S_B), world, A -> B (when has_normal)
  /// M_A = sum over A's faces of (face centroid x area vector), world origin.
  Vec3 moment_a;
  /// Energy-conserving point of application of Feng's volume-based contact
  /// theory (CMAME 373, 2021): the force along S_A acts on the line through this
  /// point, x = (S_A x M_A) / |S_A|^2 (the point of that line nearest the world
  /// origin). Valid when has_normal and the pair was clipped (polytope-like)
  /// or met as surfaces (big hulls). On that way has_normal follows the
  /// surface grains' rule (kEngulfedAreaRel), not kContactNormalRelTol: a
  /// nearly engulfed pair may differ between the two ways.
  Vec3 application_point;
  bool has_application_point = false;
  int faces = 0;         ///< faces of the clipped polyhedron (statistics)
};

/// Reusable buffers of the clipping; keep one per thread so repeated calls do
/// not allocate. After a clipped overlap it also holds the overlap polyhedron
/// (see overlap_surface and intersection_line).
struct OverlapWorkspace {
  std::vector<Vec3> points[2];
  std::vector<int> face_begin[2];
  std::vector<unsigned char> face_body[2];
  std::vector<Vec3> face_normal[2];
  std::vector<Vec3> cap;
  std::vector<Vec2> cap_flat;  ///< cap points in the clipping plane's coordinates
  std::vector<int> cap_order;  ///< their hull's order, and the hull's scratch
  std::vector<Real> side;  ///< each point's signed distance to the plane clipping it
  std::vector<unsigned char> face_place;  ///< each face's: inside the plane, beyond it, or cut
  std::vector<unsigned char> on_plane;    ///< a cut face's points: on the plane or not
  std::vector<Vec3> cut_entry, cut_exit;  ///< where each cut face comes back to the kept side and leaves it
  std::vector<int> cut_next;              ///< the cut face whose entry is each one's exit (-1: none)
  struct Plane {
    Vec3 n;  ///< unit, outward
    Real d;  ///< n . x on the plane
  };
  std::vector<Plane> planes;
  std::vector<Plane> touching;  ///< planes of B that a face of A lies in
  int result = -1;       ///< buffer holding the last clipped polyhedron; -1: none
  Transform frame;       ///< its frame (A's pose) for mapping to the world
  PosedSurfaceScratch surfaces;  ///< big hulls' overlaps found as their surfaces'
};

/// One triangle of the overlap polyhedron's surface, world frame, tagged by
/// the body whose boundary it lies on (0: A, 1: B, 2: both, for coplanar faces
/// of aligned bodies); counter-clockwise from outside.
struct OverlapTriangle {
  Vec3 v[3];
  int body;
};

/// The triangulated surface of the last clipped overlap (empty when the last
/// call did not clip: closed forms, big hulls met as surfaces, empty or
/// unsupported pairs).
std::vector<OverlapTriangle> overlap_surface(const OverlapWorkspace& work);

/// The intersection line of the last clipped overlap: the edges where a face on
/// A's boundary meets a face on B's (faces on both are on neither side), world frame, each as (start, end) oriented
/// along A's face. They form closed loops; `tol` matches end points (length).
std::vector<std::pair<Vec3, Vec3>> intersection_line(const OverlapWorkspace& work, Real tol);

/// The face planes (world frame, outward) of a polytope or box without
/// margin placed by `to` that pass within `radius` of `centre`: what clips a
/// solid inside that ball. False when the ball lies wholly beyond one of
/// them (nothing of it is inside the shape).
bool face_planes_near(const Shape& shape, const Transform& to, const Vec3& centre, Real radius,
                      std::vector<OverlapWorkspace::Plane>& planes);

/// `cache` (optional) warm-starts the GJK test that decides whether two
/// clippable shapes meet at all, as for intersect(): the DEM engine passes
/// the pair's. Other pairs are tested cold (classify_depth).
OverlapResult overlap(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                      OverlapWorkspace& work, GjkCache* cache = nullptr);

}  // namespace gjkdem
