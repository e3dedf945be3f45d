#pragma once
// The one store of what a contact remembers from step to step, keyed by the
// pair of global ids: the GJK warm start while the pair's boxes overlap, and
// the tangential, twisting and rolling springs while it touches. Keyed by
// ids, not indices, so the state follows the bodies through a checkpoint, a
// reordering or a move between MPI domains. Compounds keep one entry
// per pair of parts.
#include <compare>
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/collide/gjk_cache.hpp"
#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

/// The most parts of a compound (part indices key the pair store in 16 bits).
inline constexpr std::size_t kMaxCompoundParts = 1024;

/// The ids of a pair, smaller first (a plane wall's id is above every body's),
/// and for compounds the parts in contact: lo's part << 16 | hi's part; for
/// surface grains the patch's slot (surface_contact.hpp).
struct PairKey {
  std::uint64_t lo = 0, hi = 0;
  std::uint32_t parts = 0;
  friend constexpr auto operator<=>(const PairKey&, const PairKey&) = default;
};

/// Bodies a and b, parts part_a and part_b (0 for bodies of one convex shape).
constexpr PairKey pair_key(std::uint64_t a, std::uint64_t b, std::uint32_t part_a = 0,
                           std::uint32_t part_b = 0) noexcept {
  return a < b ? PairKey{a, b, part_a << 16 | part_b} : PairKey{b, a, part_b << 16 | part_a};
}

/// Springs of a touching contact. Each is world-frame and is carried into
/// the current tangent plane before use (contact_force.hpp).
struct PairHistory {
  Vec3 spring;   ///< tangential displacement (m)
  Real twist = 0;  ///< relative spin about the normal (rad), volume law
  Vec3 roll;     ///< relative rolling (rad): the volume law's rocking, rolling friction
};

struct PairState {
  PairKey key;
  GjkCache gjk;         ///< warm start (body pairs)
  PairHistory history;  ///< zero while the pair does not touch
  /// A patch of surface grains: its centroid in the shape frame of the body
  /// of lower id, where the next step looks for it (surface_contact.hpp).
  Vec3 anchor;
};

/// Makes `states` follow the sorted `keys`: entries of pairs still listed
/// keep their state, new pairs start cold, the rest are dropped. Needs
/// `states` sorted by key (a damaged one cannot make it index out of range);
/// no allocation once capacity suffices.
void align_pair_states(std::span<const PairKey> keys, std::vector<PairState>& states);

}  // namespace gjkdem::dem
