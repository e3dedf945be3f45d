#pragma once
// Contacts of surface grains (body.hpp, ShapeTemplate::surface_grain): the
// overlap of two closed surfaces, or of one and a plane wall, split into its
// connected pieces, the patches (contact/surface_overlap.hpp,
// contact/surface_half_space.hpp). Each patch is a contact of its own, with
// the convex overlap's geometry restricted to it: the volume, the normal
// along its vector area S_A, Feng's line of action from S_A and its first
// moment, the mean depth V / |S_A| over the contact area, and (on a plane
// wall) the depth integral, of which the Hertz and linear laws take an
// energy (contact_force.hpp, docs/contact.md).
//
// A patch keeps its springs from step to step by its slot, the last field of
// its pair key: each patch found now takes the slot of the nearest patch of
// the same pair last step (its anchor: its centroid in the shape frame of
// the body of lower id, kept in the pair store) when that lies within
// kPatchMatchRel of the smaller body's size; the others take the smallest
// free slots. Two hooked rings keep two contacts whose springs never swap.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "gjkdem/contact/surface_half_space.hpp"
#include "gjkdem/contact/surface_margin.hpp"
#include "gjkdem/contact/surface_overlap.hpp"
#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/contact_geometry.hpp"
#include "gjkdem/dem/material.hpp"
#include "gjkdem/math/union_find.hpp"

namespace gjkdem::dem {

struct SurfacePatchContact {
  ContactGeometry geometry;  ///< normal a -> b
  Vec3 centroid;             ///< of the patch's volume, world
};

/// One thread's scratch for surface contacts (memory reused from call to call).
struct SurfaceScratch {
  PosedSurfaceScratch posed;           ///< against another surface
  HalfSpaceScratch half_space;         ///< against a plane
  SurfaceMarginScratch margin;         ///< against triangles with a margin
  std::vector<MarginTriangle> margin_triangles;  ///< in the grain's frame
  std::vector<MarginContact> margin_contacts;
  std::vector<MarginTriangle> margin_pieces;     ///< a job's pieces, world
  std::vector<SurfacePatchContact> margin_found;
  std::vector<std::uint32_t> margin_hosts;
  std::vector<std::uint32_t> shell_near;  ///< a shell's triangles near the other body
  UnionFind shell_corners;                ///< a shell's corners against a plane
  std::vector<Real> shell_heights;
  std::vector<Vec3> shell_at;  ///< a shell's corners, world
  struct PlanePatch {
    std::uint32_t root;
    Real weight, depth;
    Vec3 point;  ///< weighted sum
  };
  std::vector<PlanePatch> shell_plane;  ///< a shell's patches against a plane
};


/// The patches of two placed surfaces, largest first. Returns Touching, or
/// when a piece of the overlap has volume but no contact area
/// (has_contact_area), so that nothing can push them apart: Engulfed when
/// the piece is the smaller solid whole, Pierced when it is not (a cube
/// punched through a thin plate: the plate's faces inside it, and its sides
/// inside the plate, each add up to nothing).
GeometryStatus surface_patches(const std::shared_ptr<const Surface>& a, const Transform& pose_a,
                     const std::shared_ptr<const Surface>& b, const Transform& pose_b,
                     SurfaceScratch& scratch, std::vector<SurfacePatchContact>& out);

/// Whether the solids of two placed surfaces meet: their overlap has a
/// patch, or one lies wholly inside the other. Where a generator or an
/// inflow finds room beside surface grains: the hollow of a bowl or a ring
/// is free, which their convex hulls fill.
bool surfaces_meet(const std::shared_ptr<const Surface>& a, const Transform& pose_a,
                   const std::shared_ptr<const Surface>& b, const Transform& pose_b, SurfaceScratch& scratch,
                   std::vector<SurfacePatchContact>& patches);

/// Where the hulls of a body about to be placed and of `other` (a template
/// at `other_pose`) meet: whether the body meets other's solid, a compound
/// part by part, a surface grain by its surface, a thin shell by its
/// triangles within their margin, any other by its hull. The body is its
/// shape at `pose`, and `surface` (null: none) the closed surface it meets
/// surfaces and shells by (`surface_grain`: that surface is its solid, not
/// a bound of it). Generators and inflows find room by it: a bowl's hollow,
/// a tray's and an L's notch are free.
bool placed_body_meets(const Shape& shape, const Transform& pose, const std::shared_ptr<const Surface>& surface,
                       bool surface_grain, const ShapeTemplate& other, const Transform& other_pose,
                       SurfaceScratch& scratch, std::vector<SurfacePatchContact>& patches);
/// The patches of a placed surface (b) beyond a plane wall (a), largest
/// first. Returns false when the whole surface lies beyond the plane (the
/// body went through: no cut face can push it back).
bool plane_surface_patches(const PlaneWall& wall, const Surface& b, const Transform& pose_b, SurfaceScratch& scratch,
                           std::vector<SurfacePatchContact>& out);

/// A mesh wall's piece (margin_piece) placed at `pose`: its triangle in
/// world coordinates, with its margin.
inline MarginTriangle placed_margin_triangle(const ShapeTemplate& piece, const Transform& pose) noexcept {
  const Triangle& t = *margin_piece(piece);
  return {{apply(pose, t.v[0]), apply(pose, t.v[1]), apply(pose, t.v[2])}, piece.shape.margin};
}

/// The contacts of a placed surface grain (or a thin shell's triangles:
/// shell_triangles) with the triangles of a mesh wall's pieces (world
/// coordinates) under the Hertz and linear laws: the seed's margin model
/// (contact/surface_margin.hpp), one a patch however many pieces it
/// touches; crossing pairs push to the side of the grain's point inside
/// (TriangleSet::inside: its solid's centroid). Each has a depth and a
/// point midway across the margin, no volume or area; normals point from
/// the wall to the grain. `hosts` gets, per contact, the triangle its
/// deepest pair touches. The grain's own margin (a shell's: TriangleSet::
/// margin) is added to each triangle's: they meet within both.
void margin_patches(const TriangleSet& grain, const Transform& pose, std::span<const MarginTriangle> triangles,
                    SurfaceScratch& scratch,
                    std::vector<SurfacePatchContact>& out, std::vector<std::uint32_t>& hosts);

/// A thin shell's triangles as margin contacts meet them (TriangleSet).
inline TriangleSet shell_triangles(const Shell& s) noexcept {
  return {s.vertices, s.triangles, &s.tree, s.mass.centroid, s.margin};
}

/// The triangles a part of the Margin route's grain side (pair_route:
/// a surface, or a shell) meets a mesh wall's piece by, in its frame.
inline TriangleSet margin_triangles(const ShapeTemplate& grain, std::uint32_t part) noexcept {
  return grain.shell ? shell_triangles(*grain.shell) : triangles_of(*surface_of(grain, part));
}

/// A thin shell's triangles placed at `pose`, those whose boxes meet `near`
/// (world), in world coordinates with the shell's margin.
void placed_shell_triangles(const Shell& shell, const Transform& pose, const Aabb& near, SurfaceScratch& scratch,
                            std::vector<MarginTriangle>& out);

/// The contacts of a thin shell (its template `shell`, placed at
/// `shell_pose`) with another body's part by the margin model, normals
/// a -> b (`shell_is_a`): the part's surface, or another shell's triangles
/// (the margins of both), against the shell's triangles near it. A shape
/// without volume it cannot meet: Unsupported (the run stops naming the
/// pair). (A mesh wall's pieces meet shells as they meet grains.)
GeometryStatus shell_patches(const ShapeTemplate& shell, const Transform& shell_pose, const ShapeTemplate& other,
                             std::uint32_t part, const PartPose& other_pose, bool shell_is_a,
                             SurfaceScratch& scratch, std::vector<SurfacePatchContact>& out);
/// The contacts of a placed thin shell with a plane wall: its corners
/// within its margin of the plane, those of one triangle one patch (as the
/// margin model groups a grain's triangles), each with the depth rho - h of
/// its lowest corner (h: its height above the plane) at the depth-weighted
/// mean of the corners, midway across the margin; normals along the wall's.
/// Returns false when every corner lies more than the margin beyond the
/// plane (the shell went through: nothing can push it back).
bool plane_shell_patches(const PlaneWall& wall, const Shell& shell, const Transform& pose, SurfaceScratch& scratch,
                         std::vector<SurfacePatchContact>& out);

/// Slots for one pair's patches: `anchors` of the patches now; `last` the
/// slots and anchors of its patches last step. Nearest pairs first, a patch
/// within `reach` of a last anchor takes its slot; the others take the
/// smallest slots not used last step (a vanished patch's springs are not
/// handed on). `slots` gets one per anchor.
struct PatchAnchor {
  std::uint32_t slot;
  Vec3 anchor;
};
void match_patch_slots(std::span<const Vec3> anchors, std::span<const PatchAnchor> last, Real reach,
                       std::vector<std::uint32_t>& slots);

}  // namespace gjkdem::dem
