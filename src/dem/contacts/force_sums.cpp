// The sums of a force evaluation (stages.hpp).
#include "step/stages.hpp"

namespace gjkdem::dem::detail {

StepStats sum_forces(std::span<const StepContact> contacts, std::span<Body> bodies, std::span<PairState> pairs,
                     std::span<const PlaneWall> planes, std::span<const MotionFrame> motion_frames,
                     const PeriodicCell& cell, const CellTensor& cell_rate, CellTensor& cell_stress) {
  // Sums in the fixed order of the contact list: the same bits for any thread count.
  StepStats stats;
  // The periodic cell's stress: sum of f x branch (b's centre, or image,
  // from a's centre or the wall's contact point).
  CellTensor virial{};
  const bool periodic = cell.active();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const StepContact& c = contacts[k];
    if (!c.active) {
      pairs[k].history = {};  // a contact that ended forgets its springs
      continue;
    }
    Body& b = bodies[c.b];
    const Vec3 shift = image_shift_of(cell, c);
    push_b(b, c, shift);
    if (!c.a_is_plane) push_a(bodies[c.a], c);
    if (periodic) {
      add_virial(virial, c.force, virial_branch(bodies, c, shift));
      // A deforming cell works on the bodies through the images' motion.
      if (c.image != kNoImage) stats.wall_power -= dot(c.force, affine_velocity(cell_rate, shift));
    }
    pairs[k].history = c.history;
    // Power of a driven side on the other: its velocity field against the
    // force and torque it exerts (c.force and c.torque act on b).
    const std::uint32_t motion_a = c.a_is_plane ? planes[c.a].motion : bodies[c.a].motion;
    if (motion_a) stats.wall_power += driven_power(motion_frames[motion_a - 1], c.force, c.torque);
    if (b.motion) stats.wall_power -= driven_power(motion_frames[b.motion - 1], c.force, c.torque);
    stats.elastic_energy += c.elastic;
    ++stats.contacts;
    if (c.a_is_plane || bodies[c.a].fixed || b.fixed) ++stats.wall_contacts;
  }
  if (periodic)
    for (int k = 0; k < 6; ++k) cell_stress[k] = virial[k] / cell_volume(cell);
  return stats;
}

}  // namespace gjkdem::dem::detail
