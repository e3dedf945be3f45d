// WorldBuilder (world_builder.hpp): materials, motions, templates and bodies,
// and build(), which runs the checks and preparations of the other files of
// this folder (rules.cpp, walls.cpp, region_fill.cpp, start_checks.cpp,
// shape_preparation.cpp).
#include "gjkdem/dem/world_builder.hpp"

#include <algorithm>
#include <cmath>

#include "build/builder_detail.hpp"
#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/dem/surface_contact.hpp"
#include "gjkdem/tolerances.hpp"
#include "number_text.hpp"

namespace gjkdem::dem {

using detail::boundary_surface;
using detail::number_text;

namespace {

// Refuses a body's given channel values that break their rules (a channel
// that is not given, given twice, not finite, a load on a fixed body);
// whether any load is nonzero.
bool check_given(const BodyDef& d, const std::string& label) {
  bool loaded = false;
  for (std::size_t i = 0; i < d.given.size(); ++i) {
    const BodyChannel* c = d.given[i].channel;
    if (!c || !(c->use & kChannelGiven))
      throw BuildError(label + ": " + (c ? "channel '" + std::string(c->name) + "'" : std::string("a null channel")) +
                       " is not one a body is given (kChannelGiven)");
    for (std::size_t j = 0; j < i; ++j)
      if (d.given[j].channel == c) throw BuildError(label + ": " + std::string(c->name) + " is given twice");
    bool nonzero = false;
    for (std::uint32_t k = 0; k < c->components; ++k) {
      if (!std::isfinite(d.given[i].values[k])) throw BuildError(label + ": " + std::string(c->name) + " must be finite");
      nonzero = nonzero || d.given[i].values[k] != 0;
    }
    if (!(c->use & kChannelLoad) || !nonzero) continue;
    if (d.fixed) throw BuildError(label + ": a fixed body takes no applied load (" + std::string(c->name) + " is for free bodies)");
    loaded = true;
  }
  return loaded;
}

}  // namespace

WorldBuilder::WorldBuilder(const WorldSettings& settings) : settings_(settings) {
  check_settings(settings);
  world_.settings = settings;
}

WorldBuilder::WorldBuilder(World world) : settings_(world.settings), world_(std::move(world)) {
  for (const ShapeTemplate& t : world_.templates) given_shapes_.push_back(t.shape);
  for (const BodyName& n : world_.names) names_.insert(n.name);
  for (const Body& b : world_.bodies) {
    labels_.push_back("body " + std::to_string(b.id));
    groups_ = std::max(groups_, b.group);
  }
  prepared_templates_ = world_.templates.size();
  world_.forces_current = false;
  continued_ = true;  // its cell keeps the deformation it has
}

std::uint32_t WorldBuilder::add_material(const Material& m) {
  if (find_material(m.name)) throw BuildError("material '" + m.name + "'", "name", "is defined twice");
  dem::check_material(m);
  world_.materials.push_back(m);
  return static_cast<std::uint32_t>(world_.materials.size() - 1);
}

std::optional<std::uint32_t> WorldBuilder::find_material(std::string_view name) const {
  for (std::uint32_t k = 0; k < world_.materials.size(); ++k)
    if (world_.materials[k].name == name) return k;
  return std::nullopt;
}

void WorldBuilder::check_material(std::uint32_t material, const std::string& label) const {
  if (material >= world_.materials.size())
    throw BuildError(label + ": material " + std::to_string(material) + " was never added");
}

std::uint32_t WorldBuilder::add_motion(const PrescribedMotion& motion, const std::string& label) {
  try {
    check_motion(motion);
  } catch (const std::invalid_argument& e) {
    throw BuildError(label + ": " + e.what());
  }
  if (world_.motions.size() >= 0xffff) throw BuildError(label + ": more than 65,534 motions");
  world_.motions.push_back(motion);
  return static_cast<std::uint32_t>(world_.motions.size());
}

void WorldBuilder::check_motion_number(std::uint32_t motion, const std::string& label) const {
  if (motion > world_.motions.size())
    throw BuildError(label + ": motion " + std::to_string(motion) + " was never added");
}

// A fixed body placed where it was given, from now on moved by `motion`.
void WorldBuilder::drive(std::uint32_t index, std::uint32_t motion) {
  if (motion == 0) return;
  Body& b = world_.bodies[index];
  b.motion = static_cast<std::uint16_t>(motion);
  world_.driven.push_back({index, b.position, b.orientation});
}

std::uint64_t WorldBuilder::next_id() const noexcept {
  return world_.bodies.empty() ? 0 : world_.bodies.back().id + 1;
}

std::size_t WorldBuilder::moving_count() const noexcept {
  return static_cast<std::size_t>(
      std::count_if(world_.bodies.begin(), world_.bodies.end(), [](const Body& b) { return !b.fixed; }));
}

std::uint32_t WorldBuilder::add_template(const BodyShape& shape, bool fixed, const std::string& label) {
  if (int(shape.shell != nullptr) + int(shape.surface != nullptr) + int(is_compound(shape)) > 1)
    throw BuildError(label + ": a shape is one of a thin shell, a surface and a compound's parts; it gives more than one");
  ShapeTemplate t;
  try {
    if (shape.shell) {
      if (settings_.model == ContactModel::Volume)
        throw BuildError(label + ": a thin shell takes the Hertz and linear laws (the volume law meets solids)");
      t = make_shell_template(shape.shell, fixed);
    } else if (shape.surface) {
      t = make_surface_template(shape.surface, fixed);
    } else if (is_compound(shape)) {
      check_compound(shape, label);
      t = make_compound_template(shape.parts, fixed, shape.surface_parts);
    } else {
      t = fixed ? make_wall_template(shape.shape) : make_template(shape.shape);
    }
  } catch (const std::invalid_argument& e) {
    throw BuildError(label + (fixed ? ": cannot be a body: " : ": cannot be a moving body: ") + e.what());
  }
  given_shapes_.push_back(t.shape);  // a compound's hull
  world_.templates.push_back(std::move(t));
  return static_cast<std::uint32_t>(world_.templates.size() - 1);
}

// A compound's parts may touch, not overlap (their volumes add up): convex
// parts by their penetration depth, a surface and another part by the
// patches of their overlap (depth: volume over contact area).
void WorldBuilder::check_compound(const BodyShape& shape, const std::string& label) const {
  const std::span<const PlacedShape> parts = shape.parts;
  const std::span<const PlacedSurface> surfaces = shape.surface_parts;
  const std::size_t n = parts.size() + surfaces.size();
  if (n > kMaxCompoundParts)
    throw BuildError(label + ": a compound has at most " + std::to_string(kMaxCompoundParts) + " parts");
  const auto overlap_error = [&](std::size_t i, std::size_t j, const std::string& by) {
    return BuildError(label + ": parts " + std::to_string(i) + " and " + std::to_string(j) + " overlap " + by +
                      " (parts may touch, not overlap: their volumes add up)");
  };
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (std::size_t j = i + 1; j < parts.size(); ++j) {
      const Real size = 2 * std::fmax(bounding_radius(parts[i].shape), bounding_radius(parts[j].shape));
      const PenetrationResult p = penetration(parts[i].shape, parts[i].pose, parts[j].shape, parts[j].pose);
      if (p.intersect && p.depth > kCompoundOverlapRelTol * size)
        throw overlap_error(i, j, "by " + number_text(p.depth) + " m");
    }
  if (surfaces.empty()) return;
  // Each part's closed surface (a convex part's boundary) and its radius.
  std::vector<std::shared_ptr<const Surface>> solids;
  std::vector<Real> radii;
  for (const PlacedShape& p : parts) {
    try {
      solids.push_back(boundary_surface(p.shape, settings_.tessellation));
    } catch (const SurfaceError& e) {
      throw BuildError(label + ": part " + std::to_string(solids.size()) + " cannot meet its surface parts: " + e.what());
    }
    radii.push_back(bounding_radius(p.shape));
  }
  for (const PlacedSurface& p : surfaces) {
    solids.push_back(p.surface);
    Real radius = 0;  // of the sphere about its frame's origin holding its vertices
    for (const Vec3& v : p.surface->vertices) radius = std::fmax(radius, length(v));
    radii.push_back(radius);
  }
  const auto pose_of = [&](std::size_t k) { return k < parts.size() ? parts[k].pose : surfaces[k - parts.size()].pose; };
  SurfaceScratch scratch;
  std::vector<SurfacePatchContact> patches;
  for (std::size_t j = parts.size(); j < n; ++j)
    for (std::size_t i = 0; i < j; ++i) {
      const GeometryStatus met = surface_patches(solids[i], pose_of(i), solids[j], pose_of(j), scratch, patches);
      if (met != GeometryStatus::Touching)
        throw overlap_error(i, j, met == GeometryStatus::Engulfed ? "(one wholly inside the other)" : "(one through the other)");
      const Real size = 2 * std::fmax(radii[i], radii[j]);
      for (const SurfacePatchContact& p : patches)
        if (p.geometry.depth > kCompoundOverlapRelTol * size)
          throw overlap_error(i, j, "by " + number_text(p.geometry.volume) + " m^3 (mean depth " +
                                        number_text(p.geometry.depth) + " m)");
    }
}

// The body's principal frame from the author's frame (position, rotation) and
// the shape's frame within it.
void WorldBuilder::place(Body& b, const BodyShape& s, const Vec3& position, const Quat& rotation,
                         const Vec3& velocity, const Vec3& spin) const {
  const ShapeTemplate& t = world_.templates[b.shape];
  const Transform author = Transform::from(position, rotation);
  const Quat shape_q = rotation * quat_from_matrix(s.pose.rotation);
  b.orientation = normalized(shape_q * t.principal.rotation);
  b.position = apply(author, apply(s.pose, t.unit_mass.centroid));
  b.velocity = velocity;
  if (!b.fixed) {  // L = R I R^T w, with I the principal moments
    const Vec3 moments = t.principal.moments * world_.materials[b.material].density;
    const Vec3 local = rotate(conjugate(b.orientation), spin);
    b.angular_momentum = rotate(b.orientation, Vec3{moments.x * local.x, moments.y * local.y, moments.z * local.z});
  }
}

std::uint32_t WorldBuilder::add_body(const BodyDef& d) {
  const std::string label = !d.label.empty() ? d.label
                            : !d.name.empty() ? d.name
                                              : "body " + std::to_string(world_.bodies.size());
  if (!d.name.empty()) {
    if (std::any_of(d.name.begin(), d.name.end(),
                    [](char c) { return c == ',' || c == '"' || static_cast<unsigned char>(c) < 0x20; }))
      throw BuildError(label + ": its name holds a comma, a quote or a control character (it is a trace.csv field)");
    if (names_.count(d.name)) throw BuildError(label + ": two bodies are named '" + d.name + "'");
  }
  check_material(d.material, label);
  for (const Vec3& v : {d.position, d.velocity, d.angular_velocity})
    if (!is_finite(v)) throw BuildError(label + ": position, velocity and angular velocity must be finite");
  if (!(max_abs(d.position) <= kMaxCoordinate))
    throw BuildError(label + ": position is outside the supported range [-1e100, 1e100] m");
  if (d.fixed && (length(d.velocity) > 0 || length(d.angular_velocity) > 0))
    throw BuildError(label + ": a fixed body cannot move (velocity and angular_velocity must be 0)");
  const bool loaded = check_given(d, label);
  check_motion_number(d.motion, label);
  if (d.motion && !d.fixed) throw BuildError(label + ": a motion is for fixed bodies (forces move the others)");
  Body b;
  b.id = next_id();
  b.material = d.material;
  b.fixed = d.fixed;
  if (d.shared_shape >= 0) {
    if (d.shared_shape >= static_cast<std::int64_t>(shared_.size()))
      throw BuildError(label + ": shared shape " + std::to_string(d.shared_shape) + " was never added");
    const SharedShape& shared = shared_[static_cast<std::size_t>(d.shared_shape)];
    if (d.fixed != shared.fixed)
      throw BuildError(label + ": shared shape " + std::to_string(d.shared_shape) + " was added for " +
                       (shared.fixed ? "fixed" : "moving") + " bodies");
    b.shape = shared.index;
    place(b, {given_shapes_[shared.index], shared.pose}, d.position, d.rotation, d.velocity, d.angular_velocity);
  } else {
    b.shape = add_template(d.shape, d.fixed, label);
    place(b, d.shape, d.position, d.rotation, d.velocity, d.angular_velocity);
  }
  for (const GivenChannel& g : d.given) std::copy_n(g.values.begin(), g.channel->components, g.channel->in(b));
  world_.applied_loads = world_.applied_loads || loaded;
  world_.bodies.push_back(b);
  labels_.push_back(label);
  if (!d.name.empty()) world_.names.push_back({b.id, d.name}), names_.insert(d.name);
  const std::uint32_t index = static_cast<std::uint32_t>(world_.bodies.size() - 1);
  explicit_.push_back(index);
  drive(index, d.motion);
  return index;
}

std::uint32_t WorldBuilder::add_shape(const BodyShape& shape, const std::string& label, bool fixed) {
  shared_.push_back({add_template(shape, fixed, label), shape.pose, fixed});
  return static_cast<std::uint32_t>(shared_.size() - 1);
}

World WorldBuilder::build() {
  if (world_.bodies.empty() && world_.planes.empty() && world_.inflows.empty()) throw BuildError("the world is empty");
  place_driven(world_);  // where their motions have them now, for the checks
  check_periodic_cell();
  if (!world_.bonds.empty() && world_.cell.now.active())
    throw BuildError("bonded assemblies cannot be in a periodic world yet (their bonds do not wrap)");
  prepare_shapes();
  prepare_surfaces();
  say("checking that the " + std::to_string(world_.bodies.size()) + " bodies start apart");
  check_explicit_bodies();
  check_inflow_regions();
  world_.material_pairs = make_material_table(world_.materials, settings_.model);
  // Room for every body the inflows can insert and every fragment breakage
  // can make: the bodies never move in memory.
  Real room = static_cast<Real>(world_.bodies.size()) + most_fragments(world_);  // a real: no overflow
  for (std::size_t k = 0; k < world_.inflows.size(); ++k) {
    const Inflow& f = world_.inflows[k];
    const std::uint64_t most = inflow_capacity(f, {world_.templates, world_.materials});
    Real each = 1;
    for (const std::uint32_t t : f.templates)
      each = std::fmax(each, 1 + static_cast<Real>(most_fragments(world_.templates[t], world_.materials[f.material])));
    room += static_cast<Real>(most - std::min(most, world_.inflow_states[k].inserted)) * each;
  }
  if (room > static_cast<Real>(kMostBodies))
    throw BuildError("the world could hold " + number_text(room) + " bodies with its inflows and the fragments of "
                     "its grains that break (at most " + std::to_string(kMostBodies) +
                     "): fewer bodies, or a larger unbreakable_below (a grain ends in up to (64/27) (d / "
                     "unbreakable_below)^3 fragments)");
  world_.bodies.reserve(static_cast<std::size_t>(room));
  World out = std::move(world_);
  world_ = World{};
  world_.settings = settings_;
  labels_.clear();
  names_.clear();
  inflow_labels_.clear();
  given_shapes_.clear();
  explicit_.clear();
  assemblies_.clear();
  groups_ = 0;
  prepared_templates_ = 0;
  continued_ = false;
  return out;
}

}  // namespace gjkdem::dem
