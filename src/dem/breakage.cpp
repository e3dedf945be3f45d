// Breakage at the end of a step (breakage.hpp, docs/breakage.md).
#include "gjkdem/dem/breakage.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gjkdem/dem/break_criterion.hpp"
#include "gjkdem/dem/split_body.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem::dem {
namespace {

// A force on a grain where it acts, and the grain (an index into bodies).
struct GrainLoad {
  std::uint32_t body = 0;
  Vec3 point, force;
};

// What a grain that breaks becomes.
struct Split {
  std::uint32_t body = 0;
  std::vector<Fragment> fragments;
  std::vector<ShapeTemplate> templates;  // one per fragment
};

}  // namespace

bool breakable(const ShapeTemplate& t, const Material& m, const Body& b) noexcept {
  return m.strength.mean > 0 && !b.fixed && can_split(t) && grain_size(t) >= m.strength.smallest;
}

std::uint64_t most_fragments(const ShapeTemplate& t, const Material& m) noexcept {
  if (!(m.strength.mean > 0) || !can_split(t) || grain_size(t) < m.strength.smallest) return 0;
  const Real ratio = grain_size(t) / m.strength.smallest;
  const Real leaves = std::floor(64.0 / 27.0 * ratio * ratio * ratio);
  return leaves < 1e18 ? static_cast<std::uint64_t>(leaves) - 1 : std::uint64_t{1} << 60;
}

bool world_breaks(const World& w) noexcept {
  return std::any_of(w.materials.begin(), w.materials.end(), [](const Material& m) { return m.strength.mean > 0; });
}

Real grain_size(const ShapeTemplate& t) noexcept { return std::cbrt(6 * t.unit_mass.volume / kPi); }

ShapeTemplate fragment_template(std::span<const Vec3> vertices, std::uint32_t generation, bool with_surface) {
  const Polytope piece = make_polytope(vertices);
  ShapeTemplate t = make_template(Shape{piece});
  t.generation = generation;
  if (with_surface) t.surface = std::make_shared<const Surface>(polytope_surface(piece));
  return t;
}

std::size_t built_templates(const World& w) noexcept {
  std::size_t n = w.templates.size();
  while (n > 0 && w.templates[n - 1].generation > 0) --n;
  return n;
}

int break_grains(World& w) {
  // The forces on each breakable grain, in the order of the contact list.
  std::vector<std::uint8_t> can(w.bodies.size());
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const Body& b = w.bodies[i];
    can[i] = breakable(w.templates[b.shape], w.materials[b.material], b);
  }
  std::vector<GrainLoad> loads;
  for (const StepContact& c : w.work.contacts) {
    if (!c.active) continue;
    // b's image lies at b + shift, where the contact point is.
    if (can[c.b]) loads.push_back({c.b, c.geometry.point - image_shift_of(w.cell, c), c.force});
    if (!c.a_is_plane && can[c.a]) loads.push_back({c.a, c.geometry.point, -c.force});
  }
  if (loads.empty()) return 0;
  std::stable_sort(loads.begin(), loads.end(), [](const GrainLoad& x, const GrainLoad& y) { return x.body < y.body; });

  std::vector<Split> splits;
  std::vector<Vec3> points, forces;
  for (std::size_t k = 0; k < loads.size();) {
    const std::uint32_t i = loads[k].body;
    points.clear(), forces.clear();
    for (; k < loads.size() && loads[k].body == i; ++k) points.push_back(loads[k].point), forces.push_back(loads[k].force);
    const Body& b = w.bodies[i];
    const ShapeTemplate& t = w.templates[b.shape];
    const Material& m = w.materials[b.material];
    const BreakPlane plane = break_plane(grain_stress(b.position, t.unit_mass.volume, points, forces));
    const Real strength = grain_strength(m.strength, grain_size(t), strength_draw(m.strength.seed, b.id, t.generation));
    if (!(plane.deviatoric >= strength)) continue;
    Split split{i, split_body(t, b, m.density, b.position, plane.normal), {}};
    if (split.fragments.size() != 2) continue;
    try {
      for (const Fragment& f : split.fragments)
        split.templates.push_back(fragment_template(std::get<Polytope>(f.shape.core).data->vertices,
                                                    t.generation + 1, t.surface != nullptr));
    } catch (const std::invalid_argument&) {
      continue;  // a piece too thin to be a surface grain's partner: the grain holds
    }
    splits.push_back(std::move(split));
  }
  if (splits.empty()) return 0;
  // The builder's room (most_fragments) holds every fragment.
  if (w.bodies.size() + splits.size() > w.bodies.capacity()) throw std::logic_error("break_grains: no room reserved");

  // Fragments in id order: the first takes its grain's place and id, the
  // second the next free id (the bodies stay in id order).
  std::uint64_t next_id = w.bodies.back().id + 1;
  std::vector<std::uint64_t> broken_ids;
  for (Split& s : splits) {
    const Body parent = w.bodies[s.body];
    for (std::size_t f = 0; f < 2; ++f) {
      const Fragment& piece = s.fragments[f];
      w.templates.push_back(std::move(s.templates[f]));
      Body b = parent;
      b.shape = static_cast<std::uint32_t>(w.templates.size() - 1);
      b.position = piece.position, b.orientation = piece.orientation;
      b.velocity = piece.velocity, b.angular_momentum = piece.angular_momentum;
      b.force = {}, b.torque = {};
      if (f == 0) {
        w.bodies[s.body] = b;
      } else {
        b.id = next_id++;
        w.bodies.push_back(b);
      }
    }
    broken_ids.push_back(parent.id);
  }
  // The grains' pairs are forgotten: their fragments' contacts start afresh.
  std::erase_if(w.pairs, [&](const PairState& p) {
    return std::binary_search(broken_ids.begin(), broken_ids.end(), p.key.lo) ||
           std::binary_search(broken_ids.begin(), broken_ids.end(), p.key.hi);
  });
  w.broken += splits.size();
  w.forces_current = false;
  w.search.boxes = {};  // every box remade at the next step
  w.search.renew_cell = true;
  w.work.candidates_current = false;
  return static_cast<int>(splits.size());
}

}  // namespace gjkdem::dem
