#include "gjkdem/dem/periodic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/step_context.hpp"
#include "gjkdem/dem/step_workspace.hpp"

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

namespace {

// The lattice vector that brings x into the cell: -floor of each of its
// coordinates along the edges (independent of one another), on periodic axes.
Vec3 into_cell(const PeriodicCell& cell, const Vec3& x) {
  const Vec3 d = x - cell.lo, size = cell.hi - cell.lo;
  Real f[3] = {0, 0, 0};
  if (cell.axes[2]) f[2] = d.z / size.z;
  if (cell.axes[1]) f[1] = (d.y - cell.tilt.z * f[2]) / size.y;
  if (cell.axes[0]) f[0] = (d.x - cell.tilt.x * f[1] - cell.tilt.y * f[2]) / size.x;
  int n[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    if (f[a] >= 0 && f[a] < 1) continue;
    n[a] = -static_cast<int>(std::floor(f[a]));
    if (f[a] + n[a] >= 1) --n[a];  // round-off at the face
  }
  return lattice_vector(cell, n[0], n[1], n[2]);
}

}  // namespace

Vec3 nearest_image(const PeriodicCell& cell, Vec3 d) noexcept {
  for (int a = 2; a >= 0; --a)
    if (cell.axes[a]) d -= cell_edge(cell, a) * std::round(d[a] / (cell.hi[a] - cell.lo[a]));
  return d;
}

Real cell_width(const PeriodicCell& cell, int axis) noexcept {
  if (cell.tilt == Vec3{}) return cell.hi[axis] - cell.lo[axis];
  // The volume over the area of the face spanned by the two other edges (a
  // unit edge standing in on an axis that is not periodic).
  PeriodicCell unit = cell;
  for (int a = 0; a < 3; ++a)
    if (!cell.axes[a]) unit.lo[a] = 0, unit.hi[a] = 1;
  const Vec3 size = unit.hi - unit.lo;
  const Vec3 face = cross(cell_edge(unit, (axis + 1) % 3), cell_edge(unit, (axis + 2) % 3));
  return size.x * size.y * size.z / length(face);
}

namespace {

// A moving body this world moves: a domain moves only its own (their
// owners move the others).
bool moves_here(const CellBodies& m, std::size_t i) {
  return !m.bodies[i].fixed && (!m.domain || m.domain->owns(i));
}

// The kinetic energy the cell's field gives moving bodies (a change of the
// field, a wrap): summed in body order in a whole world, listed per body in
// a domain (CellBodies).
struct FieldWorkSum {
  const CellBodies& moved;
  std::vector<FieldWork>* listed;  ///< a domain's list; null in a whole world
  Real added = 0;
  bool any = false;
  void give(Body& b, const Vec3& v) {
    const Real gained = 0.5 * moved.makeup->mass(b) * (dot(v, v) - dot(b.velocity, b.velocity));
    if (!listed) added += gained, any = true;
    else listed->push_back({b.id, gained});
    b.velocity = v;
  }
  void finish() {
    if (any) *moved.wall_work += added;
  }
};

}  // namespace

std::size_t wrap_bodies(const PeriodicCell& cell, const CellTensor& rate, BoxCache& cache, const CellBodies& moved) {
  const std::span<Body> bodies = moved.bodies;
  const bool boxed = cache.boxes.size() == bodies.size();
  std::size_t crossed = 0;
  FieldWorkSum work{moved, moved.domain ? &moved.domain->wrap_work : nullptr};
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies[i];
    if (!moves_here(moved, i)) continue;
    const Vec3 move = into_cell(cell, b.position);
    if (move == Vec3{}) continue;
    ++crossed;
    b.position += move;
    // In the field L (x - centre) the image one lattice vector m away moves
    // faster by L m: the body takes that velocity, and the kinetic energy
    // it gains or loses is the cell's work on it (Lees-Edwards' boundary
    // drives the flow this way).
    if (const Vec3 jump = affine_velocity(rate, move); jump != Vec3{}) work.give(b, b.velocity + jump);
    if (boxed) {
      cache.anchor_position[i] += move;
      cache.boxes[i].lo += move;
      cache.boxes[i].hi += move;
    }
  }
  work.finish();
  return crossed;
}

void control_cell(const CellControl& control, const CellTensor& stress, const PeriodicCell& cell, CellTensor& rate,
                  const CellBodies& moved) {
  Real scale = 0;  // of the servo's errors: the largest target
  for (int k = 0; k < 6; ++k)
    if (control.mode[k] == CellMode::Stress) scale = std::fmax(scale, std::fabs(control.value[k]));
  CellTensor next{};
  for (int k = 0; k < 6; ++k) {
    if (control.mode[k] == CellMode::StrainRate) {
      next[k] = control.value[k];
    } else if (control.mode[k] == CellMode::Stress) {
      const Real error = (stress[k] - control.value[k]) / scale;
      next[k] = control.max_strain_rate * std::clamp(error, Real(-1), Real(1));
    }
  }
  CellTensor change;
  bool changed = false;
  for (int k = 0; k < 6; ++k) change[k] = next[k] - rate[k], changed |= change[k] != 0;
  rate = next;
  if (!changed) return;
  const Vec3 centre = cell_centre(cell);
  FieldWorkSum work{moved, moved.domain ? &moved.domain->field_work : nullptr};
  for (std::size_t i = 0; i < moved.bodies.size(); ++i) {
    Body& b = moved.bodies[i];
    if (moves_here(moved, i)) work.give(b, b.velocity + affine_velocity(change, b.position - centre));
  }
  work.finish();
}

bool deform_cell(PeriodicCell& cell, const CellTensor& l, Real dt) {
  const Vec3 centre = cell_centre(cell);
  // H += dt L H, H upper triangular with diagonal Lx, Ly, Lz and tilts
  // xy, xz, yz; about the centre, which stays.
  const Vec3 size = cell.hi - cell.lo;
  const Vec3 tilt = cell.tilt;
  const Vec3 new_length{size.x * (1 + dt * l[0]), size.y * (1 + dt * l[1]), size.z * (1 + dt * l[2])};
  Vec3 new_tilt{tilt.x + dt * (l[0] * tilt.x + l[kXY] * size.y),
                tilt.y + dt * (l[0] * tilt.y + l[kXY] * tilt.z + l[kXZ] * size.z),
                tilt.z + dt * (l[1] * tilt.z + l[kYZ] * size.z)};
  // A tilt past half its edge: the same lattice with the edge taken back.
  bool flipped = false;
  const auto take_back = [&](Real& t, Real edge) {
    if (std::fabs(t) <= 0.5 * edge) return;
    t -= std::copysign(edge, t);
    flipped = true;
  };
  take_back(new_tilt.y, new_length.x);                                   // c -= a
  if (std::fabs(new_tilt.z) > 0.5 * new_length.y) {                      // c -= b
    const Real s = std::copysign(Real(1), new_tilt.z);
    new_tilt.z -= s * new_length.y, new_tilt.y -= s * new_tilt.x, flipped = true;
    take_back(new_tilt.y, new_length.x);
  }
  take_back(new_tilt.x, new_length.x);                                   // b -= a
  // The new edges about the same centre, lo + (a + b + c) / 2.
  cell.tilt = new_tilt;
  for (int a = 0; a < 3; ++a)
    if (cell.axes[a]) cell.hi[a] = cell.lo[a] + new_length[a];
  const Vec3 moved = cell_centre(cell) - centre;
  cell.lo -= moved, cell.hi -= moved;
  return flipped;
}

Real cell_drift(const PeriodicCell& now, const PeriodicCell& searched) noexcept {
  if (!searched.active()) return 0;
  // An image is at most one edge vector away on each axis: its drift is at
  // most the sum of the edges' changes.
  Real drift = 0;
  for (int a = 0; a < 3; ++a)
    if (now.axes[a]) drift += length(cell_edge(now, a) - cell_edge(searched, a));
  return drift;
}

void find_periodic_candidates(std::span<const Body> bodies, std::span<const Aabb> boxes, const PeriodicCell& cell,
                              int threads, StepWorkspace& work) {
  Vec3 widest{};
  for (const std::uint32_t i : work.moving) widest = max(widest, boxes[i].hi - boxes[i].lo);
  // Every moving and driven box, and its images where it comes within the
  // widest box of a face: a box across the face may meet them.
  std::vector<Aabb>& sweep_boxes = work.moving_boxes;
  std::vector<std::uint32_t>& sweep_body = work.image_body;
  std::vector<std::uint8_t>& sweep_image = work.image_code;
  sweep_boxes.clear(), sweep_body.clear(), sweep_image.clear();
  // A sheared cell: every image whose box reaches the cell's bounding box
  // widened by the widest box (a box there may meet it).
  const bool sheared = cell.tilt != Vec3{};
  Aabb reach{cell.lo, cell.lo};
  if (sheared) {
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p = cell.lo + lattice_vector(cell, corner & 1, corner >> 1 & 1, corner >> 2 & 1);
      reach.lo = min(reach.lo, p), reach.hi = max(reach.hi, p);
    }
    reach.lo -= widest, reach.hi += widest;
  }
  const auto images = [&](const Aabb& box, auto&& visit) {
    if (sheared) {
      for (std::uint8_t code = 0; code < 27; ++code) {
        const int shift[3] = {code % 3 - 1, code / 3 % 3 - 1, code / 9 - 1};
        if ((shift[0] && !cell.axes[0]) || (shift[1] && !cell.axes[1]) || (shift[2] && !cell.axes[2])) continue;
        const Vec3 s = image_shift(cell, code);
        const Aabb moved{box.lo + s, box.hi + s};
        if (code == kNoImage || (moved.lo.x <= reach.hi.x && moved.hi.x >= reach.lo.x && moved.lo.y <= reach.hi.y &&
                                 moved.hi.y >= reach.lo.y && moved.lo.z <= reach.hi.z && moved.hi.z >= reach.lo.z))
          visit(moved, code);
      }
      return;
    }
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
    if (i == j || (bodies[i].fixed && bodies[j].fixed)) continue;
    // j's image relative to i's: the difference of their shifts.
    const std::uint8_t si = sweep_image[p.first], sj = sweep_image[p.second];
    const int rel[3] = {sj % 3 - si % 3, sj / 3 % 3 - si / 3 % 3, sj / 9 - si / 9};
    if (rel[0] < -1 || rel[0] > 1 || rel[1] < -1 || rel[1] > 1 || rel[2] < -1 || rel[2] > 1) continue;
    add(i, j, image_code(rel));
  }
  std::vector<std::uint32_t> hits;
  for (const std::uint32_t i : work.moving) {
    if (bodies[i].fixed) continue;
    images(boxes[i], [&](const Aabb& box, std::uint8_t code) {  // i at `code` meets static f
      hits.clear();
      query_box_tree(work.fixed_tree, box, hits);
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
