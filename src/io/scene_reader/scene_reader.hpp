#pragma once
// The scene reader (docs/scenes.md): a scene file's tables, read with
// toml++, into a WorldBuilder's calls and the resolved echo (made by the
// reads: toml_reader.hpp). Every key is
// checked: unknown keys, wrong types and out-of-range values are refused
// with the key's line, before anything runs. One class, its methods by job:
// scene_reader.cpp the whole and its settings (simulation, output, contact,
// materials), shapes.cpp shapes, meshes and the [shapes] table, bodies.cpp
// bodies, generators, inflows and their regions and mixes, walls.cpp walls
// and motions.
#include "gjkdem/io/scene.hpp"
#include "gjkdem/io/run_output.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/mesh.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "gjkdem/shape/aabb.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "gjkdem/shape/shell.hpp"
#include "gjkdem/shape/surface.hpp"
#include "gjkdem/tolerances.hpp"
#include "container_check.hpp"
#include "size_mix.hpp"
#include "toml_reader.hpp"

namespace gjkdem::io::detail {

// Inflows draw their random streams (dem::derived_seed) from this number on,
// past any generator's.
inline constexpr std::uint64_t kInflowStreams = 500009;

// Limits of generators, checked before anything is drawn: each body costs
// about 0.5 KB with its contacts, each variant's vertex 24 bytes and more.
inline constexpr std::int64_t kMaxVariants = 100'000;
inline constexpr std::int64_t kMaxGeneratorVertices = 10'000'000;

// An integer of the scene as an int for a builder's rule: beyond int's range
// it becomes the nearest end, which every such rule refuses.
inline int clamped_int(std::int64_t v) {
  return static_cast<int>(std::clamp<std::int64_t>(v, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

// A shape read from a SHAPE table, in its body's frame.
using ShapeSpec = dem::BodyShape;

class SceneReader {
 public:
  SceneReader(const std::string& source, std::filesystem::path base, dem::BuildProgress progress = {})
      : source_(source), base_(std::move(base)), progress_(std::move(progress)) {}

  // One SHAPE table outside a scene (read_scene_shape): a random polyhedron
  // drawn once from `seed` (a size range drawn in too), any other type as
  // a body's shape.
  SceneShape one_shape(const toml::table& t, const std::string& where, std::uint64_t seed);
  Scene build(const toml::table& root);

 private:
  template <class F>
  void for_each_table(TableReader& top, const std::string& key, F&& read) {
    const toml::node* n = top.find(key);
    if (!n) return;
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) top.fail(key, "must be an array of tables: write [[" + key + "]]");
    int index = 0;
    for (const toml::node& e : *a) {
      TableReader r(*e.as_table(), key + "[" + std::to_string(index++) + "]", top, key, TableReader::Echo::Appended);
      read(r);
      r.finish();
    }
  }

  // Runs a builder call; what it refuses becomes a SceneError at `where`'s line.
  template <class F>
  auto building(const toml::node& where, F&& call) {
    try {
      return call();
    } catch (const dem::BuildError& e) {
      throw SceneError(std::string(e.what()) + line_of(where));
    }
  }
  // The same for a builder's rule of a field this table holds (BuildError's
  // key): named at the field's line, as the table's own checks name it.
  template <class F>
  auto building(TableReader& r, F&& call) {
    try {
      return call();
    } catch (const dem::BuildError& e) {
      if (!e.key.empty()) r.fail(e.key, e.rule);
      throw SceneError(std::string(e.what()) + line_of(r.table_node()));
    }
  }

  // The whole and its settings (scene_reader.cpp).
  const toml::table* sub_table(TableReader& top, const std::string& key);
  void read_simulation(TableReader& top);
  void read_output(TableReader& top);
  void read_contact(TableReader& top);
  void read_material(TableReader& r);
  std::uint32_t material_of(TableReader& r);

  // Shapes, meshes and the [shapes] table (shapes.cpp).
  std::filesystem::path file_of(TableReader& r, const std::string& key);

  // A mesh's vertices scaled, then placed; a scale that puts them beyond
  // kMaxCoordinate, or shrinks the mesh below what double precision
  // resolves, is refused by its key (not reported later as a flat mesh).
  void scale_mesh(TableReader& r, TriangleMesh& mesh, Real scale, const Transform& place = Transform::identity());
  Polytope mesh_hull(TableReader& r, Real scale);

  // A closed mesh as it is (a surface grain), checked by make_surface; one
  // surface per file and scale, shared by every body that names it.
  std::shared_ptr<const Surface> mesh_surface(TableReader& r, Real scale);

  // A surface given in the scene: `vertices` [[x, y, z], ...] and
  // `triangles` [[i, j, k], ...] (0-based, counter-clockwise seen from
  // outside), as the query format's mesh; scaled by `scale`.
  std::shared_ptr<const Surface> inline_surface(TableReader& r, Real scale);

  // Triangles given in the scene: `vertices` [[x, y, z], ...] scaled by
  // `scale` and `triangles` [[i, j, k], ...] (0-based indices).
  TriangleMesh inline_triangles(TableReader& r, Real scale, const std::string& what);

  // A thin shell: the triangles of a mesh `file` (scaled) or given in the
  // scene, open or closed, with a `thickness` (m, not scaled), checked by
  // make_shell.
  std::shared_ptr<const Shell> mesh_shell(TableReader& r, Real scale);

  // A compound's parts: SHAPE tables (`parts`; a surface goes to the
  // surface parts) or the objects of a mesh file (`file`, `scale`), each the
  // convex hull of its triangles.
  void read_compound_parts(TableReader& r, const toml::table& t, ShapeSpec& s);

  // A SHAPE table: the types of query-format.md, plus platonic and mesh, and
  // for generators random_polyhedron (drawn per variant by the caller).
  ShapeSpec read_shape(TableReader& owner, const std::string& key);

  // A shape of the [shapes] table, named by a string where a SHAPE goes:
  // the moving bodies that name it share one template.
  struct NamedShape {
    const toml::table* table = nullptr;  // as written (generators and inflows read it so)
    std::optional<ShapeSpec> spec;       // as read (none for a random_polyhedron)
    std::int64_t shared = -1;            // the builder's shared shape, once a moving body took it
    std::int64_t shared_fixed = -1;      // ... once a fixed body took it
  };

  // The SHAPE table at `key`: written there, or named there.
  const toml::table* shape_table_at(TableReader& owner, const std::string& key);
  NamedShape* named_shape(TableReader& owner, const std::string& key);
  void read_named_shapes(TableReader& top);

  // A SHAPE table; `where` names it in messages (as "body[2].shape").
  ShapeSpec read_shape_table(const toml::table& table, const std::string& where);

  // Bodies, generators and inflows (bodies.cpp).
  void read_body(TableReader& r);

  // A body whose shape is { type = "bonded", shape = SHAPE, pieces = N,
  // seed, relaxations }: a bonded assembly of N pieces (docs/breakage.md).
  void read_bonded_body(TableReader& r, const toml::table& table);
  void read_given_channels(TableReader& r, dem::BodyDef& d);

  // A region { min, max } of a generator or an inflow; `strict`: max must
  // exceed min on every axis (an inflow may be a plane or a point).
  // A generator's or inflow's region: a box (min, max), or with `type` a
  // "cylinder" (base, axis, radius, height) or a "sphere" (centre, radius).
  // An inflow's may be flat: a box of no extent along an axis, a disc.
  struct Region {
    Vec3 lo, hi;
    std::optional<dem::RoundRegion> round;
  };
  Region read_region(TableReader& r, bool flat);
  std::pair<Vec3, Vec3> read_box_region(TableReader& region, const toml::table& t, bool strict);

  // The bodies a generator or an inflow makes: shapes shared as variants,
  // with number probabilities (empty: equal).
  struct Mix {
    std::vector<dem::BodyShape> variants;
    std::vector<Real> weights;
  };

  // `size` of a random polyhedron: a number or [min, max]; absent when a
  // sieve table gives the sizes.
  PolyhedronSpec read_polyhedron_spec(TableReader& s, const toml::table& t, bool sized_by_table);
  static bool is_random_polyhedron(const toml::table& t);
  Mix read_mix(TableReader& r, std::int64_t count, std::mt19937_64& rng);
  void read_generator(TableReader& r);

  // The generator's `shape` when it is { type = "bonded", ... }, else null.
  static const toml::table* bonded_table(TableReader& r);

  // A generator of bonded assemblies: shape = { type = "bonded", shape =
  // SHAPE, pieces = N, seed, relaxations }, each assembly cut anew (its
  // sites from seed and its number: dem::derived_seed).
  Mix read_bonded_mix(TableReader& r, const toml::table& table, dem::RegionFill& fill);

  // The cut of a bonded table: pieces (required), seed and relaxations.
  static void read_bonded_cut(TableReader& b, dem::BondedDef& d);
  void read_inflow(TableReader& r);


  // Walls and motions (walls.cpp).
  // The optional `motion` table of a wall or fixed body: its number for the
  // builder (0: none).
  std::uint32_t read_motion(TableReader& owner);
  void read_wall(TableReader& r);
  void warn_of_bodies_outside_containers(const std::string& who, const std::vector<std::uint32_t>& placed);

  std::string source_;
  std::filesystem::path base_;
  Scene scene_;
  dem::WorldSettings settings_;
  std::optional<dem::WorldBuilder> builder_;
  dem::BuildProgress progress_;
  std::map<std::pair<std::string, Real>, std::shared_ptr<const Surface>> surfaces_;  ///< by file and scale
  std::map<std::string, NamedShape> named_shapes_;  ///< the [shapes] table, by name
  std::map<std::uint32_t, std::uint32_t> body_lines_;  // explicit bodies: index -> line
  bool accept_overlaps_ = false;
  std::uint64_t generator_count_ = 0;
  std::uint64_t inflow_count_ = 0;
  std::vector<ContainerWall> mesh_walls_;  // for warn_of_bodies_outside_containers
};

}  // namespace gjkdem::io::detail
