#include "gjkdem/dem/boxes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

using detail::kMinParallelBodies;

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

// A body's box: of its shape, or of each part of a compound.
Aabb body_box(const ShapeTemplate& t, const Body& b, Real pad) noexcept {
  const Transform pose = shape_pose(t, b);
  if (t.parts.empty()) return aabb(t.shape, pose, pad);
  Aabb box = aabb(t.parts[0].shape, compose(pose, t.parts[0].pose), pad);
  for (std::size_t k = 1; k < t.parts.size(); ++k) {
    const Aabb part = aabb(t.parts[k].shape, compose(pose, t.parts[k].pose), pad);
    box = enclose(box, part);
  }
  return box;
}

}  // namespace

bool measure_box_motion(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                        BoxCache& cache, int threads, Real drift, std::span<const std::uint8_t> ignored) {
  const std::size_t n = bodies.size(), old = cache.boxes.size();
  if (old == 0 || old > n) {  // every box is made anew
    cache.boxes.assign(n, Aabb{});
    cache.anchor_position.assign(n, Vec3{});
    cache.anchor_orientation.assign(n, Quat{});
    cache.moved.assign(n, kInfinity);
    for (std::size_t i = 0; i < n; ++i)
      if (ignored.empty() || !ignored[i]) return true;
    return false;
  }
  if (old < n) {  // bodies added: boxed as bodies that left theirs
    cache.boxes.resize(n);
    cache.anchor_position.resize(n);
    cache.anchor_orientation.resize(n);
  }
  cache.moved.resize(n);
  // How far each moving body's points may have moved since its box was made,
  // in units of its skin (> 1: it may have left the box).
  const std::int64_t count = static_cast<std::int64_t>(n);
  auto moved = [&](std::int64_t i) {
    const Body& b = bodies[i];
    const Real reach = templates[b.shape].reach;
    const Quat& q0 = cache.anchor_orientation[i];
    const Real same = q0.w * b.orientation.w + q0.x * b.orientation.x + q0.y * b.orientation.y + q0.z * b.orientation.z;
    const Real s = same < 0 ? -1 : 1;  // q and -q are one turn
    const Real dw = b.orientation.w - s * q0.w, dx = b.orientation.x - s * q0.x, dy = b.orientation.y - s * q0.y,
               dz = b.orientation.z - s * q0.z;
    const Real chord = std::sqrt(dw * dw + dx * dx + dy * dy + dz * dz);
    return (length(b.position - cache.anchor_position[i]) + 2 * chord * reach + drift) / (skin * reach);
  };
  int any = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : any) if (count >= kMinParallelBodies)
  for (std::int64_t i = 0; i < count; ++i) {
    cache.moved[i] = static_cast<std::size_t>(i) >= old ? kInfinity : is_static(bodies[i]) ? 0 : moved(i);
    if (!(cache.moved[i] <= 1) && (ignored.empty() || !ignored[i])) any = 1;
  }
  return any != 0;
}

std::size_t remake_boxes(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                         BoxCache& cache, int threads, Real threshold, std::span<const std::uint8_t> skipped) {
  const std::int64_t count = static_cast<std::int64_t>(bodies.size());
  std::int64_t updated = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : updated) if (count >= kMinParallelBodies)
  for (std::int64_t i = 0; i < count; ++i) {
    const Body& b = bodies[i];
    const ShapeTemplate& t = templates[b.shape];
    if (!(cache.moved[i] > threshold) || (!skipped.empty() && skipped[i])) continue;
    cache.boxes[i] = body_box(t, b, is_static(b) ? 0 : skin * t.reach);
    cache.anchor_position[i] = b.position;
    cache.anchor_orientation[i] = b.orientation;
    cache.moved[i] = 0;
    ++updated;
  }
  return static_cast<std::size_t>(updated);
}

std::size_t update_boxes(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                         BoxCache& cache, int threads, Real drift) {
  if (!measure_box_motion(bodies, templates, skin, cache, threads, drift)) return 0;
  return remake_boxes(bodies, templates, skin, cache, threads, kBoxBatchFraction);
}

void rebuild_boxes_at_anchors(std::span<const Body> bodies, std::span<const ShapeTemplate> templates, Real skin,
                              BoxCache& cache) {
  cache.boxes.resize(bodies.size());
  cache.moved.assign(bodies.size(), 0);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body at = bodies[i];
    at.position = cache.anchor_position[i];
    at.orientation = cache.anchor_orientation[i];
    const ShapeTemplate& t = templates[at.shape];
    cache.boxes[i] = body_box(t, at, is_static(at) ? 0 : skin * t.reach);
  }
}

}  // namespace gjkdem::dem
