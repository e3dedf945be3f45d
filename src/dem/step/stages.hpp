#pragma once
// The stages of a force evaluation, each in its own file, each taking the
// spans and values it reads and writes; the stage plan (step/stage_plan.cpp)
// hands each its part of the world, in the plan's order. Internal to src/dem.
#include <cstddef>
#include <cstdint>
#include <span>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/contact_force.hpp"
#include "gjkdem/dem/periodic.hpp"
#include "gjkdem/dem/step_context.hpp"
#include "gjkdem/dem/step_workspace.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem::detail {

/// broad_phase/candidates.cpp: the candidate body pairs (work.candidates, and in a
/// periodic world work.candidate_images) from the bodies' boxes: moving and
/// driven bodies against each other by the sweep (two driven ones never
/// touch: `any_driven` says there may be some), moving against fixed ones
/// from the static tree. `periodic`: the cell the search takes, null
/// without one.
void find_candidates(std::span<const Body> bodies, std::span<const Aabb> boxes, const PeriodicCell* periodic,
                     bool any_driven, int threads, StepWorkspace& work);

/// contacts/contact_list.cpp: the contact list (results.contacts and results.keys) in
/// pair-key order from the candidates and the plane walls the boxes reach,
/// a contact per pair of compound parts whose bounding spheres meet; a
/// domain (`domain` not null) lists only pairs with a body it owns.
void list_contacts(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                   std::span<const PlaneWall> planes, std::span<const Aabb> boxes, const PeriodicCell& cell,
                   const DomainRole* domain, const StepWorkspace& work, StepResults& results);

/// contacts/surface_patch_stage.cpp: each listed contact of a surface grain replaced by
/// one per patch (its geometry found, its slot matched against `last`, the
/// pair store of the last evaluation, keys kept in order); a pair the model
/// cannot take, or a body through a plane wall, stays one contact with that
/// status. Nothing happens in a world without surface grains.
void expand_surface_contacts(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                             std::span<const PlaneWall> planes, const PeriodicCell& cell,
                             std::span<const PairState> last, int threads, StepResults& results,
                             StepWorkspace& work);

/// contacts/wall_crossing.cpp: the first listed contact (in list order) of a moving
/// body with a mesh wall piece whose triangle (ShapeTemplate::wall_face) the
/// body's centre crossed during the last step of length `dt` (the centre's
/// path taken back by its velocity, relative to a driven piece): ThroughWall
/// naming the piece and the body, else Ok. A body that far in is past
/// holding: past the middle of the wall its contact pushes it on through.
StepReport find_wall_crossing(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                              std::span<const MotionFrame> motion_frames, const PeriodicCell& cell,
                              std::span<const StepContact> contacts, Real dt);

/// contacts/body_crossing.cpp: the first active contact (in list order) of two
/// convex bodies (no compounds, surface grains, shells or wall pieces),
/// deeper than kDeepOverlapRel of the smaller's radius of curvature, where a
/// body's centre lies inside the other: ThroughBody naming the two, else Ok.
/// The overlap is then deeper than the body is thick there, and the contact
/// pushes the two on through each other, not apart.
StepReport find_body_crossing(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                              const PeriodicCell& cell, std::span<const StepContact> contacts);

/// contacts/contact_sides.cpp: what the contact laws see of each side of a contact,
/// from the bodies' make-up, the driven motions' frames at this step's time
/// and a deforming cell's velocity gradient.
struct SideSources {
  Makeup makeup;
  std::span<const MotionFrame> motion_frames;
  CellTensor cell_rate{};
};
/// A plane wall (fixed, or moving with its motion's frame).
ContactSide plane_side(const SideSources& sources, const PlaneWall& plane);
/// A body, or a part of a compound (`part`, whose own radius of curvature
/// and volume the laws use), at its image moved by `shift`, which moves
/// with b and the deforming cell.
ContactSide side_of(const SideSources& sources, const Body& body, std::uint32_t part, const Vec3& shift = {});

/// contacts/force_sums.cpp: the contacts' forces and torques added to their bodies
/// in the fixed order of the contact list (the same bits for any thread
/// count), the pairs' springs kept or forgotten (`pairs` aligned with
/// `contacts`); returns the stats (contacts/contact_sums.hpp:
/// the driven walls' power included, but for box_updates). In a periodic
/// world (`cell` active) the contacts' stress is written to `cell_stress`
/// and the deforming cell's power (`cell_rate`) counted.
StepStats sum_forces(std::span<const StepContact> contacts, std::span<Body> bodies, std::span<PairState> pairs,
                     std::span<const PlaneWall> planes, std::span<const MotionFrame> motion_frames,
                     const PeriodicCell& cell, const CellTensor& cell_rate, CellTensor& cell_stress);

}  // namespace gjkdem::dem::detail
