#pragma once
// A force evaluation's sums over its touching contacts, written once: each
// contact gives its keyed share (contact_term), and ContactSums adds the
// shares in key order. One rank adds its contact list as it goes
// (contacts/force_sums.cpp); domains gather every rank's shares on rank 0,
// sort them by key (the serial list's order) and add them with the same
// ContactSums (domains/domains.cpp): the same bits for any number of ranks.
// Internal to src/dem.
#include <cstdint>
#include <span>
#include <type_traits>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/motion.hpp"
#include "gjkdem/dem/periodic.hpp"
#include "gjkdem/dem/step_workspace.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem::detail {

/// What a term holds (bits of ContactTerm::holds).
enum ContactTermHolds : std::uint8_t {
  kTermWall = 1,      ///< a plane wall or a fixed body on either side (StepStats::wall_contacts)
  kTermImage = 2,     ///< b at an image of a periodic cell: the cell's power through it
  kTermDrivenA = 4,   ///< a driven: its motion's power
  kTermDrivenB = 8,   ///< b driven: its motion's power
  kTermPeriodic = 16, ///< a periodic world: the virial's force and branch
};

/// A touching contact's share of the sums.
struct ContactTerm {
  PairKey key;                            ///< set where terms are sorted (domains)
  Real elastic = 0;                       ///< energy stored in it (J)
  Real on_image = 0, on_a = 0, on_b = 0;  ///< power of the cell through b's image, of a's motion, of b's (W)
  Vec3 force{}, branch{};                 ///< the virial's (a periodic cell)
  std::uint8_t holds = 0;                 ///< ContactTermHolds bits
};
static_assert(std::is_trivially_copyable_v<ContactTerm>);

/// The share of touching contact `c` of bodies `bodies`, b at its image
/// moved by `shift` (image_shift_of).
inline ContactTerm contact_term(const StepContact& c, const Vec3& shift, std::span<const Body> bodies,
                                std::span<const PlaneWall> planes, std::span<const MotionFrame> motion_frames,
                                const PeriodicCell& cell, const CellTensor& cell_rate) noexcept {
  ContactTerm t;
  t.elastic = c.elastic;
  const Body& b = bodies[c.b];
  if (c.a_is_plane || bodies[c.a].fixed || b.fixed) t.holds |= kTermWall;
  if (cell.active()) {
    t.holds |= kTermPeriodic;
    t.force = c.force, t.branch = virial_branch(bodies, c, shift);
    // A deforming cell works on the bodies through the images' motion.
    if (c.image != kNoImage) t.holds |= kTermImage, t.on_image = dot(c.force, affine_velocity(cell_rate, shift));
  }
  // Power of a driven side on the other: its velocity field against the
  // force and torque it exerts (c.force and c.torque act on b).
  const std::uint32_t motion_a = c.a_is_plane ? planes[c.a].motion : bodies[c.a].motion;
  if (motion_a) t.holds |= kTermDrivenA, t.on_a = driven_power(motion_frames[motion_a - 1], c.force, c.torque);
  if (b.motion) t.holds |= kTermDrivenB, t.on_b = driven_power(motion_frames[b.motion - 1], c.force, c.torque);
  return t;
}

/// The sums of terms added in key order.
class ContactSums {
 public:
  void add(const ContactTerm& t) noexcept {
    if (t.holds & kTermPeriodic) add_virial(virial_, t.force, t.branch);
    if (t.holds & kTermImage) stats_.wall_power -= t.on_image;
    if (t.holds & kTermDrivenA) stats_.wall_power += t.on_a;
    if (t.holds & kTermDrivenB) stats_.wall_power -= t.on_b;
    stats_.elastic_energy += t.elastic;
    ++stats_.contacts;
    if (t.holds & kTermWall) ++stats_.wall_contacts;
  }
  /// Energy, counts and the driven sides' and the cell's power.
  const StepStats& stats() const noexcept { return stats_; }
  /// The contacts' stress on a periodic cell: the virial over its volume.
  CellTensor cell_stress(const PeriodicCell& cell) const noexcept {
    CellTensor s = virial_;
    for (Real& v : s) v /= cell_volume(cell);
    return s;
  }

 private:
  StepStats stats_;
  CellTensor virial_{};
};

}  // namespace gjkdem::dem::detail
