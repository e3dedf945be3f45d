#pragma once
// What a step's splits leave for the force evaluation that follows them
// (breakage.hpp): a fragment's contacts begin where its grain's were, and
// the smaller, stiffer fragments would store more energy on the same overlap
// than the grain did. The grains' stored energy per side they touched, and
// which grain each fragment came from, let that evaluation relax the
// fragments' contacts to what their grain held (relax_inherited_contacts).
// Made by apply_splits on every rank alike, used up by the next evaluation.
#include <cstdint>
#include <vector>

#include "gjkdem/math/real.hpp"

namespace gjkdem::dem {

/// What a grain's contacts with one side (a body or plane wall, by id)
/// stored when it broke: their elastic energy (J) and overlap volume (m^3,
/// the volume law's; 0 under the others), summed in contact-list order.
struct InheritedContact {
  std::uint64_t other = 0;
  Real energy = 0;
  Real volume = 0;
};

struct SplitInheritance {
  struct Fragment {
    std::uint64_t id = 0;      ///< the fragment's
    std::uint64_t grain = 0;   ///< the grain it came from
    Real share = 0;            ///< its part of the grain's volume
  };
  /// Two sides by id, lower first: a grain and what it touched (both broken
  /// grains where two broke against each other).
  struct Sides {
    std::uint64_t lo = 0, hi = 0;
    Real energy = 0, volume = 0;
  };
  std::vector<Fragment> fragments;  ///< by id
  std::vector<Sides> sides;         ///< by (lo, hi)
  bool empty() const noexcept { return sides.empty(); }
};

/// The share of the stiffness a contact between bodies (or a wall) of ids
/// `a` and `b` may keep so that it stores no more than the part of its
/// grain's energy that falls to it: 1 for contacts no split left, and for
/// the two fragments of one grain (they touch on their cut). The part is
/// the contact's share of the grain's overlap volume with that side under
/// the volume law (the fragments partition the grain, so the parts sum to
/// the whole), the fragments' shares of their grains' volumes otherwise.
Real inherited_scale(const SplitInheritance& inherited, std::uint64_t a, std::uint64_t b, Real volume, Real elastic,
                     bool by_volume) noexcept;

}  // namespace gjkdem::dem
