// The candidate pairs of a force evaluation (stages.hpp).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "stages.hpp"

namespace gjkdem::dem::detail {

// Candidate body pairs: moving and driven bodies against each other by the
// sweep (two driven ones never touch), moving against static from the static
// tree (built again when the boxes were all made anew).
void find_candidates(World& w, int threads) {
  StepWorkspace& work = w.work;
  const std::vector<Aabb>& boxes = w.search.boxes.boxes;
  if (!work.static_ready) {
    work.moving.clear();
    std::vector<std::uint32_t> fixed;
    std::vector<Aabb> fixed_boxes;
    for (std::uint32_t i = 0; i < w.bodies.size(); ++i) {
      if (is_static(w.bodies[i])) {
        fixed.push_back(i);
        fixed_boxes.push_back(boxes[i]);
      } else {
        work.moving.push_back(i);
      }
    }
    build_static_tree(fixed_boxes, fixed, work.fixed_tree);
    work.static_ready = true;
  }
  work.moving_boxes.resize(work.moving.size());
  for (std::size_t k = 0; k < work.moving.size(); ++k) work.moving_boxes[k] = boxes[work.moving[k]];
  if (w.cell.active()) {
    if (w.search.renew_cell) w.search.cell = w.cell, w.search.renew_cell = false;
    find_periodic_candidates(w, threads);
    work.candidates_current = true;
    return;
  }
  std::vector<BodyPair>& pairs = work.candidates;
  overlapping_pairs(work.moving_boxes, work.sweep, pairs, threads);
  for (BodyPair& p : pairs) p = {work.moving[p.first], work.moving[p.second]};  // moving is increasing
  if (!w.driven.empty())
    std::erase_if(pairs, [&](const BodyPair& p) { return w.bodies[p.first].fixed && w.bodies[p.second].fixed; });
  std::vector<std::uint32_t> found;
  for (const std::uint32_t i : work.moving) {
    if (w.bodies[i].fixed) continue;
    found.clear();
    query_static_tree(work.fixed_tree, boxes[i], found);
    for (const std::uint32_t f : found) pairs.emplace_back(std::min(i, f), std::max(i, f));
  }
  std::sort(pairs.begin(), pairs.end());
  work.candidates_current = true;
}

}  // namespace gjkdem::dem::detail
