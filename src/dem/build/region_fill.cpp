// Bodies placed in a region (fill_region: a packing on a lattice of free
// cubes, each shape drawn by weight) and inflows (add_inflow), which insert
// theirs during a run (inflow.cpp).
#include "gjkdem/dem/world_builder.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/surface_contact.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "number_text.hpp"

namespace gjkdem::dem {

using detail::number_text;

namespace {

// Number probabilities, summed to 1 (equal ones when none are given).
std::vector<Real> cumulative_weights(const std::vector<Real>& weights, std::size_t variants, const std::string& label) {
  if (!weights.empty() && weights.size() != variants)
    throw BuildError(label + ": " + std::to_string(weights.size()) + " weights for " + std::to_string(variants) +
                     " shapes");
  Real total = 0;
  for (const Real w : weights) {
    if (!(w >= 0) || !std::isfinite(w)) throw BuildError(label + ": weights must be finite and >= 0");
    total += w;
  }
  if (!weights.empty() && !(total > 0)) throw BuildError(label + ": the weights add up to 0");
  std::vector<Real> cumulative(variants);
  Real sum = 0;
  for (std::size_t k = 0; k < variants; ++k) {
    sum += weights.empty() ? 1 : weights[k];
    cumulative[k] = sum / (weights.empty() ? static_cast<Real>(variants) : total);
  }
  cumulative.back() = 1;
  return cumulative;
}

std::size_t pick_weighted(const std::vector<Real>& cumulative, Real u) {
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
  return std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
}

}  // namespace

std::uint32_t WorldBuilder::add_inflow(const InflowDef& d) {
  const std::string label = d.label.empty() ? "inflow " + std::to_string(world_.inflows.size()) : d.label;
  check_material(d.material, label);
  if (d.variants.empty()) throw BuildError(label + ": no shape to insert");
  if (d.round) {
    check_round_region(*d.round, label, true);
  } else if (!is_finite(d.lo) || !is_finite(d.hi) || !(d.hi.x >= d.lo.x && d.hi.y >= d.lo.y && d.hi.z >= d.lo.z)) {
    throw BuildError(label + ": the region's max must not be below its min on any axis");
  }
  if (!is_finite(d.velocity)) throw BuildError(label + ": the velocity must be finite");
  if (!(std::isfinite(d.rate) && std::isfinite(d.mass_rate) && d.rate >= 0 && d.mass_rate >= 0 &&
        (d.rate > 0) != (d.mass_rate > 0)))
    throw BuildError(label + ": give one rate > 0, in bodies or in kilograms per second");
  if (!(std::isfinite(d.start) && d.start >= 0)) throw BuildError(label + ": the start must be >= 0 and finite");
  if (!(d.stop > d.start)) throw BuildError(label + ": the stop must come after the start");
  if (d.count == 0 && !std::isfinite(d.stop)) throw BuildError(label + ": give a count or a stop time");
  Inflow f;
  f.cumulative = cumulative_weights(d.weights, d.variants.size(), label);
  for (const BodyShape& v : d.variants) {
    if (v.shell) throw BuildError(label + ": a thin shell is a body of its own (add_body): inflows do not insert shells");
    f.templates.push_back(add_template(v, false, label));
  }
  if (d.round) {
    const Aabb box = round_box(*d.round);
    f.lo = box.lo, f.hi = box.hi, f.round = d.round;
  } else {
    f.lo = d.lo, f.hi = d.hi;
  }
  f.material = d.material;
  f.velocity = d.velocity;
  f.rate = d.rate, f.mass_rate = d.mass_rate;
  f.start = d.start, f.stop = d.stop;
  f.count = d.count;
  f.seed = d.seed;
  if (inflow_capacity(f, {world_.templates, world_.materials}) > kMaxInflowBodies)
    throw BuildError(label + ": it could insert more than " + std::to_string(kMaxInflowBodies) +
                     " bodies; give a smaller count, stop or rate");
  world_.inflows.push_back(f);
  world_.inflow_states.emplace_back();
  inflow_labels_.push_back(label);
  return static_cast<std::uint32_t>(world_.inflows.size() - 1);
}

std::vector<std::uint32_t> WorldBuilder::fill_region(const RegionFill& f, std::mt19937_64& rng) {
  const std::string& label = f.label.empty() ? std::string("region") : f.label;
  say(label + ": placing " + std::to_string(f.count) + (f.pieces > 0 ? " bonded assemblies" : " bodies"));
  Vec3 region_lo = f.lo, region_hi = f.hi;  // a round region's: its bounding box
  if (f.round) {
    const RoundRegion& g = *f.round;
    check_round_region(g, label, false);
    const Aabb box = round_box(g);
    region_lo = box.lo, region_hi = box.hi;
  }
  check_material(f.material, label);
  if (f.variants.empty()) throw BuildError(label + ": no shape to fill the region with");
  try {
    check_fill_count(f.count > kMaxFillCount ? -1 : static_cast<std::int64_t>(f.count));
  } catch (const BuildError& e) {
    throw BuildError(label, e.key, e.rule);
  }
  if (!is_finite(region_lo) || !is_finite(region_hi) || !(region_hi.x > region_lo.x && region_hi.y > region_lo.y && region_hi.z > region_lo.z))
    throw BuildError(label + ": the region's max must exceed its min on every axis");
  if (f.fixed && length(f.velocity) > 0)
    throw BuildError(label, "velocity", "must be zero for fixed bodies (fixed = true)");
  if (f.pieces > 0 && f.fixed) throw BuildError(label, "fixed", "bonded assemblies move: they cannot be fixed");
  if (f.pieces > kMaxBondedPieces || (f.pieces > 0 && f.pieces * static_cast<std::uint64_t>(f.count) > kMaxFillCount))
    throw BuildError(label, "pieces",
                     "must be at most " + std::to_string(kMaxBondedPieces) + ", and times the count at most " +
                         std::to_string(kMaxFillCount));
  if (f.pieces == 1) throw BuildError(label, "pieces", "must be at least 2 (0: no bonded assemblies)");
  const std::uint32_t first_template = static_cast<std::uint32_t>(world_.templates.size());
  Real diameter = 0;  // of a sphere about each shape frame's origin holding every variant
  for (const BodyShape& s : f.variants) {
    Real radius = 0;
    if (f.pieces > 0) {  // cut per assembly below: no template of the whole
      if (is_compound(s) || s.surface || s.shell)
        throw BuildError(label + ": a bonded assembly is cut from one convex shape, not a compound, a surface or a shell");
      radius = bounding_radius(s.shape);
    } else {
      if (s.shell) throw BuildError(label + ": a thin shell is a body of its own (add_body): generators do not make shells");
      add_template(s, f.fixed, label);
      radius = bounding_radius(given_shapes_.back());
    }
    diameter = std::fmax(diameter, 2 * (length(s.pose.translation) + radius));
  }
  // Cells of at least one diameter, the slack spread evenly.
  std::vector<std::pair<Vec3, Quat>> spots;
  const Vec3 size = region_hi - region_lo;
  const Real nx = std::floor(size.x / diameter), ny = std::floor(size.y / diameter), nz = std::floor(size.z / diameter);
  // A region far larger than its bodies (or mostly outside the walls) would
  // be scanned cell by cell for nothing: visit at most this many cells.
  const Real cell_budget = 64 * static_cast<Real>(f.count) + 1e6;
  Real visited = 0;
  // Cells are counted in doubles: beyond 2^53 of them, neighbours share a number.
  if (nx * ny * nz > 1e15)
    throw BuildError(label + ": the region spans more than 1e15 cells of the bodies' size (" + number_text(diameter) +
                     " m); make it smaller");
  if (nx >= 1 && ny >= 1 && nz >= 1) {
    const Vec3 cell{size.x / nx, size.y / ny, size.z / nz};
    const Vec3 slack = (cell - Vec3{diameter, diameter, diameter}) * 0.5;
    std::uniform_real_distribution<double> u(-1, 1);
    const Shape ball = make_sphere(diameter / 2);
    // The bodies already there: small ones in a hash grid of the region's
    // cells (each in the cells its bounding sphere, grown by a ball, meets),
    // large ones (walls) checked against every cell. Bodies placed now sit in
    // cells of their own and never meet each other.
    struct Near {
      std::uint32_t body;
      Transform pose;
      Real radius;
      Aabb box;  // large bodies: their tight box, a cheaper first test than the bounding sphere
    };
    std::vector<Near> large;
    std::unordered_map<std::uint64_t, std::vector<Near>> grid;
    const auto key = [&](Real i, Real j, Real k) {
      return static_cast<std::uint64_t>(i) + static_cast<std::uint64_t>(nx) *
                                                 (static_cast<std::uint64_t>(j) + static_cast<std::uint64_t>(ny) *
                                                                                      static_cast<std::uint64_t>(k));
    };
    for (std::uint32_t b = 0; b < world_.bodies.size(); ++b) {
      Near n{b, shape_pose(world_.templates[world_.bodies[b].shape], world_.bodies[b]),
             bounding_radius(given_shapes_[world_.bodies[b].shape]), {}};
      const Vec3 reach{n.radius + diameter, n.radius + diameter, n.radius + diameter};
      const Vec3 lo = hadamard(n.pose.translation - reach - region_lo, {1 / cell.x, 1 / cell.y, 1 / cell.z});
      const Vec3 hi = hadamard(n.pose.translation + reach - region_lo, {1 / cell.x, 1 / cell.y, 1 / cell.z});
      const Vec3 first{std::fmax(0, std::floor(lo.x)), std::fmax(0, std::floor(lo.y)), std::fmax(0, std::floor(lo.z))};
      const Vec3 last{std::fmin(nx - 1, std::floor(hi.x)), std::fmin(ny - 1, std::floor(hi.y)),
                      std::fmin(nz - 1, std::floor(hi.z))};
      if (!(first.x <= last.x && first.y <= last.y && first.z <= last.z)) continue;  // away from the region
      if ((last.x - first.x + 1) * (last.y - first.y + 1) * (last.z - first.z + 1) > 64) {
        n.box = aabb(given_shapes_[world_.bodies[b].shape], n.pose);
        large.push_back(n);
        continue;
      }
      for (Real k = first.z; k <= last.z; ++k)  // at most 64 cells, counted exactly below 2^53
        for (Real j = first.y; j <= last.y; ++j)
          for (Real i = first.x; i <= last.x; ++i) grid[key(i, j, k)].push_back(n);
    }
    // A surface grain's hull is not its solid (a bowl's hollow is free),
    // nor is a shell's (a tray's hollow is), nor a compound's (an L's notch
    // is): the ball against its solid (placed_body_meets), by the spot's
    // cube where a surface or a shell decides.
    std::shared_ptr<const Surface> cube;  // made once a surface grain, a surface part or a shell is near
    SurfaceScratch scratch;
    std::vector<SurfacePatchContact> patches;
    const auto meets = [&](const Near& n, const Vec3& centre, const Transform& ball_pose) {
      if (!(length(centre - n.pose.translation) <= n.radius + diameter / 2 &&
            intersect(given_shapes_[world_.bodies[n.body].shape], n.pose, ball, ball_pose)))
        return false;
      const ShapeTemplate& t = world_.templates[world_.bodies[n.body].shape];
      const bool by_surface = holds_surface(t);
      if (by_surface && !cube) cube = std::make_shared<const Surface>(box_surface(Box{{diameter / 2, diameter / 2, diameter / 2}}));
      return placed_body_meets(ball, ball_pose, by_surface ? cube : nullptr, false, t, n.pose, scratch, patches);
    };
    for (Real k = 0; k < nz && spots.size() < f.count; ++k)
      for (Real j = 0; j < ny && spots.size() < f.count; ++j)
        for (Real i = 0; i < nx && spots.size() < f.count; ++i) {
          if (++visited > cell_budget)
            throw BuildError(label + ": found room for only " + std::to_string(spots.size()) + " of the " +
                             std::to_string(f.count) + " bodies in the first " + number_text(cell_budget) +
                             " cells of the region; make the region smaller or closer to the bodies' size");
          const Vec3 centre = region_lo + Vec3{(i + 0.5) * cell.x, (j + 0.5) * cell.y, (k + 0.5) * cell.z} +
                              Vec3{u(rng) * slack.x, u(rng) * slack.y, u(rng) * slack.z};
          const Quat q = random_rotation(rng);
          bool free = !f.round || ball_inside(*f.round, centre, diameter / 2);
          for (const PlaneWall& p : world_.planes)
            if (dot(centre - p.point, p.normal) < diameter / 2) free = false;
          const Transform ball_pose = Transform::from(centre, Quat{});
          const Vec3 half{diameter / 2, diameter / 2, diameter / 2};
          for (std::size_t b = 0; free && b < large.size(); ++b)
            if (overlaps(large[b].box, Aabb{centre - half, centre + half}) && meets(large[b], centre, ball_pose))
              free = false;
          if (free)
            if (const auto it = grid.find(key(i, j, k)); it != grid.end())
              for (std::size_t b = 0; free && b < it->second.size(); ++b)
                if (meets(it->second[b], centre, ball_pose)) free = false;
          if (free) spots.emplace_back(centre, q);
        }
  }
  if (spots.size() < f.count)
    throw BuildError(label + ": the region holds only " + std::to_string(spots.size()) + " of the " +
                     std::to_string(f.count) + " bodies (each needs a free cube of side " + number_text(diameter) +
                     " m); enlarge the region or lower the count");
  std::uniform_int_distribution<std::size_t> pick(0, f.variants.size() - 1);
  const std::vector<Real> cumulative = cumulative_weights(f.weights, f.variants.size(), label);
  std::uniform_real_distribution<Real> uniform(0, 1);
  std::vector<std::uint32_t> placed;
  if (f.pieces > 0) {
    for (std::size_t k = 0; k < spots.size(); ++k) {
      const auto& [centre, q] = spots[k];
      const std::size_t v = f.weights.empty() ? pick(rng) : pick_weighted(cumulative, uniform(rng));
      const BodyShape& s = f.variants[v];
      const std::vector<std::uint32_t> pieces =
          add_bonded({.shape = s, .pieces = f.pieces, .seed = derived_seed(f.pieces_seed, k),
                      .relaxations = f.relaxations, .material = f.material,
                      .position = centre - rotate(q, s.pose.translation), .rotation = q, .velocity = f.velocity,
                      .label = label + " assembly " + std::to_string(k)});
      placed.insert(placed.end(), pieces.begin(), pieces.end());
    }
    return placed;
  }
  for (const auto& [centre, q] : spots) {
    Body b;
    b.id = next_id();
    const std::size_t v = f.weights.empty() ? pick(rng) : pick_weighted(cumulative, uniform(rng));
    b.shape = first_template + static_cast<std::uint32_t>(v);
    b.material = f.material;
    b.fixed = f.fixed;
    place(b, f.variants[v], centre - rotate(q, f.variants[v].pose.translation), q, f.velocity, {});
    world_.bodies.push_back(b);
    labels_.push_back(label + " body " + std::to_string(placed.size()));
    placed.push_back(static_cast<std::uint32_t>(world_.bodies.size() - 1));
  }
  return placed;
}

}  // namespace gjkdem::dem
