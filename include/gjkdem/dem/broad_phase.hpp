#pragma once
// Broad phase: the pairs of overlapping boxes (shape/aabb.hpp; enlarged and
// kept by boxes.hpp) by sweep and prune (Baraff 1992; Cohen et al. 1995) on
// the axis along which the boxes' centres spread most, within strips across
// the axis of second spread.
//
// Why strips: a plain sweep tests every box against all boxes whose interval
// on the sweep axis overlaps its own. In a bed much wider than deep (a
// hopper's floor, a 1 m x 1 m x 10 cm layer of 100k grains) that is a slab
// across the whole width, so the cost grows as N^1.5. Strips two mean box
// sizes wide keep the work per box constant; a box lies in every strip it
// crosses, and a pair is reported only by the strip where the overlap of
// their intervals on the strip axis begins, so never twice. Strips are swept
// in parallel; the pairs are sorted at the end, so the result does not depend
// on the thread count. Callers that keep the workspace between steps pay an
// almost linear insertion sort on coherent motion.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "gjkdem/shape/aabb.hpp"
#include "gjkdem/shape/box_tree.hpp"

namespace gjkdem::dem {

using BodyPair = std::pair<std::uint32_t, std::uint32_t>;

/// Working memory of the sweep, kept between calls (any content is accepted).
struct SweepWorkspace {
  std::vector<std::uint32_t> order;        ///< boxes by lower bound on the sweep axis (rebuilt when the count changes)
  int axis = -1;                           ///< the sweep axis `order` was sorted on
  std::vector<std::uint32_t> strip_begin;  ///< per strip, its first slot in `entries`
  std::vector<std::uint32_t> cursor;       ///< filling position per strip
  std::vector<std::uint32_t> entries;      ///< box indices, strip after strip, each strip in sweep order
  std::vector<std::vector<BodyPair>> found;  ///< per thread
};

/// The tree of the fixed bodies' boxes, which never move (shape/box_tree.hpp).
using StaticTree = BoxTree;

/// Every pair (i < j) of overlapping boxes (touching counts), sorted, on up
/// to `threads` OpenMP threads (the same result for any count).
void overlapping_pairs(std::span<const Aabb> boxes, SweepWorkspace& work, std::vector<BodyPair>& pairs,
                       int threads = 1);

}  // namespace gjkdem::dem
