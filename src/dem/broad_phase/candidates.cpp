// The candidate pairs of a force evaluation (stages.hpp).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "step/stages.hpp"

namespace gjkdem::dem::detail {

// Candidate body pairs: moving and driven bodies against each other by the
// sweep (two driven ones never touch), moving against static from the static
// tree (built again when the boxes were all made anew).
void find_candidates(std::span<const Body> bodies, std::span<const Aabb> boxes, const PeriodicCell* periodic,
                     bool any_driven, int threads, StepWorkspace& work) {
  if (!work.static_ready) {
    work.moving.clear();
    std::vector<std::uint32_t> fixed;
    std::vector<Aabb> fixed_boxes;
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
      if (is_static(bodies[i])) {
        fixed.push_back(i);
        fixed_boxes.push_back(boxes[i]);
      } else {
        work.moving.push_back(i);
      }
    }
    build_box_tree(fixed_boxes, fixed, work.fixed_tree);
    work.static_ready = true;
  }
  work.moving_boxes.resize(work.moving.size());
  for (std::size_t k = 0; k < work.moving.size(); ++k) work.moving_boxes[k] = boxes[work.moving[k]];
  if (periodic) {
    find_periodic_candidates(bodies, boxes, *periodic, threads, work);
    work.candidates_current = true;
    return;
  }
  std::vector<BodyPair>& pairs = work.candidates;
  overlapping_pairs(work.moving_boxes, work.sweep, pairs, threads);
  for (BodyPair& p : pairs) p = {work.moving[p.first], work.moving[p.second]};  // moving is increasing
  if (any_driven)
    std::erase_if(pairs, [&](const BodyPair& p) { return bodies[p.first].fixed && bodies[p.second].fixed; });
  std::vector<std::uint32_t> found;
  for (const std::uint32_t i : work.moving) {
    if (bodies[i].fixed) continue;
    found.clear();
    query_box_tree(work.fixed_tree, boxes[i], found);
    for (const std::uint32_t f : found) pairs.emplace_back(std::min(i, f), std::max(i, f));
  }
  std::sort(pairs.begin(), pairs.end());
  work.candidates_current = true;
}

}  // namespace gjkdem::dem::detail
