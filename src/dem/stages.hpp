#pragma once
// The stages of a force evaluation that read and write the world as a
// whole, each in its own file; step.cpp runs them in order (world.hpp lists
// every stage of a step). Internal to src/dem.
#include <cstddef>
#include <cstdint>

#include "gjkdem/dem/contact_force.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem::detail {

/// candidates.cpp: the candidate body pairs (work.candidates, and their
/// images in a periodic world) from the boxes: moving and driven bodies
/// against each other by the sweep, moving against fixed ones from the
/// static tree.
void find_candidates(World& world, int threads);

/// contact_list.cpp: the contact list (work.contacts and work.keys) in
/// pair-key order from the candidates and the plane walls, a contact per
/// pair of compound parts whose bounding spheres meet; a domain (`domain`
/// not null) lists only pairs with a body it owns.
void list_contacts(World& world, const DomainRole* domain);

/// contact_sides.cpp: what the contact laws see of each side of a contact.
/// A plane wall (fixed, or moving with its motion's frame).
ContactSide plane_side(const World& world, const PlaneWall& plane);
/// A body, or a part of a compound (`part`, whose own radius of curvature
/// and volume the laws use), at its image moved by `shift`, which moves
/// with b and the deforming cell.
ContactSide side_of(const World& world, const Body& body, std::uint32_t part, const Vec3& shift = {});

/// force_sums.cpp: the contacts' forces and torques added to their bodies
/// in the fixed order of the contact list (the same bits for any thread
/// count), the pairs' springs kept or forgotten, and the stats, the driven
/// walls' power and a periodic cell's stress summed.
void sum_forces(World& world, std::size_t box_updates);

/// Where b's image lies from b in a periodic world (zero otherwise).
inline Vec3 shift_of(const World& w, const StepContact& c) { return image_shift_of(w.cell, c); }

}  // namespace gjkdem::dem::detail
