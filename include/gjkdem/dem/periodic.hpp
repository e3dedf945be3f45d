#pragma once
// Periodic boundaries: on each periodic axis the world repeats with period
// hi - lo. A moving body that leaves the cell [lo, hi) on one side enters it
// on the other (its box anchor moves with it, so its box stays valid), and
// bodies touch across the boundary: the broad phase sweeps, besides every
// box, its images shifted by one period where they reach within the widest
// box of a face, and each candidate pair carries the image of its second
// body (StepContact::shift). A pair touches through at most one image: the
// builder refuses cells shorter than four of the largest body's reach
// (skin included) on a periodic axis. Pair keys stay the bodies' ids, so a
// contact keeps its springs while a body crosses.
#include <cstdint>
#include <vector>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

struct World;

struct PeriodicCell {
  bool axes[3] = {false, false, false};  ///< periodic on x, y, z
  Vec3 lo, hi;                           ///< the cell, on the periodic axes (m)
  bool active() const noexcept { return axes[0] || axes[1] || axes[2]; }
};

/// An image: one period back, none or forward on each axis, as a code
/// 0..26 (13: no shift).
inline constexpr std::uint8_t kNoImage = 13;
inline std::uint8_t image_code(const int shift[3]) noexcept {
  return static_cast<std::uint8_t>((shift[0] + 1) + 3 * (shift[1] + 1) + 9 * (shift[2] + 1));
}
inline Vec3 image_shift(const PeriodicCell& cell, std::uint8_t code) noexcept {
  const Vec3 period = cell.hi - cell.lo;
  return {(code % 3 - 1) * period.x, (code / 3 % 3 - 1) * period.y, (code / 9 - 1) * period.z};
}

/// The shifts of the images a body may touch through: no shift first, then
/// one period either way on each periodic axis (only no shift without a cell).
std::vector<Vec3> image_shifts(const PeriodicCell& cell);

/// Puts the moving bodies back into the cell, moving their box anchors and
/// boxes with them. Returns how many crossed.
std::size_t wrap_bodies(World& world);

/// The candidate pairs of a periodic world with their images: fills
/// work.candidates and work.candidate_images from the moving and static sets
/// that find_candidates prepared.
void find_periodic_candidates(World& world, int threads);

}  // namespace gjkdem::dem
