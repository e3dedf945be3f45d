#pragma once
// Building a world: materials, bodies, walls and generated beds go in, a
// checked World comes out. The builder gives every body and wall its global
// id, prepares each shape for the contact model (under the volume law every
// curved shape, moving or fixed, is clipped as an inscribed polytope), checks
// that explicit bodies do not start inside each other or a wall, refuses what
// the engine cannot do (a message names the body or wall, by the label it was
// given), and fills the table of material pairs. Scene files (io/scene.hpp),
// tests, benchmarks and Python all build worlds through it.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/dem/build_error.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

/// The range of WorldSettings::tessellation (support directions).
inline constexpr int kMinTessellation = 8;
inline constexpr int kMaxTessellation = 100000;
/// The most threads a world's step may ask for (0: every core).
inline constexpr int kMaxThreads = 4096;
/// The most bodies one region fill may place (about 0.5 KB each with their
/// contacts), as the most an inflow may insert (kMaxInflowBodies).
inline constexpr std::uint64_t kMaxFillCount = 10'000'000;

/// The rules of what a world is made of, each written once: the builder
/// applies them, and the scene reader and the Python module call them to
/// refuse a field where it was written. Each throws BuildError naming the
/// field by its key in the scene's table.
/// A material's values (keys: density, youngs_modulus, poisson_ratio,
/// restitution, friction, rolling_friction, rolling_damping).
void check_material(const Material& material);
/// The contact law's settings (keys of [contact]: linear_stiffness,
/// volume_stiffness, tessellation, box_skin).
void check_contact_settings(const WorldSettings& settings);
/// A periodic cell and how it deforms (keys of [simulation.periodic]: x, y,
/// z, strain_rate.C, stress.C, max_strain_rate, tilt). The widths against
/// the bodies' reach are checked when the world is built.
void check_cell(const PeriodicCell& cell, const CellControl& control);
/// Every setting: the contact settings, the cell, gravity (finite) and
/// threads (keys of [simulation]).
void check_settings(const WorldSettings& settings);
/// A region fill's count (key: count): 1 to kMaxFillCount. A reader may
/// apply it before it draws the fill's shapes.
void check_fill_count(std::int64_t count);

/// The most bodies a world may come to hold, with what its inflows insert
/// and its grains' fragments (memory is reserved for all of them, untouched
/// until used).
inline constexpr std::uint64_t kMostBodies = std::uint64_t{1} << 24;

/// A shape as an author gives it: its frame placed in the body's frame
/// (identity: centred on the body's origin, unrotated).
struct BodyShape {
  Shape shape{};
  Transform pose{};
  /// Non-empty: a compound (a non-convex grain) of these convex parts, placed
  /// in the shape's frame; `shape` is then ignored. Parts may touch, not
  /// overlap (checked); contacts are found part against part.
  std::vector<PlacedShape> parts{};
  /// A compound's closed surfaces (each checked by make_surface, one
  /// shell), parts after `parts` (part indices count them after those),
  /// each met by its patches as a surface grain is.
  std::vector<PlacedSurface> surface_parts{};
  /// Non-null: a thin shell (shape/shell.hpp: make_shell checked it), in the
  /// shape's frame, under the Hertz and linear laws; `shape` is then
  /// ignored. A shell, a surface and a compound's parts exclude each other
  /// (a shape giving two is refused).
  std::shared_ptr<const Shell> shell{};
  /// Non-null: a surface grain of this closed surface (shape/surface.hpp:
  /// make_surface checked it), in the shape's frame; `shape` is then ignored.
  std::shared_ptr<const Surface> surface{};
};

/// Whether the shape is a compound (of convex parts, surfaces or both).
inline bool is_compound(const BodyShape& s) noexcept { return !s.parts.empty() || !s.surface_parts.empty(); }

struct BodyDef {
  BodyShape shape{};            ///< ignored when `shared_shape` is set
  /// >= 0: the shape of add_shape with this index, shared with other bodies
  /// (one template, one copy of its mass properties).
  std::int64_t shared_shape = -1;
  std::uint32_t material = 0;   ///< from add_material
  Vec3 position{};              ///< of the body's frame (the author's), world (m)
  Quat rotation{};              ///< of the body's frame, world
  Vec3 velocity{};              ///< of the centre of mass (m/s)
  Vec3 angular_velocity{};      ///< world (rad/s)
  /// Values of its channels given as they are (kChannelGiven rows of
  /// body_channel_rows.hpp; each channel once, finite): the applied loads
  /// (constant unless a listener changes them; any nonzero turns
  /// World::applied_loads on; free bodies only), a feature's own.
  std::vector<GivenChannel> given{};
  bool fixed = false;           ///< not moved by forces; must have no velocity
  std::uint32_t motion = 0;     ///< > 0: a fixed body moved by this motion (add_motion)
  std::string label{};          ///< names the body in messages, e.g. "body[2]"; empty: its name, else "body N"
  /// The user's name for it: traced (World::names, trace.csv). Empty: none;
  /// else unique, without commas, quotes or control characters (a CSV field).
  std::string name{};
};

/// A bonded assembly (bonds.hpp, docs/breakage.md): a convex solid cut into
/// `pieces` Voronoi cells (shape/voronoi.hpp), each a moving body of its
/// own, every two that share a face glued there by a bond of the material's
/// glue. The cells' sites are drawn uniformly inside the solid from `seed`,
/// then moved `relaxations` times to their cells' centroids (Lloyd's
/// iteration: pieces of more even size).
struct BondedDef {
  /// The solid: a polytope or box, or a curved or rounded shape taken as
  /// its inscribed tessellation (WorldSettings::tessellation directions);
  /// not a compound or a surface.
  BodyShape shape{};
  std::uint32_t pieces = 0;     ///< 2 to kMaxBondedPieces
  std::uint64_t seed = 1;       ///< of the sites
  int relaxations = 3;          ///< Lloyd iterations, 0 to 100
  std::uint32_t material = 0;   ///< from add_material; must have a glue (Glue::tensile_strength > 0)
  Vec3 position{};              ///< of the solid's frame, world (m)
  Quat rotation{};              ///< of the solid's frame, world
  Vec3 velocity{};              ///< of the whole's centre of mass (m/s)
  Vec3 angular_velocity{};      ///< of the whole, world (rad/s)
  std::string label{};          ///< names it in messages (its pieces as label.piece[k]), e.g. "body[2]"
};

/// The most pieces of one bonded assembly.
inline constexpr std::uint32_t kMaxBondedPieces = 10000;

/// A cylindrical container: a mesh wall of `segments` flat sides (and a
/// floor and roof when capped) placed so that its inner faces lie at
/// `radius` from the axis and on the base and top planes: the bodies inside
/// have the whole of [0, height] x radius (up to the sides' flats).
struct CylinderWall {
  Vec3 base{};               ///< centre of the bottom (m)
  Vec3 axis{0, 0, 1};        ///< towards the top (made unit)
  Real radius = 0;           ///< inner radius (m)
  Real height = 0;           ///< m
  bool bottom = true;        ///< a floor
  bool top = false;          ///< a roof
  int segments = 48;         ///< flat sides, 8 to 4096 (48: the flats reach 99.8% of the radius)
  Real thickness = 0;        ///< of the pieces (0: 2% of the radius)
};

/// The rule of CylinderWall::segments: "" when `segments` keeps it, else
/// what it must be.
std::string cylinder_segments_problem(std::int64_t segments);

/// The thickness of its pieces (CylinderWall::thickness, or its default).
Real cylinder_wall_thickness(const CylinderWall& wall);

/// The triangles of a CylinderWall (world coordinates), as add_cylinder_walls
/// makes it. Throws BuildError for a bad one (naming `label`).
void cylinder_wall_mesh(const CylinderWall& wall, const std::string& label, std::vector<Vec3>& vertices,
                        std::vector<std::array<std::uint32_t, 3>>& triangles);

/// Bodies placed without overlap in the box [lo, hi] (or in `round`), in
/// cells one bounding diameter wide filled layer by layer from the bottom,
/// each with a random orientation and offset; cells that touch a body
/// already added, lie outside a plane wall or reach out of `round` are
/// skipped.
struct RegionFill {
  std::vector<BodyShape> variants;  ///< each body takes one at random (shared templates)
  std::vector<Real> weights;        ///< number probabilities of the variants (empty: equal)
  std::size_t count = 0;
  Vec3 lo, hi;                      ///< the box (ignored with `round`: its bounding box is filled)
  std::optional<RoundRegion> round{}; ///< a cylinder or ball instead of the box
  std::uint32_t material = 0;
  Vec3 velocity;
  bool fixed = false;               ///< fixed bodies (a rough floor, an obstacle field): no velocity
  std::string label;                ///< e.g. "generator[0]"
  /// > 0: each body placed is a bonded assembly (BondedDef) of its shape
  /// cut into this many pieces, the sites of the k-th drawn from
  /// derived_seed(pieces_seed, k); moving bodies only.
  std::uint32_t pieces = 0;
  std::uint64_t pieces_seed = 1;
  int relaxations = 3;              ///< of each assembly's sites (BondedDef::relaxations)
};

/// The seed of the k-th stream drawn from `seed`: the sites of the k-th
/// bonded assembly a region fill places, a scene's k-th generator and
/// inflow (src/io/scene_reader/bodies.cpp). One rule, so that streams never share a seed.
inline std::uint64_t derived_seed(std::uint64_t seed, std::uint64_t k) noexcept { return seed * 1000003 + k; }

/// A region inserting bodies during a run (inflow.hpp): a rate in bodies or
/// kilograms per second (one of them > 0), from `start` until `stop` or
/// `count` bodies (at least one of the two finite).
struct InflowDef {
  std::vector<BodyShape> variants;  ///< shapes (their pose is ignored: bodies are turned at random)
  std::vector<Real> weights;        ///< number probabilities of the variants (empty: equal)
  Vec3 lo, hi;                      ///< where centres of mass go
  std::optional<RoundRegion> round{}; ///< a cylinder (height 0: a disc) or ball instead of the box
  std::uint32_t material = 0;
  Vec3 velocity;
  Real rate = 0;                    ///< bodies/s
  Real mass_rate = 0;               ///< kg/s
  Real start = 0;
  Real stop = std::numeric_limits<Real>::infinity();
  std::uint64_t count = 0;          ///< 0: no limit but `stop`
  std::uint64_t seed = 1;
  std::string label;                ///< e.g. "inflow[0]"
};

/// What a long build is starting on (WorldBuilder::set_progress).
using BuildProgress = std::function<void(const std::string&)>;

class WorldBuilder {
 public:
  /// Checks the settings (check_settings).
  explicit WorldBuilder(const WorldSettings& settings = {});

  /// Continues a world already built (and maybe run): bodies added now join
  /// it with the next ids; its bodies keep their state and contacts. New
  /// explicit bodies are checked against everything; the world's own bodies
  /// are not checked again (a settled bed overlaps).
  explicit WorldBuilder(World world);

  const WorldSettings& settings() const noexcept { return settings_; }

  /// Checks the values (check_material) and that the name is new.
  std::uint32_t add_material(const Material& material);
  std::optional<std::uint32_t> find_material(std::string_view name) const;

  /// Adds one body; returns its index (and id).
  std::uint32_t add_body(const BodyDef& body);

  /// A shape many moving bodies share (BodyDef::shared_shape), or with
  /// `fixed` many fixed ones (a fixed body's template has no mass); returns
  /// its index.
  std::uint32_t add_shape(const BodyShape& shape, const std::string& label, bool fixed = false);

  /// Explicit bodies may start overlapping each other and the walls: a state
  /// saved from a settled bed, or a stack started at its resting overlaps.
  /// (By default such a start is refused, naming the two bodies.)
  void accept_initial_overlaps() noexcept { check_overlaps_ = false; }

  /// Told what the builder starts on where that can take long (cutting a
  /// bonded assembly, filling a region, checking the start), so that a long
  /// build can say where it is: one line each, as "LABEL: cutting it into
  /// 2000 pieces".
  void set_progress(BuildProgress progress) { progress_ = std::move(progress); }

  /// A prescribed motion (motion.hpp) for walls and fixed bodies; returns
  /// its number (> 0) for BodyDef::motion and the walls' `motion`.
  std::uint32_t add_motion(const PrescribedMotion& motion, const std::string& label);

  /// An infinite plane; `normal` need not be unit but must have a direction.
  /// Walls take an optional motion (add_motion) that moves them as one piece.
  void add_plane(const Vec3& point, const Vec3& normal, std::uint32_t material, const std::string& label,
                 std::uint32_t motion = 0);

  /// A box container [lo, hi]: one fixed slab of the given thickness per side
  /// outside it (no roof when open_top), the floor and roof spanning the side
  /// slabs so the corners are closed.
  void add_box_walls(const Vec3& lo, const Vec3& hi, bool open_top, Real thickness, std::uint32_t material,
                     const std::string& label, std::uint32_t motion = 0);

  /// A triangle mesh (world coordinates) as one fixed piece per triangle:
  /// the seed's triangle with a margin of thickness / 2 under the penetration
  /// laws, a prism of that thickness under the volume law (the pieces of a
  /// flat region tile it and their overlap volumes add up exactly).
  void add_mesh_walls(std::span<const Vec3> vertices, std::span<const std::array<std::uint32_t, 3>> triangles,
                      Real thickness, std::uint32_t material, const std::string& label, std::uint32_t motion = 0);

  /// A cylindrical container (CylinderWall): its mesh as add_mesh_walls takes it.
  void add_cylinder_walls(const CylinderWall& wall, std::uint32_t material, const std::string& label,
                          std::uint32_t motion = 0);

  /// A bonded assembly (BondedDef): its pieces as bodies, with the next ids,
  /// and their bonds. Returns the pieces' indices.
  std::vector<std::uint32_t> add_bonded(const BondedDef& bonded);

  /// An inflow (InflowDef); returns its index. The world reserves room for
  /// every body its inflows can insert, so views of its bodies stay valid.
  std::uint32_t add_inflow(const InflowDef& inflow);

  /// Fills a region (RegionFill); draws from `rng`. Throws BuildError when
  /// the region holds fewer than `count` bodies. Returns the bodies' indices.
  std::vector<std::uint32_t> fill_region(const RegionFill& fill, std::mt19937_64& rng);

  std::size_t body_count() const noexcept { return world_.bodies.size(); }
  /// Where body `index` (as add_body and fill_region return it) is now: its centre of mass.
  Vec3 position_of(std::uint32_t index) const { return world_.bodies.at(index).position; }
  std::size_t moving_count() const noexcept;

  /// Checks and prepares everything; the builder is empty afterwards.
  World build();

 private:
  std::uint32_t add_template(const BodyShape& shape, bool fixed, const std::string& label);
  void check_compound(const BodyShape& shape, const std::string& label) const;
  std::uint64_t next_id() const noexcept;
  void place(Body& body, const BodyShape& shape, const Vec3& position, const Quat& rotation, const Vec3& velocity,
             const Vec3& spin) const;
  std::uint32_t add_fixed_piece(const Shape& shape, const Vec3& position, std::uint32_t material, std::uint32_t group,
                                const std::string& label, std::uint32_t motion);
  void check_material(std::uint32_t material, const std::string& label) const;
  void check_motion_number(std::uint32_t motion, const std::string& label) const;
  void drive(std::uint32_t body, std::uint32_t motion);
  void check_explicit_bodies() const;
  void prepare_shapes();
  void prepare_surfaces();
  void check_periodic_cell();
  void check_inflow_regions() const;
  void prepare_for_volume_law(Shape& shape, std::optional<Shape>& given, const std::string& who,
                              std::size_t user) const;

  WorldSettings settings_;
  World world_;
  std::vector<std::string> labels_;     ///< per body
  std::unordered_set<std::string> names_;  ///< World::names' names, for the uniqueness rule
  std::vector<std::string> inflow_labels_;  ///< per inflow
  std::vector<Shape> given_shapes_;     ///< per template, as given (before preparation)
  std::vector<std::uint32_t> explicit_; ///< bodies from add_body
  /// Each bonded assembly's pieces, [first, end) of the bodies: the cells of
  /// one solid tile it, so the start check skips their pairs.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> assemblies_;
  std::size_t prepared_templates_ = 0;  ///< templates of a continued world, prepared already
  struct SharedShape {
    std::uint32_t index;  ///< template
    Transform pose;       ///< of the shape in its body's frame
    bool fixed;
  };
  std::vector<SharedShape> shared_;  ///< add_shape
  bool check_overlaps_ = true;
  BuildProgress progress_;
  void say(const std::string& what) const {
    if (progress_) progress_(what);
  }
  std::uint32_t groups_ = 0;
  bool continued_ = false;              ///< made from a world: its periodic cell is state to keep
};

}  // namespace gjkdem::dem
