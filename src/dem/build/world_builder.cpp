#include "gjkdem/dem/world_builder.hpp"

#include <algorithm>
#include <tuple>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/contact/half_space.hpp"
#include "gjkdem/dem/surface_contact.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "gjkdem/shape/tessellate.hpp"
#include "gjkdem/tolerances.hpp"
#include "number_text.hpp"

namespace gjkdem::dem {
namespace {

using detail::number_text;

// A solid polytope or box without margin: what the volume law clips.
bool solid_polytope(const Shape& s) {
  if (s.margin != 0) return false;
  if (const auto* b = std::get_if<Box>(&s.core))
    return b->half_extents.x > 0 && b->half_extents.y > 0 && b->half_extents.z > 0;
  if (const auto* p = std::get_if<Polytope>(&s.core)) return !p->data->triangles.empty();
  return false;
}

// Flat cores without a margin: a point, a segment, a triangle, a flat
// polytope or box. Curved cores and anything with a margin have volume.
bool without_volume(const Shape& s) {
  return s.margin == 0 && !solid_polytope(s) &&
         (std::holds_alternative<Point>(s.core) || std::holds_alternative<Segment>(s.core) ||
          std::holds_alternative<Triangle>(s.core) || std::holds_alternative<Polytope>(s.core) ||
          std::holds_alternative<Box>(s.core));
}

// The closed surface surface grains meet a convex shape of volume by: a
// solid polytope's hull triangles (a big hull's own, kept with it:
// hull_surface), a curved shape's inscribed tessellation (throws
// SurfaceError for a flat one).
std::shared_ptr<const Surface> boundary_surface(const Shape& s, int tessellation) {
  if (std::holds_alternative<Box>(s.core) && s.margin == 0)
    return std::make_shared<const Surface>(box_surface(std::get<Box>(s.core)));
  if (solid_polytope(s)) {
    const Polytope& hull = std::get<Polytope>(s.core);
    if (std::shared_ptr<const Surface> kept = hull_surface(hull)) return kept;
    return std::make_shared<const Surface>(polytope_surface(hull));
  }
  return std::make_shared<const Surface>(polytope_surface(tessellate(s, tessellation).polytope));
}

}  // namespace

namespace {

// A field's rule: throws BuildError(subject, key, rule) unless `ok`.
void need(bool ok, const std::string& subject, const std::string& key, const std::string& rule) {
  if (!ok) throw BuildError(subject, key, rule);
}

}  // namespace

void check_material(const Material& m) {
  const std::string who = "material '" + m.name + "'";
  for (const auto& [key, v] : {std::pair{"density", m.density}, {"youngs_modulus", m.youngs_modulus},
                               {"poisson_ratio", m.poisson_ratio}, {"restitution", m.restitution},
                               {"friction", m.friction}, {"rolling_friction", m.rolling_friction},
                               {"rolling_damping", m.rolling_damping}})
    need(std::isfinite(v), who, key, "must be finite");
  need(m.density > 0, who, "density", "must be > 0");
  need(m.youngs_modulus > 0, who, "youngs_modulus", "must be > 0");
  need(m.poisson_ratio > -1 && m.poisson_ratio < 0.5, who, "poisson_ratio", "must lie in (-1, 0.5)");
  need(m.restitution > 0 && m.restitution <= 1, who, "restitution", "must lie in (0, 1]");
  need(m.friction >= 0, who, "friction", "must be >= 0");
  need(m.rolling_friction >= 0, who, "rolling_friction", "must be >= 0");
  need(m.rolling_damping >= 0 && m.rolling_damping <= 1, who, "rolling_damping", "must lie in [0, 1]");
  // Breakage (docs/breakage.md), by the scene's keys.
  const Strength& s = m.strength;
  need(std::isfinite(s.mean) && s.mean >= 0, who, "strength", "must be finite and >= 0 (Pa; 0: never breaks)");
  need(std::isfinite(s.weibull_modulus) && s.weibull_modulus > 0, who, "weibull_modulus", "must be finite and > 0");
  need(std::isfinite(s.reference_size) && s.reference_size >= 0, who, "strength_size", "must be finite and > 0 (m)");
  need(std::isfinite(s.smallest) && s.smallest >= 0, who, "unbreakable_below", "must be finite and > 0 (m)");
  if (s.mean > 0) {
    need(s.reference_size > 0, who, "strength_size",
         "must be given, > 0 (m): the size whose grains' mean strength is `strength`");
    need(s.smallest > 0, who, "unbreakable_below",
         "must be given, > 0 (m): grains smaller than this no longer break, which ends the cascade");
  }
  const Glue& g = m.glue;
  for (const auto& [key, v] : {std::pair{"bond_tensile_strength", g.tensile_strength},
                               {"bond_shear_strength", g.shear_strength},
                               {"bond_moment_strength", g.moment_strength},
                               {"bond_normal_stiffness", g.normal_stiffness},
                               {"bond_shear_stiffness", g.shear_stiffness}})
    need(std::isfinite(v) && v >= 0, who, key, "must be finite and >= 0");
  need(std::isfinite(g.damping) && g.damping >= 0 && g.damping <= 1, who, "bond_damping", "must lie in [0, 1]");
  if (g.tensile_strength > 0)
    need(g.shear_strength > 0, who, "bond_shear_strength",
         "must be given, > 0 (Pa), with a bond_tensile_strength");
}

void check_contact_settings(const WorldSettings& s) {
  const std::string who = "settings";
  need(std::isfinite(s.linear_stiffness) && s.linear_stiffness >= 0, who, "linear_stiffness",
       "must be finite and >= 0 (N/m; 0: from the materials)");
  need(std::isfinite(s.volume_stiffness) && s.volume_stiffness >= 0, who, "volume_stiffness",
       "must be finite and >= 0 (N/m^3; 0: from the materials)");
  need(s.tessellation >= kMinTessellation && s.tessellation <= kMaxTessellation, who, "tessellation",
       "must be between " + std::to_string(kMinTessellation) + " and " + std::to_string(kMaxTessellation) +
           " directions");
  need(std::isfinite(s.box_skin) && s.box_skin >= 0, who, "box_skin", "must be finite and >= 0");
}

void check_cell(const PeriodicCell& cell, const CellControl& control) {
  const std::string who = "periodic cell";
  const char* names[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (!cell.axes[a]) continue;
    need(std::isfinite(cell.lo[a]) && std::isfinite(cell.hi[a]) && cell.hi[a] > cell.lo[a], who, names[a],
         "must be [min, max] with max > min (finite)");
    need(std::fabs(cell.lo[a]) <= kMaxCoordinate && std::fabs(cell.hi[a]) <= kMaxCoordinate, who, names[a],
         "must lie within [-1e100, 1e100] m");
  }
  need(cell.tilt == Vec3{}, who, "tilt", "must be zero: a periodic cell starts unsheared");
  for (int k = 0; k < 6; ++k) {
    if (control.mode[k] == CellMode::Fixed) continue;
    const std::string key =
        std::string(control.mode[k] == CellMode::Stress ? "stress." : "strain_rate.") + kCellComponents[k];
    // A component deforms the cell along its first axis with the position on its second.
    const int along = k < 3 ? k : k == kYZ ? 1 : 0, across = k < 3 ? k : k == kXY ? 1 : 2;
    if (!cell.axes[along] || !cell.axes[across])
      throw BuildError(who, key, std::string("the cell is not periodic on ") + names[cell.axes[along] ? across : along]);
    need(std::isfinite(control.value[k]), who, key, "must be finite");
    if (control.mode[k] == CellMode::Stress && k < 3)
      need(control.value[k] > 0, who, key, "must be > 0 (Pa, compression positive)");
  }
  if (!control.servo()) {
    need(control.max_strain_rate == 0, who, "max_strain_rate",
         "bounds the servo of a cell driven to a stress: give stress too");
    return;
  }
  need(cell.axes[0] && cell.axes[1] && cell.axes[2], who, "stress",
       "needs a cell periodic on x, y and z (the stress is the contacts' over the cell's volume)");
  need(control.max_strain_rate != 0, who, "stress", "needs max_strain_rate too (1/s): the servo's largest strain rate");
  need(control.max_strain_rate > 0 && std::isfinite(control.max_strain_rate), who, "max_strain_rate",
       "must be finite and > 0 (1/s)");
  bool normal = false;
  for (int a = 0; a < 3; ++a) normal = normal || control.mode[a] == CellMode::Stress;
  need(normal, who, "stress", "needs a normal stress (x, y or z) besides shear ones: its size scales the servo");
}

void check_settings(const WorldSettings& s) {
  const std::string who = "settings";
  need(is_finite(s.gravity), who, "gravity", "must be finite");
  need(s.threads >= 0 && s.threads <= kMaxThreads, who, "threads",
       "must be 0 (all cores) or a thread count up to " + std::to_string(kMaxThreads));
  check_contact_settings(s);
  try {
    check_cell(s.periodic, s.cell_control);
  } catch (const BuildError& e) {  // named as the scene nests it: [simulation.periodic]
    throw BuildError(who, "periodic." + e.key, e.rule);
  }
}

void check_fill_count(std::int64_t count) {
  need(count > 0 && static_cast<std::uint64_t>(count) <= kMaxFillCount, "region", "count",
       "must be a positive integer up to " + std::to_string(kMaxFillCount));
}

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
      if (!surface_patches(solids[i], pose_of(i), solids[j], pose_of(j), ContactModel::Volume, scratch, patches))
        throw overlap_error(i, j, "(one wholly inside the other)");
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
  if (d.fixed && (length(d.velocity) > 0 || length(d.angular_velocity) > 0))
    throw BuildError(label + ": a fixed body cannot move (velocity and angular_velocity must be 0)");
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

void WorldBuilder::add_plane(const Vec3& point, const Vec3& normal, std::uint32_t material, const std::string& label,
                             std::uint32_t motion) {
  check_material(material, label);
  check_motion_number(motion, label);
  if (!is_finite(point) || !is_finite(normal)) throw BuildError(label + ": point and normal must be finite");
  // Scaled first, so that huge components do not overflow the length.
  const Real largest = max_abs(normal);
  const Vec3 unit = largest > 0 ? normalized(normal / largest) : Vec3{};
  if (!(length(unit) > 0.5)) throw BuildError(label + ": the normal must not be zero");
  world_.planes.push_back({kPlaneIdBase + world_.planes.size(), point, unit, material, motion, point, unit});
}

std::uint32_t WorldBuilder::add_fixed_piece(const Shape& shape, const Vec3& position, std::uint32_t material,
                                            std::uint32_t group, const std::string& label, std::uint32_t motion) {
  Body b;
  b.id = next_id();
  b.shape = add_template(BodyShape{shape, {}}, true, label);
  b.material = material;
  b.group = group;
  b.fixed = true;
  b.position = position;
  world_.bodies.push_back(b);
  labels_.push_back(label);
  const std::uint32_t index = static_cast<std::uint32_t>(world_.bodies.size() - 1);
  drive(index, motion);
  return index;
}

void WorldBuilder::add_box_walls(const Vec3& lo, const Vec3& hi, bool open_top, Real t, std::uint32_t material,
                                 const std::string& label, std::uint32_t motion) {
  check_material(material, label);
  check_motion_number(motion, label);
  if (!is_finite(lo) || !is_finite(hi) || !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
    throw BuildError(label + ": max must exceed min on every axis");
  if (!(t > 0) || !std::isfinite(t)) throw BuildError(label + ": the thickness must be > 0");
  const std::uint32_t group = ++groups_;
  const Vec3 c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
  auto slab = [&](const Vec3& half, const Vec3& centre, const char* side) {
    add_fixed_piece(Shape{Box{half}}, centre, material, group, label + side, motion);
  };
  slab({h.x + 2 * t, h.y + 2 * t, t / 2}, {c.x, c.y, lo.z - t / 2}, " (floor)");
  if (!open_top) slab({h.x + 2 * t, h.y + 2 * t, t / 2}, {c.x, c.y, hi.z + t / 2}, " (roof)");
  slab({t / 2, h.y + t, h.z}, {lo.x - t / 2, c.y, c.z}, " (side -x)");
  slab({t / 2, h.y + t, h.z}, {hi.x + t / 2, c.y, c.z}, " (side +x)");
  slab({h.x, t / 2, h.z}, {c.x, lo.y - t / 2, c.z}, " (side -y)");
  slab({h.x, t / 2, h.z}, {c.x, hi.y + t / 2, c.z}, " (side +y)");
}

void WorldBuilder::add_mesh_walls(std::span<const Vec3> vertices,
                                  std::span<const std::array<std::uint32_t, 3>> triangles, Real thick,
                                  std::uint32_t material, const std::string& label, std::uint32_t motion) {
  check_material(material, label);
  check_motion_number(motion, label);
  for (const Vec3& v : vertices)
    if (!is_finite(v)) throw BuildError(label + ": vertices must be finite (a scale beyond double precision?)");
  if (!(thick > 0) || !std::isfinite(thick)) throw BuildError(label + ": the thickness must be > 0 and finite");
  const std::uint32_t group = ++groups_;
  std::size_t index = 0;
  for (const auto& tri : triangles) {
    const std::string piece = label + " (triangle " + std::to_string(index++) + ")";
    for (std::uint32_t v : tri)
      if (v >= vertices.size()) throw BuildError(piece + ": vertex index out of range");
    const Vec3 a = vertices[tri[0]], b = vertices[tri[1]], c = vertices[tri[2]];
    const Vec3 n3 = cross(b - a, c - a);
    if (!(length(n3) > 0)) continue;  // degenerate triangles hold nothing
    const Vec3 centre = (a + b + c) / 3.0, n = normalized(n3) * (thick / 2);
    Shape shape;
    if (settings_.model == ContactModel::Volume) {
      const Vec3 prism[6] = {a - centre + n, b - centre + n, c - centre + n, a - centre - n, b - centre - n, c - centre - n};
      shape = Shape{make_polytope(prism)};
    } else {
      shape = Shape{Triangle{{a - centre, b - centre, c - centre}}, thick / 2};
    }
    const std::uint32_t placed = add_fixed_piece(shape, centre, material, group, piece, motion);
    world_.templates[world_.bodies[placed].shape].wall_face = Triangle{{a - centre, b - centre, c - centre}};
  }
}

std::string cylinder_segments_problem(std::int64_t segments) {
  constexpr std::int64_t kFewest = 8, kMost = 4096;
  if (segments >= kFewest && segments <= kMost) return "";
  return "must be " + std::to_string(kFewest) + " to " + std::to_string(kMost);
}

Real cylinder_wall_thickness(const CylinderWall& w) { return w.thickness > 0 ? w.thickness : 0.02 * w.radius; }

void cylinder_wall_mesh(const CylinderWall& w, const std::string& label, std::vector<Vec3>& vertices,
                        std::vector<std::array<std::uint32_t, 3>>& triangles) {
  if (!is_finite(w.base) || !is_finite(w.axis) || !(length(w.axis) > 0))
    throw BuildError(label + ": the base and a non-zero axis must be finite");
  if (!(w.radius > 0) || !std::isfinite(w.radius) || !(w.height > 0) || !std::isfinite(w.height))
    throw BuildError(label + ": the radius and height must be finite and > 0");
  if (const std::string why = cylinder_segments_problem(w.segments); !why.empty())
    throw BuildError(label + ": segments " + why);
  if (!(w.thickness >= 0) || !std::isfinite(w.thickness)) throw BuildError(label + ": the thickness must be >= 0");
  const Real t = cylinder_wall_thickness(w);
  const Vec3 a = normalized(w.axis);
  Vec3 u, v;
  orthonormal_basis(a, u, v);
  const int n = w.segments;
  // A piece's middle lies half a thickness behind its inner face: the flats
  // at radius + t/2 (their corners farther out), the caps t/2 beyond the ends.
  const Real corner = (w.radius + t / 2) / std::cos(kPi / n);
  const Vec3 low = w.base - a * (t / 2), high = w.base + a * (w.height + t / 2);
  vertices.clear(), triangles.clear();
  for (int k = 0; k < n; ++k) {
    const Real angle = 2 * kPi * k / n;
    const Vec3 out = (u * std::cos(angle) + v * std::sin(angle)) * corner;
    vertices.push_back(low + out);
    vertices.push_back(high + out);
  }
  const auto at = [n](int k, int level) { return static_cast<std::uint32_t>(2 * ((k % n + n) % n) + level); };
  for (int k = 0; k < n; ++k) {
    triangles.push_back({at(k, 0), at(k + 1, 0), at(k + 1, 1)});
    triangles.push_back({at(k, 0), at(k + 1, 1), at(k, 1)});
  }
  // Caps: fans about their centres, the side walls' ends reaching them. All
  // triangles face out (counter-clockwise seen from outside), so a capped
  // cylinder is a closed mesh (the scene's containment check takes it).
  for (const auto& [capped, centre, level] : {std::tuple{w.bottom, low, 0}, std::tuple{w.top, high, 1}}) {
    if (!capped) continue;
    const auto middle = static_cast<std::uint32_t>(vertices.size());
    vertices.push_back(centre);
    for (int k = 0; k < n; ++k)
      triangles.push_back(level ? std::array{middle, at(k, 1), at(k + 1, 1)} : std::array{middle, at(k + 1, 0), at(k, 0)});
  }
}

void WorldBuilder::add_cylinder_walls(const CylinderWall& wall, std::uint32_t material, const std::string& label,
                                      std::uint32_t motion) {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  cylinder_wall_mesh(wall, label, vertices, triangles);
  add_mesh_walls(vertices, triangles, cylinder_wall_thickness(wall), material, label, motion);
}

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
      const bool by_surface = t.surface_grain || t.shell ||
                              std::any_of(t.parts.begin(), t.parts.end(), [](const TemplatePart& p) { return p.surface_grain; });
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

namespace {

// How deep a part of body a and a part of body b overlap at the start: a
// surface and a mesh wall's piece by the margin model, a convex part and a
// piece by their penetration, two parts by their surfaces' patches
// (infinite: one wholly inside the other), or by their penetration in a
// world without surfaces; 0 where one part has no surface to meet the
// other's by (no volume: the run reports the pair).
Real start_overlap(std::span<const ShapeTemplate> templates, const Body& a, std::uint32_t pa, const Body& b,
                   std::uint32_t pb, SurfaceScratch& scratch, std::vector<SurfacePatchContact>& patches,
                   std::vector<std::uint32_t>& hosts) {
  const ShapeTemplate &ta = templates[a.shape], &tb = templates[b.shape];
  const PartPose at_a = part_pose(ta, a, pa), at_b = part_pose(tb, b, pb);
  patches.clear();
  if (ta.shell || tb.shell) {  // the margin model, against another body's surface
    const bool shell_is_a = ta.shell != nullptr;
    const ShapeTemplate &shell = shell_is_a ? ta : tb, &other = shell_is_a ? tb : ta;
    const PartPose &at_shell = shell_is_a ? at_a : at_b, &body = shell_is_a ? at_b : at_a;
    if (margin_piece(other)) {  // the shell's triangles against the piece, with both margins
      const MarginTriangle piece = placed_margin_triangle(other, body.pose);
      margin_patches(shell_triangles(*shell.shell), at_shell.pose, {&piece, 1}, scratch, patches, hosts);
    } else if (shell_patches(shell, at_shell.pose, other, shell_is_a ? pb : pa, body, shell_is_a, scratch, patches) ==
               GeometryStatus::Unsupported) {
      return 0;  // the run reports the pair
    }
  } else if (margin_piece(ta) || margin_piece(tb)) {
    const bool piece_is_a = margin_piece(ta) != nullptr;
    const ShapeTemplate& other = piece_is_a ? tb : ta;
    const std::uint32_t part = piece_is_a ? pb : pa;
    const PartPose& piece = piece_is_a ? at_a : at_b;
    const PartPose& body = piece_is_a ? at_b : at_a;
    if (!surface_side(other, part)) {
      const PenetrationResult pr = penetration(*body.shape, body.pose, *piece.shape, piece.pose);
      return pr.intersect ? pr.depth : 0;
    }
    const MarginTriangle t = placed_margin_triangle(piece_is_a ? ta : tb, piece.pose);
    margin_patches(triangles_of(*surface_of(other, part)), body.pose, {&t, 1}, scratch, patches,
                   hosts);
  } else {
    const std::shared_ptr<const Surface>&sa = surface_of(ta, pa), &sb = surface_of(tb, pb);
    if (!sa && !sb) {  // convex parts (a world without surfaces): their penetration
      const PenetrationResult pr = penetration(*at_a.shape, at_a.pose, *at_b.shape, at_b.pose);
      return pr.intersect ? pr.depth : 0;
    }
    if (!sa || !sb) return 0;
    if (!surface_patches(sa, at_a.pose, sb, at_b.pose, ContactModel::Volume, scratch, patches))
      return std::numeric_limits<Real>::infinity();
  }
  Real depth = 0;
  for (const SurfacePatchContact& p : patches) depth = std::fmax(depth, p.geometry.depth);
  return depth;
}

}  // namespace

// Explicit bodies must not overlap each other, fixed bodies or planes
// (touching is fine: stacks start touching). Generated bodies are placed
// clear of everything added before them.
void WorldBuilder::check_explicit_bodies() const {
  const World& w = world_;
  if (!check_overlaps_ || explicit_.empty()) return;
  std::vector<bool> is_explicit(w.bodies.size(), false);
  for (std::uint32_t i : explicit_) is_explicit[i] = true;
  std::vector<Transform> poses(w.bodies.size());
  std::vector<Aabb> boxes(w.bodies.size());  // of bounding spheres
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    poses[i] = shape_pose(w.templates[w.bodies[i].shape], w.bodies[i]);
    const Real r = bounding_radius(given_shapes_[w.bodies[i].shape]);
    boxes[i] = {poses[i].translation - Vec3{r, r, r}, poses[i].translation + Vec3{r, r, r}};
  }
  for (std::uint32_t i : explicit_) {
    const Body& a = w.bodies[i];
    const Shape& sa = given_shapes_[a.shape];
    const Real tol = kStartOverlapRelTol * bounding_radius(sa);
    for (const PlaneWall& p : w.planes)
      if (!a.fixed && half_space_contact(sa, poses[i], p.point, p.normal).depth > tol)
        throw BuildError(labels_[i] + " starts inside a plane wall (point " + number_text(p.point.x) + ", " +
                             number_text(p.point.y) + ", " + number_text(p.point.z) + ")",
                         {i});
  }
  SweepWorkspace sweep;
  std::vector<BodyPair> pairs;
  overlapping_pairs(boxes, sweep, pairs);
  SurfaceScratch surface_scratch;
  std::vector<SurfacePatchContact> patches;
  std::vector<std::uint32_t> hosts;
  for (const auto& [i, j] : pairs) {  // i < j; reported as the explicit one of smaller index first
    if (!is_explicit[i] && !is_explicit[j]) continue;
    const Body& a = w.bodies[i];
    const Body& b = w.bodies[j];
    if (a.fixed && b.fixed) continue;
    const Shape& sa = given_shapes_[a.shape];
    const Shape& sb = given_shapes_[b.shape];
    const Real tol = kStartOverlapRelTol * bounding_radius(is_explicit[i] ? sa : sb);
    const ShapeTemplate &ta = w.templates[a.shape], &tb = w.templates[b.shape];
    Real depth = 0;
    // Part by part (a compound's hull is not its solid), surfaces by their
    // patches (hooked rings' hulls overlap).
    if (holds_surface(ta) || holds_surface(tb) || !ta.parts.empty() || !tb.parts.empty()) {
      const std::size_t a_parts = std::max<std::size_t>(ta.parts.size(), 1), b_parts = std::max<std::size_t>(tb.parts.size(), 1);
      for (std::uint32_t pa = 0; pa < a_parts; ++pa)
        for (std::uint32_t pb = 0; pb < b_parts; ++pb)
          depth = std::fmax(depth, start_overlap(w.templates, a, pa, b, pb, surface_scratch, patches, hosts));
    } else {
      const PenetrationResult pr = penetration(sa, poses[i], sb, poses[j]);
      if (pr.intersect) depth = pr.depth;
    }
    if (depth > tol) {
      const std::uint32_t first = is_explicit[i] ? i : j, second = first == i ? j : i;
      if (std::isinf(depth))
        throw BuildError(labels_[first] + " and " + labels_[second] + " start one wholly inside the other",
                         {first, second});
      throw BuildError(labels_[first] + " overlaps " + labels_[second] + " by " + number_text(depth) +
                           " m at the start",
                       {first, second});
    }
  }
}

// Every shape gets what the contact model needs, moving or fixed: the volume
// law clips solid polytopes, so every other shape becomes the inscribed
// polytope of a tessellation (its mass properties stay those of the shape);
// shapes without volume cannot take part. The penetration laws take every shape.
void WorldBuilder::prepare_shapes() {
  if (settings_.model != ContactModel::Volume) return;
  std::vector<std::size_t> user(world_.templates.size(), 0);  // a body of each template, for messages
  for (std::size_t i = world_.bodies.size(); i-- > 0;) user[world_.bodies[i].shape] = i;
  for (std::size_t t = prepared_templates_; t < world_.templates.size(); ++t) {
    const std::string& who = labels_.empty() ? std::string("a body") : labels_[user[t]];
    if (world_.templates[t].surface_grain) continue;  // its hull only bounds it
    if (world_.templates[t].parts.empty()) {
      prepare_for_volume_law(world_.templates[t].shape, world_.templates[t].given, who, user[t]);
      make_hull_surface(world_.templates[t].shape);
    } else {  // the hull stays: it only bounds the parts
      for (TemplatePart& part : world_.templates[t].parts)
        if (!part.surface_grain) prepare_for_volume_law(part.shape, part.given, who, user[t]), make_hull_surface(part.shape);
    }
  }
}

// In a world with surface grains every other template, and every part of a
// compound, gets the closed surface their contacts take: a solid
// polytope's hull triangles, a curved shape's inscribed tessellation.
// Shapes without volume get none (their contacts with surface grains stop
// the run as unsupported pairs), nor do a mesh wall's triangles under the
// penetration laws (the margin model meets the grains' triangles).
void WorldBuilder::prepare_surfaces() {
  std::vector<ShapeTemplate>& templates = world_.templates;
  if (std::none_of(templates.begin(), templates.end(), [](const ShapeTemplate& t) { return holds_surface(t); })) return;
  constexpr std::size_t kNoBody = ~std::size_t{0};  // an inflow's template
  std::vector<std::size_t> user(templates.size(), kNoBody);
  for (std::size_t i = world_.bodies.size(); i-- > 0;) user[world_.bodies[i].shape] = i;
  for (std::size_t k = 0; k < templates.size(); ++k) {
    ShapeTemplate& t = templates[k];
    if (t.surface || t.shell) continue;  // a shell meets surfaces by its own triangles
    const std::string who = user[k] == kNoBody ? "an inflow's shape"
                            : labels_.empty()   ? std::string("a body")
                                                : labels_[user[k]];
    const std::vector<std::uint32_t> at =
        user[k] == kNoBody ? std::vector<std::uint32_t>{} : std::vector<std::uint32_t>{static_cast<std::uint32_t>(user[k])};
    const auto boundary = [&](const Shape& s) {
      try {
        return boundary_surface(s, settings_.tessellation);
      } catch (const SurfaceError& e) {
        throw BuildError(who + ": its boundary cannot meet surface grains: " + e.what(), at);
      }
    };
    if (!t.parts.empty()) {
      for (TemplatePart& part : t.parts)
        if (!part.surface && !without_volume(part.shape)) part.surface = boundary(part.shape);
    } else if (!without_volume(t.shape) && !margin_piece(t)) {  // a mesh wall's piece meets them by its margin
      t.surface = boundary(t.shape);
    }
  }
}

// Under the volume law: a solid polytope as it is, a curved shape as its
// inscribed polytope; a shape without volume is refused.
void WorldBuilder::prepare_for_volume_law(Shape& s, std::optional<Shape>& given, const std::string& who,
                                          std::size_t user) const {
  if (solid_polytope(s)) return;
  if (without_volume(s))
    throw BuildError(who + ": a shape without volume cannot take part in the volume law (give it a margin or "
                           "thickness, or use model \"hertz\" or \"linear\")",
                     {static_cast<std::uint32_t>(user)});
  Tessellation tess = tessellate(s, settings_.tessellation);
  if (!solid_polytope(Shape{tess.polytope}))
    throw BuildError(who + ": the tessellation of this shape for the volume law is flat");
  given = s;
  s = Shape{tess.polytope};
}

// A periodic cell must hold every body with room to spare: a pair may meet
// through one image only. Moving bodies start inside it. (What the cell and
// its control must be alone: check_cell, in the constructor.)
void WorldBuilder::check_periodic_cell() {
  const PeriodicCell& cell = settings_.periodic;
  const CellControl& control = settings_.cell_control;
  const char* names[3] = {"x", "y", "z"};
  if (!continued_) world_.cell = cell, world_.cell_rate = {}, world_.cell_stress = {};
  if (!cell.active()) return;
  for (int a = 0; a < 3; ++a) {
    if (!cell.axes[a]) continue;
    const Real need = shortest_period(world_), length = cell_width(world_.cell, a);
    if (!(length > need))
      throw BuildError(std::string("the periodic cell is ") + number_text(length) + " m wide across " +
                       names[a] + ": it must exceed four times the largest body's reach (" + number_text(need) + " m)");
  }
  // A fixed body (a wall piece) about as long as the period could meet a
  // body directly and through its image at once; a pair keeps one image, so
  // the contact would jump between the two. Refuse it: such a wall must be
  // cut along the periodic axis (a mesh with more segments there).
  const Real two_reaches = shortest_period(world_) / 2;
  for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
    const Body& b = world_.bodies[i];
    if (!b.fixed) continue;
    const Aabb box = aabb(given_shapes_[b.shape], shape_pose(world_.templates[b.shape], b));
    for (int a = 0; a < 3; ++a) {
      const Real period = world_.cell.hi[a] - world_.cell.lo[a], extent = box.hi[a] - box.lo[a];
      if (cell.axes[a] && extent > period - two_reaches)
        throw BuildError(labels_[i] + " spans " + number_text(extent) + " m along the periodic axis " + names[a] +
                             ", more than the period less two of the largest body's reach (" +
                             number_text(period - two_reaches) +
                             " m): a body could touch it directly and through its image at once. Cut it along " +
                             names[a] + " (a mesh with more segments there)",
                         {static_cast<std::uint32_t>(i)});
    }
  }
  world_.settings.periodic = cell;
  world_.settings.cell_control = control;
  const Makeup makeup{world_.templates, world_.materials};
  wrap_bodies(world_.cell, world_.cell_rate, world_.search.boxes, {world_.bodies, &makeup, nullptr, &world_.wall_work});
}

// An inflow whose region lies wholly beyond a plane wall that never moves,
// or inside a fixed body that never moves, could never insert a body: the
// run would say nothing and insert nothing.
void WorldBuilder::check_inflow_regions() const {
  for (std::size_t k = 0; k < world_.inflows.size(); ++k) {
    const Inflow& f = world_.inflows[k];
    const std::string& label = k < inflow_labels_.size() ? inflow_labels_[k] : "an inflow";
    Vec3 corners[8];
    for (int c = 0; c < 8; ++c)
      corners[c] = {c & 1 ? f.hi.x : f.lo.x, c & 2 ? f.hi.y : f.lo.y, c & 4 ? f.hi.z : f.lo.z};
    for (const PlaneWall& p : world_.planes) {
      if (p.motion != 0) continue;
      bool beyond = true;
      for (const Vec3& c : corners) beyond = beyond && dot(c - p.point, p.normal) < 0;
      if (beyond)
        throw BuildError(label + ": its region lies wholly beyond the plane wall with id " + std::to_string(p.id) +
                         ": no body could ever be inserted there");
    }
    for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
      const Body& b = world_.bodies[i];
      // (A compound's given shape is its hull: a hopper of parts holds room
      // inside. A surface grain's solid is its surface's: a bowl's hollow is
      // free. A shell has no inside.)
      const ShapeTemplate& t = world_.templates[b.shape];
      if (!b.fixed || b.motion != 0 || !t.parts.empty() || t.shell) continue;
      const Shape& shape = given_shapes_[b.shape];
      const Transform pose = shape_pose(t, b);
      bool inside = true;
      for (const Vec3& c : corners)
        inside = inside && (t.surface_grain ? winding_number(t.surface->vertices, t.surface->triangles,
                                                             apply_inverse(pose, c)) > 0.5
                                            : intersect(Shape{Point{}}, Transform::from(c, Quat{}), shape, pose));
      if (inside)
        throw BuildError(label + ": its region lies wholly inside " + labels_[i] +
                         ": no body could ever be inserted there", {static_cast<std::uint32_t>(i)});
    }
  }
}

World WorldBuilder::build() {
  if (world_.bodies.empty() && world_.planes.empty() && world_.inflows.empty()) throw BuildError("the world is empty");
  place_driven(world_);  // where their motions have them now, for the checks
  check_periodic_cell();
  if (!world_.bonds.empty() && world_.cell.active())
    throw BuildError("bonded assemblies cannot be in a periodic world yet (their bonds do not wrap)");
  prepare_shapes();
  prepare_surfaces();
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
  groups_ = 0;
  prepared_templates_ = 0;
  continued_ = false;
  return out;
}

}  // namespace gjkdem::dem
