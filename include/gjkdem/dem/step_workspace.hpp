#pragma once
// The scratch of a step: everything a step computes and throws away, kept in
// the world only so that its memory is reused. Nothing here survives into a
// checkpoint; a world restored without it rebuilds it on its first step.
// (What the broad phase keeps that a bit-exact resume needs is state:
// World::search. What passes between the halves of a step, and a domain's
// role in a domain run, is the step's context: step_context.hpp.)
#include <array>
#include <cstdint>
#include <utility>
#include <span>
#include <vector>

#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/dem/broad_phase.hpp"
#include "gjkdem/dem/contact_geometry.hpp"
#include "gjkdem/dem/motion.hpp"
#include "gjkdem/dem/periodic.hpp"
#include "gjkdem/dem/pair_state.hpp"
#include "gjkdem/dem/surface_contact.hpp"

namespace gjkdem::dem {

/// One candidate contact of a force evaluation: bodies (a, b), or plane wall a
/// and body b. Slot k of the contact list goes with entry k of the world's
/// pair store; each slot is written by one thread only.
struct StepContact {
  std::uint32_t a = 0, b = 0;
  std::uint16_t part_a = 0, part_b = 0;  ///< of compounds (0 otherwise)
  std::uint8_t image = kNoImage;  ///< periodic worlds: b's image (periodic.hpp: b moved by image_shift)
  bool a_is_plane = false;
  bool surface = false;     ///< a surface grain's: one patch, its geometry found by expand_surface_contacts
  bool active = false;      ///< touching, after merging the contacts of a wall
  ContactGeometry geometry;
  Vec3 anchor;              ///< surface patches: PairState::anchor now
  // Force law.
  Vec3 force;               ///< on b
  Vec3 torque;              ///< on b, about the world origin
  PairHistory history;      ///< the springs after this evaluation
  Real elastic = 0;         ///< energy stored in the contact (J)
};

/// Where b's image lies from b (periodic worlds; zero without an image).
inline Vec3 image_shift_of(const PeriodicCell& cell, const StepContact& c) noexcept {
  return c.image == kNoImage ? Vec3{} : image_shift(cell, c.image);
}
/// The branch a periodic cell's stress sums force x branch over: from a's
/// centre (or a wall's contact point) to b's image, moved by `shift`.
inline Vec3 virial_branch(std::span<const Body> bodies, const StepContact& c, const Vec3& shift) noexcept {
  return bodies[c.b].position + shift - (c.a_is_plane ? c.geometry.point : bodies[c.a].position);
}

/// What a contact adds to b's force and torque (b at its image, moved by
/// `shift`; torque about b's centre), and to a's: summed in the order of
/// the contact list (step.cpp, and a domain run's gathered world).
inline void push_b(Body& b, const StepContact& c, const Vec3& shift) noexcept {
  b.force += c.force;
  b.torque += c.torque - cross(b.position + shift, c.force);
}
inline void push_a(Body& a, const StepContact& c) noexcept {
  a.force -= c.force;
  a.torque -= c.torque - cross(a.position, c.force);
}

/// Which kinds of template a world holds, so that a stage serving one kind
/// skips the contact list of a world without it. During a run templates are
/// only appended (breakage's fragments), never changed: the templates from
/// `seen` on are all that can add a kind (step.cpp).
struct TemplateKinds {
  std::size_t seen = 0;         ///< templates looked at
  bool surface_grains = false;  ///< one is a surface grain (ShapeTemplate::surface_grain)
  bool wall_faces = false;      ///< one is a mesh wall piece (ShapeTemplate::wall_face)
};

struct StepWorkspace {
  TemplateKinds kinds;
  StaticTree fixed_tree;             ///< of the fixed bodies' boxes
  bool static_ready = false;         ///< fixed_tree and moving are built
  SweepWorkspace sweep;
  std::vector<BodyPair> candidates;  ///< body index pairs (i < j) whose boxes overlap, sorted
  std::vector<std::uint8_t> candidate_images;  ///< periodic worlds: the image of each pair's second body
  bool candidates_current = false;   ///< no box changed since the candidates were found
  std::vector<StepContact> contacts; ///< sorted by pair key, aligned with World::pairs (outputs read the last evaluation's)
  std::vector<PairKey> keys;         ///< the contacts' keys
  std::vector<OverlapWorkspace> overlap;  ///< clipping buffers, one per thread
  std::vector<SurfaceScratch> surface;    ///< surface grains' buffers, one per thread
  std::vector<std::uint32_t> surface_listed;                   ///< contacts of surface grains before expansion
  std::vector<std::vector<SurfacePatchContact>> surface_found; ///< and their patches
  std::vector<GeometryStatus> surface_status;                  ///< and whether they could be found
  /// The listed contacts in jobs (surface_jobs: [begin, end) of surface_order):
  /// one contact, or a grain's contacts with the pieces of one mesh wall.
  std::vector<std::uint32_t> surface_order;
  std::vector<std::array<std::uint32_t, 2>> surface_jobs;
  std::vector<std::array<std::uint32_t, 3>> surface_walls;  ///< per listed contact: (grain, its part, wall group)
  std::vector<StepContact> expanded;      ///< the contact list being expanded (swapped with contacts)
  std::vector<PairKey> expanded_keys;
  std::vector<std::uint32_t> moving;      ///< indices of the moving and driven bodies
  std::vector<Aabb> moving_boxes;         ///< their boxes, for the sweep (and their periodic images)
  std::vector<std::uint32_t> image_body;  ///< periodic worlds: the body of each swept box
  std::vector<std::uint8_t> image_code;   ///< and its image
  std::vector<MotionFrame> motion_frames; ///< per motion, at world.time (place_driven)
  std::vector<Real> bond_energies;        ///< per bond of World::bonds, at the last evaluation (bonds.hpp)
};

}  // namespace gjkdem::dem
