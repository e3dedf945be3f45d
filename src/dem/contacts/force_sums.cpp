// The sums of a force evaluation (stages.hpp).
#include "contacts/contact_sums.hpp"
#include "step/stages.hpp"

namespace gjkdem::dem::detail {

StepStats sum_forces(std::span<const StepContact> contacts, std::span<Body> bodies, std::span<PairState> pairs,
                     std::span<const PlaneWall> planes, std::span<const MotionFrame> motion_frames,
                     const PeriodicCell& cell, const CellTensor& cell_rate, CellTensor& cell_stress) {
  // Sums in the fixed order of the contact list: the same bits for any thread count.
  ContactSums sums;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const StepContact& c = contacts[k];
    if (!c.active) {
      pairs[k].history = {};  // a contact that ended forgets its springs
      continue;
    }
    const Vec3 shift = image_shift_of(cell, c);
    push_b(bodies[c.b], c, shift);
    if (!c.a_is_plane) push_a(bodies[c.a], c);
    pairs[k].history = c.history;
    sums.add(contact_term(c, shift, bodies, planes, motion_frames, cell, cell_rate));
  }
  if (cell.active()) cell_stress = sums.cell_stress(cell);
  return sums.stats();
}

}  // namespace gjkdem::dem::detail
