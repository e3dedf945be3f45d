#include "gjkdem/dem/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gjkdem::dem {
namespace {

struct Bisection {
  std::span<const Vec3> centres;
  std::span<const Real> weights;
  std::span<const std::uint64_t> ids;
  Decomposition& out;
  std::vector<Real> prefix;  // scratch: cumulative weights of the bodies being split
};

// The longest axis of a box (the lower axis on a tie).
int longest_axis(const Vec3& extent) {
  return extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
}

void split(Bisection& b, std::span<std::uint32_t> bodies, std::uint32_t first_part, int parts, DomainBox box) {
  if (parts == 1) {
    b.out.boxes[first_part] = box;
    for (const std::uint32_t i : bodies) b.out.owner[i] = first_part;
    return;
  }
  const int left_parts = parts / 2;
  const std::size_t n = bodies.size();
  int axis;
  if (n == 0) {
    axis = longest_axis(box.hi - box.lo);
  } else {
    Vec3 lo = b.centres[bodies[0]], hi = lo;
    for (const std::uint32_t i : bodies) lo = min(lo, b.centres[i]), hi = max(hi, b.centres[i]);
    axis = longest_axis(hi - lo);
  }
  std::sort(bodies.begin(), bodies.end(), [&](std::uint32_t p, std::uint32_t q) {
    const Real cp = b.centres[p][axis], cq = b.centres[q][axis];
    return cp < cq || (cp == cq && b.ids[p] < b.ids[q]);
  });
  auto coord = [&](std::size_t k) { return b.centres[bodies[k]][axis]; };
  // Left takes the first k bodies: the k whose weight is nearest its share,
  // moved to a change of coordinate so that the cut can run between them.
  std::vector<Real>& prefix = b.prefix;
  prefix.assign(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) prefix[k + 1] = prefix[k] + b.weights[bodies[k]];
  const Real target = prefix[n] * left_parts / parts;
  auto error = [&](std::size_t k) { return std::fabs(prefix[k] - target); };
  std::size_t k = 0;
  for (std::size_t j = 1; j <= n; ++j)
    if (error(j) < error(k)) k = j;
  if (k > 0 && k < n && coord(k - 1) == coord(k)) {
    std::size_t down = k, up = k;
    while (down > 0 && coord(down - 1) == coord(down)) --down;
    while (up < n && coord(up - 1) == coord(up)) ++up;
    k = error(down) <= error(up) ? down : up;
  }
  Real cut;
  if (n == 0) {
    cut = box.lo[axis] + (box.hi[axis] - box.lo[axis]) / 2;
  } else if (k == 0) {
    cut = coord(0);  // the left box [lo, coord(0)) holds none
  } else if (k == n) {
    cut = std::nextafter(coord(n - 1), std::numeric_limits<Real>::infinity());  // holds all; <= hi
  } else {
    cut = coord(k - 1) + (coord(k) - coord(k - 1)) / 2;
    if (!(cut > coord(k - 1))) cut = coord(k);  // neighbouring doubles
  }
  DomainBox left = box, right = box;
  left.hi[axis] = cut;
  right.lo[axis] = cut;
  split(b, bodies.first(k), first_part, left_parts, left);
  split(b, bodies.subspan(k), first_part + static_cast<std::uint32_t>(left_parts), parts - left_parts, right);
}

}  // namespace

Decomposition bisect(std::span<const Vec3> centres, std::span<const Real> weights, std::span<const std::uint64_t> ids,
                     int parts, const Vec3& lo, const Vec3& hi) {
  if (parts < 1) throw std::invalid_argument("bisect: parts must be at least 1");
  if (weights.size() != centres.size() || ids.size() != centres.size())
    throw std::invalid_argument("bisect: centres, weights and ids must have one entry per body");
  const DomainBox domain{lo, hi};
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (!domain.holds(centres[i]))
      throw std::invalid_argument("bisect: body " + std::to_string(ids[i]) + " lies outside the domain");
    if (!(weights[i] >= 0) || !std::isfinite(weights[i]))
      throw std::invalid_argument("bisect: body " + std::to_string(ids[i]) + " has a weight that is not finite and >= 0");
  }
  Decomposition out;
  out.boxes.resize(static_cast<std::size_t>(parts));
  out.owner.resize(centres.size());
  std::vector<std::uint32_t> bodies(centres.size());
  for (std::uint32_t i = 0; i < bodies.size(); ++i) bodies[i] = i;
  Bisection b{centres, weights, ids, out, {}};
  split(b, bodies, 0, parts, domain);
  return out;
}

}  // namespace gjkdem::dem
