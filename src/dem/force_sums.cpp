// The sums of a force evaluation (stages.hpp).
#include "stages.hpp"

namespace gjkdem::dem::detail {

void sum_forces(World& w, std::size_t updated) {
  const std::vector<StepContact>& contacts = w.work.contacts;
  // Sums in the fixed order of the contact list: the same bits for any thread count.
  StepStats& stats = w.stats;
  stats = {};
  stats.box_updates = static_cast<int>(updated);
  // The periodic cell's stress: sum of f x branch (b's centre, or image,
  // from a's centre or the wall's contact point).
  CellTensor virial{};
  const bool periodic = w.cell.active();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const StepContact& c = contacts[k];
    if (!c.active) {
      w.pairs[k].history = {};  // a contact that ended forgets its springs
      continue;
    }
    Body& b = w.bodies[c.b];
    const Vec3 shift = shift_of(w, c);
    push_b(b, c, shift);
    if (!c.a_is_plane) push_a(w.bodies[c.a], c);
    if (periodic) {
      add_virial(virial, c.force, virial_branch(w.bodies, c, shift));
      // A deforming cell works on the bodies through the images' motion.
      if (c.image != kNoImage) stats.wall_power -= dot(c.force, affine_velocity(w.cell_rate, shift));
    }
    w.pairs[k].history = c.history;
    // Power of a driven side on the other: its velocity field against the
    // force and torque it exerts (c.force and c.torque act on b).
    const std::uint32_t motion_a = c.a_is_plane ? w.planes[c.a].motion : w.bodies[c.a].motion;
    if (motion_a) stats.wall_power += driven_power(w.work.motion_frames[motion_a - 1], c.force, c.torque);
    if (b.motion) stats.wall_power -= driven_power(w.work.motion_frames[b.motion - 1], c.force, c.torque);
    stats.elastic_energy += c.elastic;
    ++stats.contacts;
    if (c.a_is_plane || w.bodies[c.a].fixed || b.fixed) ++stats.wall_contacts;
  }
  if (periodic)
    for (int k = 0; k < 6; ++k) w.cell_stress[k] = virial[k] / cell_volume(w.cell);
}

}  // namespace gjkdem::dem::detail
