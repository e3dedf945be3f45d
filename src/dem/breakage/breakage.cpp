// Breakage at the end of a step (breakage.hpp, docs/breakage.md).
#include "gjkdem/dem/breakage.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/break_criterion.hpp"
#include "gjkdem/dem/split_body.hpp"
#include "gjkdem/shape/surface.hpp"
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

// A force on a grain where it acts, and the grain (an index into bodies).
struct GrainLoad {
  std::uint32_t body = 0;
  Vec3 point, force;
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

Real most_fragments(const World& w) noexcept {
  Real room = 0;
  for (const Body& b : w.bodies)
    if (!b.fixed) room += static_cast<Real>(most_fragments(w.templates[b.shape], w.materials[b.material]));
  return room;
}

bool world_breaks(const World& w) noexcept {
  return std::any_of(w.materials.begin(), w.materials.end(), [](const Material& m) { return m.strength.mean > 0; });
}

Real sphere_diameter(Real volume) noexcept { return std::cbrt(6 * volume / kPi); }

Real grain_size(const ShapeTemplate& t) noexcept { return sphere_diameter(t.unit_mass.volume); }

ShapeTemplate fragment_template(const Polytope& solid, std::uint32_t generation, bool with_surface) {
  ShapeTemplate t = make_template(Shape{solid});
  make_hull_surface(t.shape);  // a big fragment's kept surface now, not inside a step's overlap()
  t.generation = generation;
  if (with_surface) t.surface = std::make_shared<const Surface>(polytope_surface(solid));
  return t;
}

std::size_t built_templates(const World& w) noexcept {
  std::size_t n = w.templates.size();
  while (n > 0 && w.templates[n - 1].generation > 0) --n;
  return n;
}

std::vector<GrainSplit> find_splits(const World& w, const DomainRole* domain) {
  // The forces on each breakable grain (of the domain's own), in the order
  // of the contact list.
  // A piece of a bonded assembly splits only once its bonds have broken
  // (its bonds hold it by points of its own body).
  const std::vector<std::uint64_t> held = held_bodies(w.bonds);
  std::vector<std::uint8_t> can(w.bodies.size());
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const Body& b = w.bodies[i];
    can[i] = (!domain || domain->owns(i)) && breakable(w.templates[b.shape], w.materials[b.material], b) &&
             !std::binary_search(held.begin(), held.end(), b.id);
  }
  std::vector<GrainLoad> loads;
  for (const StepContact& c : w.results.contacts) {
    if (!c.active) continue;
    // b's image lies at b + shift, where the contact point is.
    if (can[c.b]) loads.push_back({c.b, c.geometry.point - image_shift_of(w.cell.now, c), c.force});
    if (!c.a_is_plane && can[c.a]) loads.push_back({c.a, c.geometry.point, -c.force});
  }
  std::stable_sort(loads.begin(), loads.end(), [](const GrainLoad& x, const GrainLoad& y) { return x.body < y.body; });

  std::vector<GrainSplit> splits;
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
    std::vector<Fragment> pieces = split_body(t, b, m.density, b.position, plane.normal);
    if (pieces.size() != 2) continue;
    GrainSplit split{.parent = b.id, .generation = t.generation + 1, .surface = t.surface != nullptr};
    try {
      for (std::size_t f = 0; f < 2; ++f) {
        const Fragment& piece = pieces[f];
        split.fragments[f] = {.vertices = {}, .position = piece.position, .orientation = piece.orientation,
                              .velocity = piece.velocity, .angular_momentum = piece.angular_momentum};
        const Polytope& solid = std::get<Polytope>(piece.shape.core);
        split.fragments[f].vertices.assign(solid.data->vertices.begin(), solid.data->vertices.end());
        split.templates[f] = fragment_template(solid, split.generation, split.surface);
      }
    } catch (const std::invalid_argument&) {
      continue;  // a piece too thin to be a surface grain's partner: the grain holds
    }
    splits.push_back(std::move(split));
  }
  return splits;
}

void apply_splits(World& w, std::span<GrainSplit> splits, std::uint64_t next_id, DomainRole* domain) {
  // The builder's room (most_fragments) holds every fragment of a whole
  // world; a copy of a world (a vector's copy keeps no spare room) takes it
  // again at its first split.
  if (!domain && w.bodies.size() + splits.size() > w.bodies.capacity())
    w.bodies.reserve(w.bodies.size() + splits.size() + static_cast<std::size_t>(most_fragments(w)));
  std::vector<std::uint64_t> broken_ids;
  for (GrainSplit& s : splits) {
    const std::uint32_t first = static_cast<std::uint32_t>(w.templates.size());
    for (ShapeTemplate& t : s.templates) w.templates.push_back(std::move(t));
    const std::uint64_t second_id = next_id++;
    broken_ids.push_back(s.parent);
    // The grain, where this world holds it (a domain holds only some).
    const auto at = std::lower_bound(w.bodies.begin(), w.bodies.end(), s.parent,
                                     [](const Body& b, std::uint64_t id) { return b.id < id; });
    if (at == w.bodies.end() || at->id != s.parent) continue;
    const std::size_t i = static_cast<std::size_t>(at - w.bodies.begin());
    const Body parent = *at;
    const Real volumes = w.templates[first].unit_mass.volume + w.templates[first + 1].unit_mass.volume;
    for (std::size_t f = 0; f < 2; ++f) {
      const GrainSplit::Piece& piece = s.fragments[f];
      Body b = parent;
      b.shape = first + static_cast<std::uint32_t>(f);
      b.position = piece.position, b.orientation = piece.orientation;
      b.velocity = piece.velocity, b.angular_momentum = piece.angular_momentum;
      // The other channels as their rows say (ByMass: by volume, one density).
      const Real share = w.templates[b.shape].unit_mass.volume / volumes;
      for (const BodyChannel& c : kBodyChannels) {
        if (c.compute || c.split == ChannelSplit::Kinematic || c.split == ChannelSplit::Copied) continue;
        Real* v = c.in(b);
        for (std::uint32_t k = 0; k < c.components; ++k) v[k] = c.split == ChannelSplit::Zeroed ? Real(0) : v[k] * share;
      }
      if (f == 0) {
        w.bodies[i] = b;
      } else {
        b.id = second_id;
        w.bodies.push_back(b);
        if (domain) domain->foreign.push_back(domain->foreign[i]);  // owned where its grain was, until the exchange
      }
    }
  }
  // The grains' pairs are forgotten: their fragments' contacts start afresh.
  std::sort(broken_ids.begin(), broken_ids.end());
  std::erase_if(w.pairs, [&](const PairState& p) {
    return std::binary_search(broken_ids.begin(), broken_ids.end(), p.key.lo) ||
           std::binary_search(broken_ids.begin(), broken_ids.end(), p.key.hi);
  });
  w.broken += splits.size();
  // Every box made again now, at the bodies' places (as a restored
  // checkpoint makes them from these anchors), and the broad phase's lists
  // built anew at the next step.
  w.search.boxes = {};
  update_boxes(w.bodies, w.templates, w.settings.box_skin, w.search.boxes, detail::thread_count(w.settings.threads));
  w.search.renew_cell = true;
  w.work.static_ready = false;
  w.work.candidates_current = false;
  w.forces_current = false;
}

int break_grains(World& w) {
  std::vector<GrainSplit> splits = find_splits(w, nullptr);
  if (splits.empty()) return 0;
  // Fragments in id order: the first takes its grain's place and id, the
  // second the next free id (the bodies stay in id order).
  apply_splits(w, splits, w.bodies.back().id + 1, nullptr);
  return static_cast<int>(splits.size());
}

}  // namespace gjkdem::dem
