#include "gjkdem/dem/periodic.hpp"

#include <algorithm>
#include <cstdint>
#include <tuple>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

std::vector<Vec3> image_shifts(const PeriodicCell& cell) {
  std::vector<Vec3> shifts{Vec3{}};
  for (std::uint8_t code = 0; code < 27; ++code) {
    if (code == kNoImage) continue;
    const int shift[3] = {code % 3 - 1, code / 3 % 3 - 1, code / 9 - 1};
    if ((shift[0] && !cell.axes[0]) || (shift[1] && !cell.axes[1]) || (shift[2] && !cell.axes[2])) continue;
    shifts.push_back(image_shift(cell, code));
  }
  return shifts;
}
namespace {

struct Candidate {
  std::uint32_t a, b;
  std::uint8_t image;  ///< of b
};

std::uint8_t negated(std::uint8_t code) { return static_cast<std::uint8_t>(26 - code); }

}  // namespace

std::size_t wrap_bodies(World& w) {
  const PeriodicCell& cell = w.settings.periodic;
  const Vec3 period = cell.hi - cell.lo;
  BoxCache& cache = w.work.boxes;
  const bool boxed = cache.boxes.size() == w.bodies.size();
  std::size_t crossed = 0;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    Body& b = w.bodies[i];
    if (b.fixed) continue;
    Vec3 move{};
    for (int a = 0; a < 3; ++a) {
      if (!cell.axes[a]) continue;
      if (b.position[a] < cell.lo[a]) move[a] = period[a];
      else if (b.position[a] >= cell.hi[a]) move[a] = -period[a];
    }
    if (move == Vec3{}) continue;
    ++crossed;
    b.position += move;
    if (boxed) {
      cache.anchor_position[i] += move;
      cache.boxes[i].lo += move;
      cache.boxes[i].hi += move;
    }
  }
  return crossed;
}

void find_periodic_candidates(World& w, int threads) {
  StepWorkspace& work = w.work;
  const PeriodicCell& cell = w.settings.periodic;
  const std::vector<Aabb>& boxes = work.boxes.boxes;
  Vec3 widest{};
  for (const std::uint32_t i : work.moving) widest = max(widest, boxes[i].hi - boxes[i].lo);
  // Every moving and driven box, and its images where it comes within the
  // widest box of a face: a box across the face may meet them.
  std::vector<Aabb>& sweep_boxes = work.moving_boxes;
  std::vector<std::uint32_t>& sweep_body = work.image_body;
  std::vector<std::uint8_t>& sweep_image = work.image_code;
  sweep_boxes.clear(), sweep_body.clear(), sweep_image.clear();
  const auto images = [&](const Aabb& box, auto&& visit) {
    int options[3][3], count[3];
    for (int a = 0; a < 3; ++a) {
      count[a] = 0;
      options[a][count[a]++] = 0;
      if (!cell.axes[a]) continue;
      if (box.lo[a] < cell.lo[a] + widest[a]) options[a][count[a]++] = 1;
      if (box.hi[a] > cell.hi[a] - widest[a]) options[a][count[a]++] = -1;
    }
    for (int x = 0; x < count[0]; ++x)
      for (int y = 0; y < count[1]; ++y)
        for (int z = 0; z < count[2]; ++z) {
          const int shift[3] = {options[0][x], options[1][y], options[2][z]};
          const std::uint8_t code = image_code(shift);
          const Vec3 s = image_shift(cell, code);
          visit(Aabb{box.lo + s, box.hi + s}, code);
        }
  };
  for (const std::uint32_t i : work.moving)
    images(boxes[i], [&](const Aabb& box, std::uint8_t code) {
      sweep_boxes.push_back(box);
      sweep_body.push_back(i);
      sweep_image.push_back(code);
    });
  std::vector<BodyPair> raw;
  overlapping_pairs(sweep_boxes, work.sweep, raw, threads);
  std::vector<Candidate> found;
  const auto add = [&](std::uint32_t i, std::uint32_t j, std::uint8_t image_of_j) {  // j at image_of_j meets i
    if (i < j) found.push_back({i, j, image_of_j});
    else found.push_back({j, i, negated(image_of_j)});
  };
  for (const BodyPair& p : raw) {
    const std::uint32_t i = sweep_body[p.first], j = sweep_body[p.second];
    if (i == j || (w.bodies[i].fixed && w.bodies[j].fixed)) continue;
    // j's image relative to i's: the difference of their shifts.
    const std::uint8_t si = sweep_image[p.first], sj = sweep_image[p.second];
    const int rel[3] = {sj % 3 - si % 3, sj / 3 % 3 - si / 3 % 3, sj / 9 - si / 9};
    if (rel[0] < -1 || rel[0] > 1 || rel[1] < -1 || rel[1] > 1 || rel[2] < -1 || rel[2] > 1) continue;
    add(i, j, image_code(rel));
  }
  std::vector<std::uint32_t> hits;
  for (const std::uint32_t i : work.moving) {
    if (w.bodies[i].fixed) continue;
    images(boxes[i], [&](const Aabb& box, std::uint8_t code) {  // i at `code` meets static f
      hits.clear();
      query_static_tree(work.fixed_tree, box, hits);
      for (const std::uint32_t f : hits) add(f, i, code);
    });
  }
  std::sort(found.begin(), found.end(),
            [](const Candidate& x, const Candidate& y) { return std::tie(x.a, x.b, x.image) < std::tie(y.a, y.b, y.image); });
  // One image per pair: the cell is long enough that a pair meets through one
  // only; keep the first should round-off show two.
  found.erase(std::unique(found.begin(), found.end(),
                          [](const Candidate& x, const Candidate& y) { return x.a == y.a && x.b == y.b; }),
              found.end());
  work.candidates.resize(found.size());
  work.candidate_images.resize(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    work.candidates[k] = {found[k].a, found[k].b};
    work.candidate_images[k] = found[k].image;
  }
}

}  // namespace gjkdem::dem
