#pragma once
// What a DEM world is made of: shape templates shared by many bodies, bodies,
// and plane walls. Bodies are plain, fixed-size data (no pointers, no
// containers), so that an array of them can be viewed from NumPy or sent
// between MPI ranks as it is. What a contact remembers between
// steps lives in the world's pair store (pair_state.hpp), not in the bodies.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>
#include <type_traits>

#include "gjkdem/dem/body_channel_rows.hpp"
#include "gjkdem/dem/material.hpp"
#include "gjkdem/shape/mass_properties.hpp"
#include "gjkdem/shape/shape.hpp"
#include "gjkdem/shape/shell.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem::dem {

/// A part of a compound template (a non-convex grain as a rigid union of
/// parts): contacts are found part against part. A part is convex, or a
/// closed surface met by its patches as a surface grain is (surface_grain).
struct TemplatePart {
  Shape shape;                   ///< as the contact model sees it, in the part's frame (a surface part: its hull, a bound)
  Transform pose;                ///< part frame -> the template's shape frame
  Real radius = 0;               ///< of a sphere about the part frame's origin holding the part
  Real curvature_radius = 0;     ///< for the Hertz law: of the part alone (as for a template)
  Real volume = 0;               ///< of the part (0 for fixed pieces)
  std::optional<Shape> given{};  ///< the part as given, where `shape` is its tessellation (volume law)
  /// Its boundary as surface grains meet it (as ShapeTemplate::surface), in
  /// the part's frame; null in a world without surface grains. A surface
  /// part's own surface.
  std::shared_ptr<const Surface> surface;
  /// The part is a closed surface, convex or not (as ShapeTemplate::surface_grain).
  bool surface_grain = false;
};

/// A closed surface placed in a compound's frame: a part met by its patches.
struct PlacedSurface {
  std::shared_ptr<const Surface> surface;
  Transform pose;  ///< surface frame -> the compound's frame
};

/// A shape and its mass properties per unit density, computed once and
/// shared by every body made from it.
struct ShapeTemplate {
  Shape shape;                   ///< in its own local frame, as the world's contact model sees it
  /// The shape as given, where `shape` is its inscribed tessellation (a
  /// curved shape under the volume law; the mass properties are the given
  /// shape's): what an exported scene writes.
  std::optional<Shape> given{};
  MassProperties unit_mass;      ///< per unit density, in the shape's frame (zero for walls)
  PrincipalAxes principal;       ///< of unit_mass.inertia
  /// Radius of curvature for the Hertz law (m): exact for spheres and capsules;
  /// for other shapes the radius of the sphere of equal volume (documented
  /// approximation for polyhedra). Infinite for wall pieces.
  Real curvature_radius = 0;
  /// Largest distance of the shape's points from the centre of mass (m):
  /// how far a turn can move them (box skins, generators).
  Real reach = 0;
  /// A compound's convex parts; empty for one convex `shape`. For a compound
  /// `shape` is the hull of its parts, used only where a bound will do
  /// (placing bodies, overlap checks).
  std::vector<TemplatePart> parts;
  /// A surface grain (a closed triangle surface, convex or not): its contacts
  /// are the patches of the overlap of surfaces (surface_contact.hpp) and
  /// `shape` is its convex hull, used only where a bound will do.
  bool surface_grain = false;
  /// The closed surface contacts with surface grains take: a surface grain's
  /// own, or a convex template's boundary (its polytope, or its inscribed
  /// tessellation when curved) in a world with surface grains; null otherwise.
  /// In the shape's frame.
  std::shared_ptr<const Surface> surface;
  /// A thin shell (shape/shell.hpp): its triangles with their margin meet
  /// surfaces by the margin model and planes by their corners; `shape` is
  /// its hull grown by the margin, used only where a bound will do. In the
  /// shape's frame; null for other shapes.
  std::shared_ptr<const Shell> shell;
  /// A mesh wall piece's triangle (the middle of its thickness), in the
  /// shape's frame: a moving body whose centre crosses it during a step has
  /// gone through the wall (StepStatus::ThroughWall). Unset for other shapes.
  std::optional<Triangle> wall_face;
  /// A fragment's: how many splits made it from a template of the builder
  /// (0: the builder's own). Fragments' templates are added during a run,
  /// after the builder's (breakage.hpp).
  std::uint32_t generation = 0;
};

/// A template for a moving particle (throws std::invalid_argument for shapes
/// without volume).
ShapeTemplate make_template(const Shape& shape);

/// A big solid polytope's kept surface (hull_surface, shape/surface.hpp)
/// made now, so that no step makes it inside overlap(): the builder does
/// it for every template it prepares under the volume law, breakage for
/// each fragment. Nothing for other shapes and for small hulls.
void make_hull_surface(const Shape& shape);

/// A template for fixed pieces (a flat triangle has no volume): no mass, and
/// its principal frame is the shape's own frame.
ShapeTemplate make_wall_template(const Shape& shape);

/// A compound of convex parts and then closed surfaces (each one closed
/// shell, as a surface grain), placed in the compound's frame, moving (exact
/// mass properties of the union; throws std::invalid_argument for a part
/// without volume) or fixed (no mass). Parts must not overlap: the builder
/// checks it.
ShapeTemplate make_compound_template(std::span<const PlacedShape> parts, bool fixed,
                                     std::span<const PlacedSurface> surfaces = {});

/// A surface grain, moving (exact mass properties of its solid) or fixed (no
/// mass: a bowl, a peg).
ShapeTemplate make_surface_template(std::shared_ptr<const Surface> surface, bool fixed);

/// A thin shell, moving (mass properties of its plates) or fixed (no mass).
/// Its Hertz radius is that of the sphere of its area (a documented
/// approximation, as the sphere of equal volume is for polyhedra).
ShapeTemplate make_shell_template(std::shared_ptr<const Shell> shell, bool fixed);

/// Whether a body of template `t` meets others at `part` (0 for a body of
/// one shape) by the patches of surfaces: a surface grain, or a compound's
/// surface part.
inline bool surface_side(const ShapeTemplate& t, std::uint32_t part) noexcept {
  return t.parts.empty() ? t.surface_grain : t.parts[part].surface_grain;
}

/// The closed surface a body of template `t` meets others by at `part` (a
/// compound's: its part's); null where it has none (no volume, a shell, a
/// mesh wall's piece, a world without surfaces).
inline const std::shared_ptr<const Surface>& surface_of(const ShapeTemplate& t, std::uint32_t part) noexcept {
  return t.parts.empty() ? t.surface : t.parts[part].surface;
}

/// A mesh wall's piece under the Hertz and linear laws (a triangle with a
/// margin, which meets surfaces by margin_patches): its triangle, or null
/// for any other template.
inline const Triangle* margin_piece(const ShapeTemplate& t) noexcept {
  return t.wall_face && t.shape.margin > 0 ? std::get_if<Triangle>(&t.shape.core) : nullptr;
}

/// How a part of a body meets others (`part` 0 for a body of one shape):
/// the one fact the contacts' routes are read from (pair_route).
enum class PartKind : std::uint8_t {
  Convex,     ///< a convex shape (in a world with surfaces, met by its boundary, ShapeTemplate::surface)
  Surface,    ///< a closed surface, convex or not: a surface grain, a compound's surface part
  Shell,      ///< a thin shell: its triangles with their margin
  WallPiece,  ///< a mesh wall's piece under the penetration laws (margin_piece)
};

inline PartKind part_kind(const ShapeTemplate& t, std::uint32_t part) noexcept {
  if (t.shell) return PartKind::Shell;
  if (surface_side(t, part)) return PartKind::Surface;
  return margin_piece(t) ? PartKind::WallPiece : PartKind::Convex;
}

/// How two sides of a contact meet. Every place that meets two bodies (the
/// step's narrow phase and surface stage, the start's overlap check, the
/// placing of generated and inflowing bodies) takes its route from here.
enum class ContactRoute : std::uint8_t {
  Convex,   ///< convex shapes: GJK and the narrow phase's laws
  Patches,  ///< the patches of two closed surfaces (a convex part by its boundary), or of a surface beyond a plane
  Shell,    ///< a thin shell's triangles against the other side's surface, or a plane by their corners
  Margin,   ///< a surface's or a shell's triangles against a mesh wall's piece: the margin model
};

/// The route of parts of kinds `a` and `b` (either order gives the same).
constexpr ContactRoute pair_route(PartKind a, PartKind b) noexcept {
  const auto meshed = [](PartKind k) { return k == PartKind::Surface || k == PartKind::Shell; };
  if ((a == PartKind::WallPiece && meshed(b)) || (b == PartKind::WallPiece && meshed(a))) return ContactRoute::Margin;
  if (a == PartKind::Shell || b == PartKind::Shell) return ContactRoute::Shell;
  if (a == PartKind::Surface || b == PartKind::Surface) return ContactRoute::Patches;
  return ContactRoute::Convex;
}

/// The route of a plane wall and a part of kind `b`.
constexpr ContactRoute plane_route(PartKind b) noexcept {
  if (b == PartKind::Shell) return ContactRoute::Shell;
  return b == PartKind::Surface ? ContactRoute::Patches : ContactRoute::Convex;
}

/// Whether template `t` is a thin shell or any part of it a surface
/// (surface_side): worlds with one give every other shape a surface to be
/// met by.
bool holds_surface(const ShapeTemplate& t) noexcept;

/// A body: who it is (constant, by hand here) and what it holds (its
/// channels, one member per row of body_channel_rows.hpp, in row order:
/// position, orientation, velocity, angular_momentum, force and torque of
/// the last evaluation, applied_force, applied_torque, applied_work; each
/// row says what it is, in which unit, and who takes it).
struct Body {
  std::uint64_t id = 0;          ///< global id, stable across domains and restarts
  std::uint32_t shape = 0;       ///< index into World::templates
  std::uint32_t material = 0;    ///< index into World::materials
  std::uint32_t group = 0;       ///< > 0: a piece of a wall (contacts with one group are merged)
  std::uint16_t fixed = 0;       ///< 1: not moved by forces (walls, obstacles)
  std::uint16_t motion = 0;      ///< > 0: a fixed body moved by World::motions[motion - 1]
#define GJKDEM_BODY_MEMBER(name, Type, ...) Type name{};
#define GJKDEM_BODY_NO_MEMBER(...)
  GJKDEM_BODY_CHANNEL_ROWS(GJKDEM_BODY_MEMBER, GJKDEM_BODY_NO_MEMBER)
#undef GJKDEM_BODY_MEMBER
#undef GJKDEM_BODY_NO_MEMBER
};
static_assert(std::is_trivially_copyable_v<Body> && std::is_standard_layout_v<Body>);

/// What bodies are made of, by the indices they hold (Body::shape,
/// Body::material): the view of a world's templates and materials that the
/// stages of a step take, and the one place a body's mass is worked out.
struct Makeup {
  std::span<const ShapeTemplate> templates;
  std::span<const Material> materials;

  /// kg, of a body or of one made of template `shape` and `material`
  Real mass(std::uint32_t shape, std::uint32_t material) const noexcept {
    return materials[material].density * templates[shape].unit_mass.volume;
  }
  Real mass(const Body& b) const noexcept { return mass(b.shape, b.material); }
  /// Principal moments of inertia (kg m^2).
  Vec3 moments(const Body& b) const noexcept { return templates[b.shape].principal.moments * materials[b.material].density; }
};

/// The index of the body with this id in `bodies` (kept in increasing id
/// order, as a world keeps them), or bodies.size() when none has it.
std::size_t index_of_body(std::span<const Body> bodies, std::uint64_t id) noexcept;

/// Fixed and without a motion: its box and place never change.
inline bool is_static(const Body& b) noexcept { return b.fixed && b.motion == 0; }

/// Plane walls get ids from here up, above every body's.
inline constexpr std::uint64_t kPlaneIdBase = std::uint64_t{1} << 62;

/// An infinite plane wall: material on the side opposite to `normal`.
struct PlaneWall {
  std::uint64_t id = 0;       ///< global id, above every body's (it keys the pair store)
  Vec3 point;                 ///< now
  Vec3 normal;                ///< now; unit, pointing out of the wall
  std::uint32_t material = 0;
  std::uint32_t motion = 0;   ///< > 0: moved by World::motions[motion - 1]
  Vec3 given_point, given_normal;  ///< as built, before any motion
};

/// A fixed body with a motion: where it was given (its motion moves it from there).
struct DrivenBody {
  std::uint32_t body = 0;     ///< index into World::bodies
  Vec3 position;              ///< centre of mass as given
  Quat orientation;           ///< as given
};

/// Pose of a body's shape: its principal frame placed in the world, composed
/// with the shape's frame relative to its principal frame.
Transform shape_pose(const ShapeTemplate& shape, const Body& body) noexcept;

/// Part `part` of a body's template (the template itself when it has no
/// parts) and its pose in the world.
struct PartPose {
  const Shape* shape;
  Transform pose;
};
PartPose part_pose(const ShapeTemplate& shape, const Body& body, std::uint32_t part) noexcept;

/// The orientation of the frame the shape was given in (shape frame -> world).
Quat shape_orientation(const ShapeTemplate& shape, const Body& body) noexcept;

}  // namespace gjkdem::dem
