#pragma once
// What a force evaluation finds and the outputs read: the contact list (with
// its keys), the driven motions' frames, the bonds' energies. Results, not
// state (a checkpoint does not hold them: a restored world finds them again
// at its first evaluation) and not scratch (step_workspace.hpp): VTK and
// view frames, measurements, breakage, domains and Python read the last
// evaluation's.
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/contact_geometry.hpp"
#include "gjkdem/dem/motion.hpp"
#include "gjkdem/dem/pair_state.hpp"
#include "gjkdem/dem/periodic.hpp"

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

/// The last force evaluation's results (World::results).
struct StepResults {
  std::vector<StepContact> contacts;      ///< sorted by pair key, aligned with World::pairs
  std::vector<PairKey> keys;              ///< the contacts' keys
  std::vector<MotionFrame> motion_frames; ///< per motion, at World::time (place_driven)
  std::vector<Real> bond_energies;        ///< per bond of World::bonds (bonds.hpp)
};

}  // namespace gjkdem::dem
