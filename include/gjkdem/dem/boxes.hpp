#pragma once
// The boxes of the broad phase, enlarged by a skin and kept while a body
// stays inside its own (the Verlet-list idea of molecular dynamics, and
// Yade's "verletDist"): a box is recomputed (shape/aabb.hpp) only when
// the body may have left it, and when no box changed the broad phase keeps
// its candidate pairs.
//
// A moving body holds its box while its points cannot have moved by more than
// the skin since the box was made: a point at distance r from the centre of
// mass moves by at most |dx| + 2 |q - q0| r when the centre moves by dx and the
// orientation turns from q0 to q (unit quaternions with q . q0 >= 0: the
// chord |q - q0| = 2 sin(theta / 4) and the point moves 2 sin(theta / 2) r <=
// 4 sin(theta / 4) r). Fixed bodies get a tight box once; driven ones
// (motion.hpp) are boxed as moving bodies are.
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/broad_phase.hpp"

namespace gjkdem::dem {

struct BoxCache {
  std::vector<Aabb> boxes;          ///< per body, world
  std::vector<Vec3> anchor_position;     ///< centre of mass when the box was made
  std::vector<Quat> anchor_orientation;  ///< orientation then
  std::vector<Real> moved;               ///< per body: how far it may have moved, in skins (scratch, not saved)
};

/// Brings the boxes of `bodies` up to date: every box when the cache is
/// empty or holds more bodies (then fixed bodies too), else those of bodies
/// added since and of moving bodies that may have left theirs. `skin` is relative to each template's reach.
/// `drift` (m) is added to every moving body's motion: how far periodic
/// images may have moved since the candidates were found (a deforming cell).
/// Returns how many boxes were recomputed.
std::size_t update_boxes(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                         BoxCache& cache, int threads, Real drift = 0);

/// update_boxes in two halves, for domain runs, whose domains must agree
/// whether any box is remade (domains.hpp). measure_box_motion records in
/// cache.moved how far each body may have moved, in skins (infinite for a
/// body without a box: all of them when the cache is empty or holds more
/// bodies, fixed ones included), and says whether a body not `ignored`
/// (empty: none) may have left its box or has none. remake_boxes then
/// remakes the boxes of the bodies that moved more than `threshold` skins
/// (but those `skipped`):
/// update_boxes uses 1/2 when any left (else there is nothing to remake),
/// so that the sweep that follows serves those half way out too, instead of
/// running again a step later.
bool measure_box_motion(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                        BoxCache& cache, int threads, Real drift = 0, std::span<const std::uint8_t> ignored = {});
std::size_t remake_boxes(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                         BoxCache& cache, int threads, Real threshold, std::span<const std::uint8_t> skipped = {});
/// The threshold update_boxes remakes boxes at, in skins, once one body left its box.
inline constexpr Real kBoxBatchFraction = 0.5;

/// Remakes every box from the anchors held in `cache` (restoring a
/// checkpoint): each box comes out with the same bits as when it was made.
void rebuild_boxes_at_anchors(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                              BoxCache& cache);

}  // namespace gjkdem::dem
