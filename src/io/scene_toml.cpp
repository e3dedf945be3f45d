// Scene files (TOML, read with toml++) into a World. Every key is checked:
// unknown keys, wrong types and out-of-range values are refused with the key's
// line, before anything runs.
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

namespace gjkdem::io {
namespace {

// Inflows draw their random streams (dem::derived_seed) from this number on,
// past any generator's.
constexpr std::uint64_t kInflowStreams = 500009;

using Json = nlohmann::ordered_json;
using detail::as_real;
using detail::line_of;
using detail::TableReader;
using detail::ContainerWall;
using detail::bodies_outside_containers;
using detail::MixPart;
using detail::PolyhedronSpec;
using detail::SampledMix;
using detail::SizeClass;
using detail::sample_mix;


// Limits of generators, checked before anything is drawn: each body costs
// about 0.5 KB with its contacts, each variant's vertex 24 bytes and more.
constexpr std::int64_t kMaxVariants = 100'000;
constexpr std::int64_t kMaxGeneratorVertices = 10'000'000;

// An integer of the scene as an int for a builder's rule: beyond int's range
// it becomes the nearest end, which every such rule refuses.
int clamped_int(std::int64_t v) {
  return static_cast<int>(std::clamp<std::int64_t>(v, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

Json to_json(const Vec3& v) { return Json::array({v.x, v.y, v.z}); }
Json to_json(const Quat& q) { return Json::array({q.w, q.x, q.y, q.z}); }

// A shape read from a SHAPE table, in its body's frame.
using ShapeSpec = dem::BodyShape;

class SceneBuilder {
 public:
  SceneBuilder(const std::string& source, std::filesystem::path base) : source_(source), base_(std::move(base)) {}

  // One SHAPE table outside a scene (read_scene_shape): a random polyhedron
  // drawn once from `seed` (a size range drawn in too), any other type as
  // a body's shape.
  SceneShape one_shape(const toml::table& t, const std::string& where, std::uint64_t seed) {
    SceneShape out;
    if (is_random_polyhedron(t)) {
      TableReader r(t, where);
      const PolyhedronSpec p = read_polyhedron_spec(r, t, false);
      std::mt19937_64 rng(seed);
      std::uniform_real_distribution<double> draw(p.size_lo, p.size_hi);
      out.shape = {random_polyhedron(static_cast<int>(p.vertices), draw(rng), rng), {}};
    } else {
      out.shape = read_shape_table(t, where);
    }
    out.warnings = std::move(scene_.warnings);
    return out;
  }

  Scene build(const toml::table& root) {
    TableReader top(root, source_);
    read_simulation(top);
    read_output(top);
    read_contact(top);
    builder_.emplace(settings_);
    if (accept_overlaps_) builder_->accept_initial_overlaps();
    for_each_table(top, "material", [&](TableReader& r) { read_material(r); });
    read_named_shapes(top);
    for_each_table(top, "wall", [&](TableReader& r) { read_wall(r); });
    for_each_table(top, "body", [&](TableReader& r) { read_body(r); });
    for_each_table(top, "generator", [&](TableReader& r) { read_generator(r); });
    for_each_table(top, "inflow", [&](TableReader& r) { read_inflow(r); });
    top.finish();
    if (builder_->moving_count() == 0 && inflow_count_ == 0)
      throw SceneError(source_ + ": the scene has no moving body (add a [[body]], a [[generator]] or an [[inflow]])");
    try {
      scene_.world = builder_->build();
    } catch (const dem::BuildError& e) {
      std::string lines;  // of the bodies at fault, when the scene gave them
      for (const std::uint32_t b : e.bodies)
        if (const auto it = body_lines_.find(b); it != body_lines_.end())
          lines += (lines.empty() ? " (line " : ", line ") + std::to_string(it->second);
      throw SceneError(source_ + ": " + e.what() + (lines.empty() ? "" : lines + ")"));
    }
    if (scene_.dt_auto) scene_.dt = dem::critical_time_step(scene_.world);
    resolved_["simulation"]["dt"] = scene_.dt;
    resolved_["simulation"]["dt_auto"] = scene_.dt_auto;
    scene_.resolved_json = resolved_.dump(2);
    return std::move(scene_);
  }

 private:
  template <class F>
  void for_each_table(TableReader& top, const std::string& key, F&& read) {
    const toml::node* n = top.find(key);
    if (!n) return;
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) top.fail(key, "must be an array of tables: write [[" + key + "]]");
    int index = 0;
    for (const toml::node& e : *a) {
      TableReader r(*e.as_table(), key + "[" + std::to_string(index++) + "]");
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

  const toml::table* sub_table(TableReader& top, const std::string& key) {
    const toml::node* n = top.find(key);
    if (!n) return nullptr;
    if (!n->is_table()) top.fail(key, "must be a table: write [" + key + "]");
    return n->as_table();
  }

  void read_simulation(TableReader& top) {
    const toml::table* t = sub_table(top, "simulation");
    if (!t) throw SceneError(source_ + ": missing the [simulation] table (it needs 'duration')");
    TableReader r(*t, "simulation");
    scene_.duration = r.positive("duration");
    if (const toml::node* n = r.find("dt")) {
      if (n->is_string()) {
        if (n->value<std::string>().value() != "auto") r.fail("dt", "must be a number of seconds or \"auto\"");
      } else {
        scene_.dt_auto = false;
        scene_.dt = r.positive("dt");
      }
    }
    settings_.gravity = r.vec3("gravity").value_or(dem::WorldSettings{}.gravity);
    const std::int64_t threads = r.integer("threads").value_or(0);  // a scene's default: every core
    settings_.threads = clamped_int(threads);
    const std::string overlaps = r.string("initial_overlaps").value_or("refuse");
    if (overlaps != "refuse" && overlaps != "accept")
      r.fail("initial_overlaps", "must be \"refuse\" or \"accept\", not \"" + overlaps + "\"");
    accept_overlaps_ = overlaps == "accept";
    const std::string guards = r.string("guards").value_or("stop");
    if (guards == "stop") scene_.guards.action = dem::GuardAction::Stop;
    else if (guards == "warn") scene_.guards.action = dem::GuardAction::Warn;
    else if (guards == "off") scene_.guards.action = dem::GuardAction::Off;
    else r.fail("guards", "must be \"stop\", \"warn\" or \"off\", not \"" + guards + "\"");
    const std::int64_t seed = r.integer("seed").value_or(1);
    if (seed < 0) r.fail("seed", "must be >= 0");
    scene_.seed = static_cast<std::uint64_t>(seed);
    Json periodic = Json::object();
    if (const toml::table* periodic_table = r.table("periodic")) {
      TableReader p(*periodic_table, r.where() + ".periodic");
      const char* names[3] = {"x", "y", "z"};
      for (int a = 0; a < 3; ++a) {
        const std::vector<Real> range = p.numbers(names[a], 2);
        if (range.empty()) continue;
        settings_.periodic.axes[a] = true;
        settings_.periodic.lo[a] = range[0];
        settings_.periodic.hi[a] = range[1];
        periodic[names[a]] = {range[0], range[1]};
      }
      if (!settings_.periodic.active()) r.fail("periodic", "needs at least one axis, e.g. { x = [0.0, 0.1] }");
      // How the cell deforms: per component a strain rate or a target stress.
      dem::CellControl& control = settings_.cell_control;
      const auto components = [&](const char* key, dem::CellMode mode, const char* example) {
        const toml::table* given_table = p.table(key);
        if (!given_table) return;
        TableReader q(*given_table, p.where() + "." + key);
        Json given = Json::object();
        for (int k = 0; k < 6; ++k) {
          const char* name = dem::kCellComponents[k];
          const std::optional<Real> v = q.number(name);
          if (!v) continue;
          if (control.mode[k] != dem::CellMode::Fixed)
            q.fail(name, "a component takes either a strain rate or a stress, not both");
          control.mode[k] = mode;
          control.value[k] = *v;
          given[name] = *v;
        }
        q.finish();
        if (given.empty()) p.fail(key, std::string("needs at least one component, e.g. ") + example);
        periodic[key] = given;
      };
      components("strain_rate", dem::CellMode::StrainRate, "{ z = -0.1 } or { xz = 1.0 }");
      components("stress", dem::CellMode::Stress, "{ x = 1.0e4, y = 1.0e4, z = 1.0e4 }");
      if (const std::optional<Real> rate = p.number("max_strain_rate")) {
        control.max_strain_rate = *rate;
        periodic["max_strain_rate"] = *rate;
      }
      p.finish();
    }
    r.finish();
    building(r, [&] { dem::check_settings(settings_); });
    resolved_["simulation"] = {{"duration", scene_.duration}, {"gravity", to_json(settings_.gravity)},
                               {"threads", threads}, {"seed", seed}, {"guards", guards},
                               {"initial_overlaps", overlaps}};
    if (!periodic.empty()) resolved_["simulation"]["periodic"] = periodic;
  }

  void read_output(TableReader& top) {
    scene_.output_every = scene_.duration / 100;
    if (const toml::table* t = sub_table(top, "output")) {
      TableReader r(*t, "output");
      scene_.output_dir = r.string("dir").value_or("out");
      if (scene_.output_dir.empty()) r.fail("dir", "must not be empty");
      scene_.output_every = r.positive("every", scene_.output_every);
      scene_.overwrite = r.boolean("overwrite", false);
      const std::int64_t every = r.integer("checkpoint_every").value_or(kDefaultCheckpointEvery);
      if (every < 0) r.fail("checkpoint_every", "must be >= 0 (0: no checkpoints)");
      scene_.checkpoint_every = static_cast<int>(every);
      scene_.write_frames = r.boolean("frames", true);
      scene_.write_view = r.boolean("view", true);
      r.finish();
    }
    resolved_["output"] = {{"dir", scene_.output_dir}, {"every", scene_.output_every},
                           {"overwrite", scene_.overwrite}, {"checkpoint_every", scene_.checkpoint_every},
                           {"frames", scene_.write_frames}, {"view", scene_.write_view}};
  }

  void read_contact(TableReader& top) {
    dem::WorldSettings& w = settings_;
    std::string model = dem::name_of(w.model), form = dem::name_of(w.volume_form);
    if (const toml::table* t = sub_table(top, "contact")) {
      TableReader r(*t, "contact");
      model = r.string("model").value_or(model);
      if (const auto m = dem::contact_model_named(model)) w.model = *m;
      else r.fail("model", std::string("must be ") + dem::kContactModelNames + ", not \"" + model + "\"");
      w.volume_stiffness = r.number("volume_stiffness").value_or(w.volume_stiffness);
      form = r.string("volume_form").value_or(form);
      if (const auto f = dem::volume_form_named(form)) w.volume_form = *f;
      else r.fail("volume_form", std::string("must be ") + dem::kVolumeFormNames + ", not \"" + form + "\"");
      w.linear_stiffness = r.number("linear_stiffness").value_or(w.linear_stiffness);
      w.rocking_resistance = r.boolean("rocking_resistance", w.rocking_resistance);
      w.tessellation = clamped_int(r.integer("tessellation").value_or(w.tessellation));
      building(r, [&] { dem::check_contact_settings(w); });
      r.finish();
    }
    resolved_["contact"] = {{"model", model}, {"volume_form", form},
                            {"rocking_resistance", w.rocking_resistance}, {"tessellation", w.tessellation}};
    if (w.volume_stiffness > 0) resolved_["contact"]["volume_stiffness"] = w.volume_stiffness;
    if (w.linear_stiffness > 0) resolved_["contact"]["linear_stiffness"] = w.linear_stiffness;
  }

  void read_material(TableReader& r) {
    dem::Material m;  // its defaults are the scene's
    m.name = r.required_string("name");
    m.density = r.required_number("density");
    m.youngs_modulus = r.required_number("youngs_modulus");
    for (auto [key, value] : {std::pair{"poisson_ratio", &m.poisson_ratio}, {"restitution", &m.restitution},
                              {"friction", &m.friction}, {"rolling_friction", &m.rolling_friction},
                              {"rolling_damping", &m.rolling_damping}})
      *value = r.number(key).value_or(*value);
    dem::Strength& st = m.strength;  // breakage (docs/breakage.md)
    for (auto [key, value] : {std::pair{"strength", &st.mean}, {"weibull_modulus", &st.weibull_modulus},
                              {"strength_size", &st.reference_size}, {"unbreakable_below", &st.smallest}})
      *value = r.number(key).value_or(*value);
    if (const std::optional<std::int64_t> seed = r.integer("strength_seed")) {
      if (*seed < 0) r.fail("strength_seed", "must be >= 0");
      st.seed = static_cast<std::uint64_t>(*seed);
    }
    dem::Glue& g = m.glue;  // bonded assemblies (docs/breakage.md)
    for (auto [key, value] : {std::pair{"bond_tensile_strength", &g.tensile_strength},
                              {"bond_shear_strength", &g.shear_strength}, {"bond_moment_strength", &g.moment_strength},
                              {"bond_normal_stiffness", &g.normal_stiffness},
                              {"bond_shear_stiffness", &g.shear_stiffness}, {"bond_damping", &g.damping}})
      *value = r.number(key).value_or(*value);
    building(r, [&] { return builder_->add_material(m); });
    Json& resolved = resolved_["material"].emplace_back(
        Json{{"name", m.name}, {"density", m.density}, {"youngs_modulus", m.youngs_modulus},
                       {"poisson_ratio", m.poisson_ratio}, {"restitution", m.restitution}, {"friction", m.friction},
                       {"rolling_friction", m.rolling_friction}, {"rolling_damping", m.rolling_damping}});
    if (st.mean > 0)
      resolved.update({{"strength", st.mean}, {"weibull_modulus", st.weibull_modulus},
                       {"strength_size", st.reference_size}, {"unbreakable_below", st.smallest},
                       {"strength_seed", st.seed}});
    if (g.tensile_strength > 0)
      resolved.update({{"bond_tensile_strength", g.tensile_strength}, {"bond_shear_strength", g.shear_strength},
                       {"bond_moment_strength", g.moment_strength},
                       {"bond_normal_stiffness", g.normal_stiffness}, {"bond_shear_stiffness", g.shear_stiffness},
                       {"bond_damping", g.damping}});
  }

  std::uint32_t material_of(TableReader& r) {
    const std::string name = r.required_string("material");
    const std::optional<std::uint32_t> m = builder_->find_material(name);
    if (!m) r.fail("material", "no [[material]] is named '" + name + "'");
    return *m;
  }


  std::filesystem::path file_of(TableReader& r, const std::string& key) {
    const std::filesystem::path f = base_ / r.required_string(key);
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(f, ec);
    if (ec && ec != std::errc::no_such_file_or_directory)
      r.fail(key, "cannot read " + f.string() + " (" + ec.message() + ")");
    if (!std::filesystem::exists(status)) r.fail(key, "file not found: " + f.string());
    if (!std::filesystem::is_regular_file(status)) r.fail(key, f.string() + " is not a regular file");
    return f;
  }

  // A mesh's vertices scaled, then placed; a scale that puts them beyond
  // kMaxCoordinate, or shrinks the mesh below what double precision
  // resolves, is refused by its key (not reported later as a flat mesh).
  void scale_mesh(TableReader& r, TriangleMesh& mesh, Real scale, const Transform& place = Transform::identity()) {
    Real extent = 0;
    for (const Vec3& v : mesh.vertices) extent = std::fmax(extent, max_abs(v));
    if (!mesh.vertices.empty() && !(extent * scale >= kMinMeshSize))
      r.fail("scale", "shrinks the mesh below 1e-100 m (not resolvable)");
    for (Vec3& v : mesh.vertices) {
      v = apply(place, v * scale);
      if (!(max_abs(v) <= kMaxCoordinate)) r.fail("scale", "puts the mesh beyond 1e100 m (not resolvable)");
    }
  }

  Polytope mesh_hull(TableReader& r, Real scale) {
    const std::filesystem::path file = file_of(r, "file");
    try {
      TriangleMesh mesh = read_mesh(file);
      scale_mesh(r, mesh, scale);
      ConvexMesh c = convex_from_mesh(mesh, file.string());
      for (std::string& w : c.warnings) scene_.warnings.push_back(r.where() + ": " + w);
      return c.polytope;
    } catch (const MeshError& e) {
      r.fail("file", e.what());
    }
  }

  // A closed mesh as it is (a surface grain), checked by make_surface; one
  // surface per file and scale, shared by every body that names it.
  std::shared_ptr<const Surface> mesh_surface(TableReader& r, Real scale) {
    if (!r.has("file")) return inline_surface(r, scale);
    if (r.has("vertices") || r.has("triangles")) r.fail("file", "give either a 'file' or 'vertices' and 'triangles'");
    const std::filesystem::path file = file_of(r, "file");
    std::shared_ptr<const Surface>& known = surfaces_[{file.string(), scale}];
    if (known) return known;
    try {
      TriangleMesh mesh = read_mesh(file);
      scale_mesh(r, mesh, scale);
      known = std::make_shared<const Surface>(make_surface(std::move(mesh.vertices), std::move(mesh.triangles)));
      return known;
    } catch (const MeshError& e) {
      r.fail("file", e.what());
    } catch (const SurfaceError& e) {
      r.fail("file", file.string() + " is not a closed surface a grain can have: " + e.what());
    }
  }

  // A surface given in the scene: `vertices` [[x, y, z], ...] and
  // `triangles` [[i, j, k], ...] (0-based, counter-clockwise seen from
  // outside), as the query format's mesh; scaled by `scale`.
  std::shared_ptr<const Surface> inline_surface(TableReader& r, Real scale) {
    TriangleMesh mesh = inline_triangles(r, scale, "a surface");
    try {
      return std::make_shared<const Surface>(make_surface(std::move(mesh.vertices), std::move(mesh.triangles)));
    } catch (const SurfaceError& e) {
      r.fail("triangles", std::string("not a closed surface a grain can have: ") + e.what());
    }
  }

  // Triangles given in the scene: `vertices` [[x, y, z], ...] scaled by
  // `scale` and `triangles` [[i, j, k], ...] (0-based indices).
  TriangleMesh inline_triangles(TableReader& r, Real scale, const std::string& what) {
    if (!r.has("vertices") || !r.has("triangles"))
      r.fail("type", what + " takes a mesh 'file', or 'vertices' and 'triangles'");
    std::vector<Vec3> vertices;
    for (const std::vector<Real>& v : r.rows("vertices", 3, "[x, y, z]")) vertices.push_back(Vec3{v[0], v[1], v[2]} * scale);
    std::vector<TriangleIndices> triangles;
    for (const std::vector<Real>& t : r.rows("triangles", 3, "[i, j, k] of vertex indices")) {
      TriangleIndices ids{};
      for (int k = 0; k < 3; ++k) {
        if (!(t[k] >= 0 && t[k] < static_cast<Real>(vertices.size()) && t[k] == std::floor(t[k])))
          r.fail("triangles", "must hold indices of vertices (integers from 0 to " +
                                  std::to_string(vertices.size() - 1) + ")");
        ids[k] = static_cast<std::uint32_t>(t[k]);
      }
      triangles.push_back(ids);
    }
    TriangleMesh mesh;
    mesh.vertices = std::move(vertices);
    mesh.triangles = std::move(triangles);
    return mesh;
  }

  // A thin shell: the triangles of a mesh `file` (scaled) or given in the
  // scene, open or closed, with a `thickness` (m, not scaled), checked by
  // make_shell.
  std::shared_ptr<const Shell> mesh_shell(TableReader& r, Real scale) {
    const Real thickness = r.positive("thickness");
    TriangleMesh mesh;
    const bool from_file = r.has("file");
    if (from_file) {
      if (r.has("vertices") || r.has("triangles")) r.fail("file", "give either a 'file' or 'vertices' and 'triangles'");
      const std::filesystem::path file = file_of(r, "file");
      try {
        mesh = read_mesh(file);
        scale_mesh(r, mesh, scale);
      } catch (const MeshError& e) {
        r.fail("file", e.what());
      }
    } else {
      mesh = inline_triangles(r, scale, "a shell");
    }
    try {
      return std::make_shared<const Shell>(make_shell(std::move(mesh.vertices), std::move(mesh.triangles), thickness));
    } catch (const ShellError& e) {
      r.fail(from_file ? "file" : "triangles", std::string("not a shell: ") + e.what());
    }
  }

  // A compound's parts: SHAPE tables (`parts`; a surface goes to the
  // surface parts) or the objects of a mesh file (`file`, `scale`), each the
  // convex hull of its triangles.
  void read_compound_parts(TableReader& r, const toml::table& t, ShapeSpec& s) {
    std::vector<PlacedShape>& parts = s.parts;
    if (r.has("file")) {
      if (r.has("parts")) r.fail("parts", "give either 'parts' or 'file', not both");
      const std::filesystem::path file = file_of(r, "file");
      const Real scale = r.positive("scale", 1.0);
      try {
        TriangleMesh mesh = read_mesh(file);
        scale_mesh(r, mesh, scale);
        for (ConvexMesh& c : convex_parts_from_mesh(mesh, file.string())) {
          for (std::string& w : c.warnings) scene_.warnings.push_back(r.where() + ": " + w);
          parts.push_back({Shape{c.polytope}, {}});
        }
      } catch (const MeshError& e) {
        r.fail("file", e.what());
      }
      return;
    }
    const toml::node* n = r.find("parts");
    const toml::array* a = n ? n->as_array() : nullptr;
    if (!a || a->empty() || !a->is_array_of_tables())
      throw SceneError(r.where() + ": a compound needs 'parts', an array of SHAPE tables, or a mesh 'file'" +
                       line_of(n ? *n : static_cast<const toml::node&>(t)));
    for (std::size_t k = 0; k < a->size(); ++k) {
      const std::string where = r.where() + ".parts[" + std::to_string(k) + "]";
      const toml::table& part = *(*a)[k].as_table();
      if (part.get("type") && part.get("type")->value<std::string>() == std::optional<std::string>("compound"))
        throw SceneError(where + ": a part cannot itself be a compound" + line_of(part));
      const ShapeSpec p = read_shape_table(part, where);
      if (p.shell) throw SceneError(where + ": a shell is not a compound's part (a body of its own)" + line_of(part));
      if (p.surface) s.surface_parts.push_back({p.surface, p.pose});
      else parts.push_back({p.shape, p.pose});
    }
  }

  // A SHAPE table: the types of query-format.md, plus platonic and mesh, and
  // for generators random_polyhedron (drawn per variant by the caller).
  ShapeSpec read_shape(TableReader& owner, const std::string& key) {
    if (const NamedShape* named = named_shape(owner, key)) {
      if (!named->spec) owner.fail(key, "names a random_polyhedron, which generators and inflows draw: a body needs a shape");
      return *named->spec;
    }
    const toml::table* t = owner.table(key);
    if (!t) throw SceneError(owner.where() + ": missing required key '" + key + "'" + line_of(owner.table_node()));
    return read_shape_table(*t, owner.where() + "." + key);
  }

  // A shape of the [shapes] table, named by a string where a SHAPE goes:
  // the moving bodies that name it share one template.
  struct NamedShape {
    const toml::table* table = nullptr;  // as written (generators and inflows read it so)
    std::optional<ShapeSpec> spec;       // as read (none for a random_polyhedron)
    std::int64_t shared = -1;            // the builder's shared shape, once a moving body took it
    std::int64_t shared_fixed = -1;      // ... once a fixed body took it
  };

  // The SHAPE table at `key`: written there, or named there.
  const toml::table* shape_table_at(TableReader& owner, const std::string& key) {
    if (const NamedShape* named = named_shape(owner, key)) return named->table;
    return owner.table(key);
  }

  NamedShape* named_shape(TableReader& owner, const std::string& key) {
    const toml::node* n = owner.find(key);
    if (!n || !n->is_string()) return nullptr;
    const std::string name = **n->as_string();
    const auto it = named_shapes_.find(name);
    if (it == named_shapes_.end())
      owner.fail(key, "names no shape of the [shapes] table ('" + name + "')");
    return &it->second;
  }

  void read_named_shapes(TableReader& top) {
    const toml::table* shapes = top.table("shapes");
    if (!shapes) return;
    for (const auto& [key, node] : *shapes) {
      const std::string name(key.str()), where = "shapes." + name;
      if (!node.is_table())
        throw SceneError(where + ": must be a SHAPE table, e.g. { type = \"box\", ... }" + line_of(node));
      NamedShape& named = named_shapes_[name];
      named.table = node.as_table();
      if (!is_random_polyhedron(*named.table)) named.spec = read_shape_table(*named.table, where);
      resolved_["shapes"].push_back(name);
    }
  }

  // A SHAPE table; `where` names it in messages (as "body[2].shape").
  ShapeSpec read_shape_table(const toml::table& table, const std::string& where) {
    const toml::table* t = &table;
    TableReader r(*t, where);
    const std::string type = r.required_string("type");
    ShapeSpec s;
    if (type == "platonic") {
      const std::string name = r.required_string("name");
      const Real size = r.positive("size");
      try {
        s.shape = platonic(name, size);
      } catch (const std::invalid_argument& e) {
        r.fail("name", e.what());
      }
      r.finish();
    } else if (type == "mesh") {
      const Real scale = r.positive("scale", 1.0);
      s.shape = Shape{mesh_hull(r, scale)};
      r.finish();
    } else if (type == "surface") {
      const Real scale = r.positive("scale", 1.0);
      s.surface = mesh_surface(r, scale);
      s.pose = Transform::from(r.vec3("center").value_or(Vec3{}), r.rotation("rotation").value_or(Quat{}));
      r.finish();
    } else if (type == "shell") {
      const Real scale = r.positive("scale", 1.0);
      s.shell = mesh_shell(r, scale);
      s.pose = Transform::from(r.vec3("center").value_or(Vec3{}), r.rotation("rotation").value_or(Quat{}));
      r.finish();
    } else if (type == "compound") {
      read_compound_parts(r, *t, s);
      r.finish();
    } else if (type == "bonded") {
      r.fail("type", "\"bonded\" is the shape of a [[body]] or of a [[generator]]'s single `shape` only (written "
                     "there, not named in [shapes]; inflows and compounds take single shapes)");
    } else {
      std::ostringstream json;
      json << toml::json_formatter{*t};
      // In a scene a shape is given in its body's frame: centred on the
      // body's origin and unrotated unless it says otherwise.
      try {
        const PlacedInput p = parse_shape(json.str(), ShapeFrame::Own);
        s.shape = p.shape;
        s.pose = p.pose;
      } catch (const std::exception& e) {
        throw SceneError(where + ": " + e.what() + line_of(*t));
      }
    }
    return s;
  }

  void read_body(TableReader& r) {
    if (const toml::node* n = r.find("shape"); n && n->is_table()) {
      const toml::table& t = *n->as_table();
      if (t.get("type") && t.get("type")->value<std::string>() == std::optional<std::string>("bonded"))
        return read_bonded_body(r, t);
    }
    dem::BodyDef d;
    d.label = r.where();
    const std::optional<std::string> name = r.string("name");
    d.shape = read_shape(r, "shape");
    d.material = material_of(r);
    d.fixed = r.boolean("fixed", false);
    if (NamedShape* named = named_shape(r, "shape")) {  // one template for its moving bodies, one for its fixed ones
      std::int64_t& shared = d.fixed ? named->shared_fixed : named->shared;
      if (shared < 0) shared = building(r.table_node(), [&] { return builder_->add_shape(d.shape, d.label, d.fixed); });
      d.shared_shape = shared;
    }
    d.position = r.vec3("position").value_or(Vec3{});
    d.rotation = r.rotation("rotation").value_or(Quat{});
    d.velocity = r.vec3("velocity").value_or(Vec3{});
    d.angular_velocity = r.vec3("angular_velocity").value_or(Vec3{});
    if (d.fixed && (length(d.velocity) > 0 || length(d.angular_velocity) > 0))
      r.fail("velocity", "a fixed body cannot move (velocity and angular_velocity must be 0; give it a 'motion')");
    d.applied_force = r.vec3("applied_force").value_or(Vec3{});
    d.applied_torque = r.vec3("applied_torque").value_or(Vec3{});
    if (d.fixed && (length(d.applied_force) > 0 || length(d.applied_torque) > 0))
      r.fail("applied_force", "is for free bodies (a fixed body takes no applied load)");
    Json motion_json;
    if (r.has("motion") && !d.fixed) r.fail("motion", "is for fixed bodies (set fixed = true)");
    d.motion = read_motion(r, motion_json);
    if (name && name->empty()) r.fail("name", "must not be empty (leave it out for an untraced body)");
    if (name) d.name = *name;  // the builder checks it (unique, a CSV field)
    const std::uint32_t index = building(r.table_node(), [&] { return builder_->add_body(d); });
    body_lines_[index] = r.table_node().source().begin.line;
    Json j = {{"shape", "(as given)"}, {"material", r.required_string("material")},
              {"position", to_json(d.position)}, {"rotation", to_json(d.rotation)}, {"velocity", to_json(d.velocity)},
              {"angular_velocity", to_json(d.angular_velocity)}, {"fixed", d.fixed}};
    if (length(d.applied_force) > 0 || length(d.applied_torque) > 0)
      j["applied_force"] = to_json(d.applied_force), j["applied_torque"] = to_json(d.applied_torque);
    if (name) j["name"] = *name;
    if (d.motion) j["motion"] = motion_json["motion"];
    resolved_["body"].push_back(j);
  }

  // A body whose shape is { type = "bonded", shape = SHAPE, pieces = N,
  // seed, relaxations }: a bonded assembly of N pieces (docs/breakage.md).
  void read_bonded_body(TableReader& r, const toml::table& table) {
    TableReader b(table, r.where() + ".shape");
    b.required_string("type");
    dem::BondedDef d;
    d.label = r.where();
    d.shape = read_shape(b, "shape");
    read_bonded_cut(b, d);
    b.finish();
    d.material = material_of(r);
    for (const char* key : {"name", "fixed", "motion"})
      if (r.has(key)) r.fail(key, "is not for a bonded assembly (its pieces move, each a body of its own)");
    d.position = r.vec3("position").value_or(Vec3{});
    d.rotation = r.rotation("rotation").value_or(Quat{});
    d.velocity = r.vec3("velocity").value_or(Vec3{});
    d.angular_velocity = r.vec3("angular_velocity").value_or(Vec3{});
    const std::vector<std::uint32_t> indices = building(r.table_node(), [&] { return builder_->add_bonded(d); });
    for (const std::uint32_t index : indices) body_lines_[index] = r.table_node().source().begin.line;
    resolved_["body"].push_back(
        Json{{"shape", {{"type", "bonded"}, {"shape", "(as given)"}, {"pieces", d.pieces}, {"seed", d.seed},
                        {"relaxations", d.relaxations}}},
             {"material", r.required_string("material")}, {"position", to_json(d.position)},
             {"rotation", to_json(d.rotation)}, {"velocity", to_json(d.velocity)},
             {"angular_velocity", to_json(d.angular_velocity)}, {"fixed", false}});
  }

  // A region { min, max } of a generator or an inflow; `strict`: max must
  // exceed min on every axis (an inflow may be a plane or a point).
  // A generator's or inflow's region: a box (min, max), or with `type` a
  // "cylinder" (base, axis, radius, height) or a "sphere" (centre, radius).
  // An inflow's may be flat: a box of no extent along an axis, a disc.
  struct Region {
    Vec3 lo, hi;
    std::optional<dem::RoundRegion> round;
    Json resolved;
  };
  Region read_region(TableReader& r, bool flat) {
    const toml::table* t = r.table("region");
    if (!t) throw SceneError(r.where() + ": missing required key 'region'" + line_of(r.table_node()));
    TableReader region(*t, r.where() + ".region");
    const std::string type = region.string("type").value_or("box");
    Region g;
    if (type == "box") {
      std::tie(g.lo, g.hi) = read_box_region(region, *t, !flat);
      g.resolved = {{"min", to_json(g.lo)}, {"max", to_json(g.hi)}};
      return g;
    }
    dem::RoundRegion round;
    if (type == "cylinder") {
      round.base = region.vec3("base").value_or(Vec3{});
      round.axis = region.vec3("axis").value_or(Vec3{0, 0, 1});
      if (!(length(round.axis) > 0)) region.fail("axis", "must not be zero");
      round.radius = region.positive("radius");
      if (flat) {
        round.height = region.number("height").value_or(-1);
        if (!(round.height >= 0)) region.fail("height", "must be >= 0 (0: a disc)");
      } else {
        round.height = region.positive("height");
      }
      g.resolved = {{"type", type}, {"base", to_json(round.base)}, {"axis", to_json(round.axis)},
                    {"radius", round.radius}, {"height", round.height}};
    } else if (type == "sphere") {
      round.kind = dem::RoundRegion::Kind::Ball;
      const std::optional<Vec3> centre = region.vec3("centre");
      if (!centre) throw SceneError(region.where() + ": a sphere region needs 'centre'" + line_of(*t));
      round.base = *centre;
      round.radius = region.positive("radius");
      g.resolved = {{"type", type}, {"centre", to_json(round.base)}, {"radius", round.radius}};
    } else {
      region.fail("type", "must be \"box\", \"cylinder\" or \"sphere\", not \"" + type + "\"");
    }
    region.finish();
    g.round = round;
    return g;
  }

  std::pair<Vec3, Vec3> read_box_region(TableReader& region, const toml::table& t, bool strict) {
    const Vec3 lo = region.vec3("min").value_or(Vec3{}), hi = region.vec3("max").value_or(Vec3{});
    if (!region.has("min") || !region.has("max"))
      throw SceneError(region.where() + ": needs 'min' and 'max'" + line_of(t));
    if (strict ? !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z) : !(hi.x >= lo.x && hi.y >= lo.y && hi.z >= lo.z))
      region.fail("max", strict ? "must exceed 'min' on every axis" : "must not be below 'min' on any axis");
    region.finish();
    return {lo, hi};
  }

  // The bodies a generator or an inflow makes: shapes shared as variants,
  // with number probabilities (empty: equal).
  struct Mix {
    std::vector<dem::BodyShape> variants;
    std::vector<Real> weights;
    Json resolved;
  };

  // `size` of a random polyhedron: a number or [min, max]; absent when a
  // sieve table gives the sizes.
  PolyhedronSpec read_polyhedron_spec(TableReader& s, const toml::table& t, bool sized_by_table) {
    s.required_string("type");
    PolyhedronSpec p;
    p.vertices = s.integer("vertices").value_or(12);
    if (p.vertices < 4 || p.vertices > 10000) s.fail("vertices", "must be between 4 and 10000");
    if (const toml::node* n = s.find("size"); n && n->is_number()) {
      p.size_lo = p.size_hi = s.positive("size");
    } else {
      const std::vector<Real> range = s.numbers("size", 2);
      if (range.empty() && !sized_by_table) throw SceneError(s.where() + ": missing required key 'size'" + line_of(t));
      if (!range.empty()) {
        p.size_lo = range[0], p.size_hi = range[1];
        if (!(p.size_lo > 0 && p.size_hi >= p.size_lo)) s.fail("size", "must be [min, max] with 0 < min <= max");
      }
    }
    if (sized_by_table && p.size_hi > 0) s.fail("size", "is given by the sieve table 'sizes': remove it here");
    s.finish();
    return p;
  }

  static bool is_random_polyhedron(const toml::table& t) {
    return t.get("type") && t.get("type")->value<std::string>() == std::optional<std::string>("random_polyhedron");
  }

  Mix read_mix(TableReader& r, std::int64_t count, std::mt19937_64& rng) {
    Mix mix;
    if (!r.has("sizes") && !r.has("shapes")) {  // one shape, equal variants (as before tables existed)
      const std::int64_t variants = r.integer("variants").value_or(std::min<std::int64_t>(count, 50));
      if (variants <= 0 || variants > std::min<std::int64_t>(count, kMaxVariants))
        r.fail("variants", "must be a positive integer up to the count and " + std::to_string(kMaxVariants));
      const toml::table* st = shape_table_at(r, "shape");
      if (!st) throw SceneError(r.where() + ": missing required key 'shape'" + line_of(r.table_node()));
      if (is_random_polyhedron(*st)) {
        TableReader s(*st, r.where() + ".shape");
        const PolyhedronSpec p = read_polyhedron_spec(s, *st, false);
        if (p.vertices * variants > kMaxGeneratorVertices)
          s.fail("vertices", "times the variants must stay under " + std::to_string(kMaxGeneratorVertices) +
                                 " (memory for the shapes)");
        std::uniform_real_distribution<double> draw(p.size_lo, p.size_hi);
        for (std::int64_t k = 0; k < variants; ++k)
          mix.variants.push_back({random_polyhedron(static_cast<int>(p.vertices), draw(rng), rng), {}});
        mix.resolved = {{"shape", {{"type", "random_polyhedron"}, {"vertices", p.vertices},
                                   {"size", {p.size_lo, p.size_hi}}, {"variants", variants}}},
                        {"variants", variants}};
      } else {
        mix.variants.push_back(read_shape(r, "shape"));
        std::ostringstream json;
        json << toml::json_formatter{*st};
        mix.resolved = {{"shape", Json::parse(json.str())}, {"variants", variants}};
      }
      return mix;
    }

    // Parts (a shape and its fraction), each in the size classes of the sieve table.
    struct Part {
      const toml::table* table;
      std::string where;
      Real fraction;
    };
    std::vector<Part> parts;
    if (const toml::node* n = r.find("shapes")) {
      const toml::array* a = n->as_array();
      if (!a || a->empty() || !a->is_array_of_tables())
        r.fail("shapes", "must be an array of { shape = SHAPE, fraction = f } tables");
      for (std::size_t k = 0; k < a->size(); ++k) {
        TableReader part(*(*a)[k].as_table(), r.where() + ".shapes[" + std::to_string(k) + "]");
        const toml::table* shape = shape_table_at(part, "shape");
        if (!shape) throw SceneError(part.where() + ": missing required key 'shape'" + line_of(*(*a)[k].as_table()));
        const Real f = part.number("fraction").value_or(-1);
        if (!(f > 0)) part.fail("fraction", "must be > 0");
        part.finish();
        parts.push_back({shape, part.where() + ".shape", f});
      }
      if (r.has("shape")) r.fail("shape", "give either 'shape' or 'shapes', not both");
    } else {
      const toml::table* shape = shape_table_at(r, "shape");
      if (!shape) throw SceneError(r.where() + ": missing required key 'shape'" + line_of(r.table_node()));
      parts.push_back({shape, r.where() + ".shape", 1});
    }
    const std::string fractions = r.string("fractions").value_or("number");
    if (fractions != "number" && fractions != "mass") r.fail("fractions", "must be \"number\" or \"mass\"");
    std::vector<SizeClass> classes;
    const std::string sieve_row = "[min_size, max_size, mass_fraction] (a sieve table)";
    if (r.has("sizes")) {
      Real total = 0;
      for (const std::vector<Real>& v : r.rows("sizes", 3, sieve_row)) {
        if (!(v[0] > 0 && v[1] >= v[0])) r.fail("sizes", "sizes must be finite with 0 < min_size <= max_size");
        if (!(v[2] >= 0)) r.fail("sizes", "mass fractions must be finite and >= 0");
        classes.push_back({v[0], v[1], v[2]});
        total += v[2];
      }
      if (!(std::fabs(total - 1) <= kMassFractionSumTol))
        r.fail("sizes", "the mass fractions add up to " + std::to_string(total) + ", not 1");
    }
    const bool sized = !classes.empty();
    const std::size_t class_count = sized ? classes.size() : 1;
    const std::int64_t per_group = r.integer("variants").value_or(sized ? 10 : 1);
    if (per_group <= 0 || per_group * static_cast<std::int64_t>(parts.size() * class_count) > kMaxVariants)
      r.fail("variants", "must be a positive integer (variants per shape and size class), all of them up to " +
                             std::to_string(kMaxVariants));
    std::vector<MixPart> mix_parts;
    Json resolved_parts = Json::array();
    for (const Part& part : parts) {
      TableReader s(*part.table, part.where);
      MixPart m;
      m.where = part.where, m.fraction = part.fraction;
      if (is_random_polyhedron(*part.table)) {
        m.polyhedron = read_polyhedron_spec(s, *part.table, sized);
        if (m.polyhedron->vertices * per_group * static_cast<std::int64_t>(class_count) > kMaxGeneratorVertices)
          s.fail("vertices", "times the variants must stay under " + std::to_string(kMaxGeneratorVertices));
      } else {
        m.base = read_shape_table(*part.table, part.where);
        if (m.base.shell)
          throw SceneError(part.where + ": a thin shell is a [[body]] of its own (generators and inflows do not make them)" +
                           line_of(*part.table));
        m.base_size = 2 * bounding_radius(m.base.shape);
        for (const PlacedShape& p : m.base.parts)  // a compound: of the sphere about its frame holding its parts
          m.base_size = std::fmax(m.base_size, 2 * (length(p.pose.translation) + bounding_radius(p.shape)));
        if (m.base.surface)  // a surface grain: of the sphere about its frame holding its vertices
          for (const Vec3& v : m.base.surface->vertices) m.base_size = std::fmax(m.base_size, 2 * length(v));
        for (const dem::PlacedSurface& p : m.base.surface_parts)
          for (const Vec3& v : p.surface->vertices) m.base_size = std::fmax(m.base_size, 2 * length(apply(p.pose, v)));
        if (!(m.base_size > 0)) throw SceneError(part.where + ": a shape without size cannot be sized by the table");
      }
      mix_parts.push_back(std::move(m));
      std::ostringstream json;
      json << toml::json_formatter{*part.table};
      resolved_parts.push_back({{"shape", Json::parse(json.str())}, {"fraction", part.fraction}});
    }
    SampledMix sampled = sample_mix(mix_parts, classes, per_group, fractions == "mass", rng);
    mix.variants = std::move(sampled.variants);
    mix.weights = std::move(sampled.weights);
    mix.resolved = {{"shapes", resolved_parts}, {"fractions", fractions}, {"variants", per_group}};
    if (sized) {
      Json table = Json::array();
      for (const SizeClass& c : classes) table.push_back({c.lo, c.hi, c.mass_fraction});
      mix.resolved["sizes"] = table;
    }
    return mix;
  }

  void read_generator(TableReader& r) {
    const std::int64_t count = r.integer("count").value_or(-1);
    building(r, [&] { dem::check_fill_count(count); });  // before anything is drawn
    dem::RegionFill fill;
    fill.label = r.where();
    fill.count = static_cast<std::size_t>(count);
    fill.material = material_of(r);
    const Region region = read_region(r, false);
    fill.lo = region.lo, fill.hi = region.hi, fill.round = region.round;
    fill.velocity = r.vec3("velocity").value_or(Vec3{});
    fill.fixed = r.boolean("fixed", false);
    std::mt19937_64 rng(dem::derived_seed(scene_.seed, generator_count_++));
    const toml::table* bonded = bonded_table(r);
    Mix mix = bonded ? read_bonded_mix(r, *bonded, fill) : read_mix(r, count, rng);
    fill.variants = std::move(mix.variants);
    fill.weights = std::move(mix.weights);
    const std::vector<std::uint32_t> placed = building(*r.table("region"), [&] { return builder_->fill_region(fill, rng); });
    warn_of_bodies_outside_containers(r.where(), placed);
    Json j = {{"count", count}, {"material", r.required_string("material")},
              {"region", region.resolved}, {"velocity", to_json(fill.velocity)}};
    if (fill.fixed) j["fixed"] = true;
    j.update(mix.resolved);
    resolved_["generator"].push_back(j);
  }

  // The generator's `shape` when it is { type = "bonded", ... }, else null.
  static const toml::table* bonded_table(TableReader& r) {
    const toml::node* n = r.find("shape");
    if (!n || !n->is_table()) return nullptr;
    const toml::table& t = *n->as_table();
    return t.get("type") && t.get("type")->value<std::string>() == std::optional<std::string>("bonded") ? &t : nullptr;
  }

  // A generator of bonded assemblies: shape = { type = "bonded", shape =
  // SHAPE, pieces = N, seed, relaxations }, each assembly cut anew (its
  // sites from seed and its number: dem::derived_seed).
  Mix read_bonded_mix(TableReader& r, const toml::table& table, dem::RegionFill& fill) {
    for (const char* key : {"shapes", "sizes", "variants", "fractions"})
      if (r.has(key))
        r.fail(key, "is not for a generator of bonded assemblies (one shape, each assembly cut anew from its seed)");
    if (fill.fixed) r.fail("fixed", "bonded assemblies move: they cannot be fixed");
    TableReader b(table, r.where() + ".shape");
    b.required_string("type");
    Mix mix;
    mix.variants.push_back(read_shape(b, "shape"));
    dem::BondedDef cut;
    read_bonded_cut(b, cut);
    std::ostringstream json;
    json << toml::json_formatter{*shape_table_at(b, "shape")};
    b.finish();
    fill.pieces = cut.pieces, fill.pieces_seed = cut.seed, fill.relaxations = cut.relaxations;
    mix.resolved = {{"shape", {{"type", "bonded"}, {"shape", Json::parse(json.str())}, {"pieces", cut.pieces},
                               {"seed", cut.seed}, {"relaxations", cut.relaxations}}}};
    return mix;
  }

  // The cut of a bonded table: pieces (required), seed and relaxations.
  static void read_bonded_cut(TableReader& b, dem::BondedDef& d) {
    const std::int64_t pieces = b.integer("pieces").value_or(0);
    if (pieces < 2 || pieces > dem::kMaxBondedPieces)
      b.fail("pieces", "must be given, between 2 and " + std::to_string(dem::kMaxBondedPieces));
    d.pieces = static_cast<std::uint32_t>(pieces);
    const std::int64_t seed = b.integer("seed").value_or(1);
    if (seed < 0) b.fail("seed", "must be >= 0");
    d.seed = static_cast<std::uint64_t>(seed);
    const std::int64_t relaxations = b.integer("relaxations").value_or(3);
    if (relaxations < 0 || relaxations > 100) b.fail("relaxations", "must be between 0 and 100");
    d.relaxations = static_cast<int>(relaxations);
  }

  void read_inflow(TableReader& r) {
    dem::InflowDef d;
    d.label = r.where();
    d.material = material_of(r);
    const Region region = read_region(r, true);
    d.lo = region.lo, d.hi = region.hi, d.round = region.round;
    d.velocity = r.vec3("velocity").value_or(Vec3{});
    const std::optional<Real> rate = r.number("rate"), mass_rate = r.number("mass_rate");
    if (rate.has_value() == mass_rate.has_value())
      throw SceneError(r.where() + ": give one of 'rate' (bodies per second) and 'mass_rate' (kg per second)" +
                       line_of(r.table_node()));
    if (rate && !(*rate > 0)) r.fail("rate", "must be > 0");
    if (mass_rate && !(*mass_rate > 0)) r.fail("mass_rate", "must be > 0");
    d.rate = rate.value_or(0);
    d.mass_rate = mass_rate.value_or(0);
    d.start = r.number("start").value_or(0);
    if (!(d.start >= 0)) r.fail("start", "must be >= 0");
    d.stop = r.number("stop").value_or(scene_.duration);
    if (!(d.stop > d.start)) r.fail("stop", "must come after the start");
    const std::int64_t count = r.integer("count").value_or(0);
    if (count < 0 || count > static_cast<std::int64_t>(dem::kMaxInflowBodies))
      r.fail("count", "must be a positive integer up to " + std::to_string(dem::kMaxInflowBodies));
    d.count = static_cast<std::uint64_t>(count);
    d.seed = dem::derived_seed(scene_.seed, kInflowStreams + inflow_count_);
    std::mt19937_64 rng(d.seed);
    Mix mix = read_mix(r, count > 0 ? count : 50, rng);
    d.variants = std::move(mix.variants);
    d.weights = std::move(mix.weights);
    building(r.table_node(), [&] { return builder_->add_inflow(d); });
    ++inflow_count_;
    Json j = {{"material", r.required_string("material")},
              {"region", region.resolved}, {"velocity", to_json(d.velocity)},
              {"start", d.start}, {"stop", d.stop}};
    if (rate) j["rate"] = *rate;
    if (mass_rate) j["mass_rate"] = *mass_rate;
    if (count > 0) j["count"] = count;
    j.update(mix.resolved);
    resolved_["inflow"].push_back(j);
  }

  // The optional `motion` table of a wall or fixed body: its number for the
  // builder (0: none), its resolved form added to `j`.
  std::uint32_t read_motion(TableReader& owner, Json& j) {
    const toml::table* t = owner.table("motion");
    if (!t) return 0;
    TableReader r(*t, owner.where() + ".motion");
    dem::PrescribedMotion m;
    m.center = r.vec3("center").value_or(Vec3{});
    m.velocity = r.vec3("velocity").value_or(Vec3{});
    m.angular_velocity = r.vec3("angular_velocity").value_or(Vec3{});
    Json out = {{"center", to_json(m.center)}, {"velocity", to_json(m.velocity)},
                {"angular_velocity", to_json(m.angular_velocity)}};
    if (const toml::table* v = r.table("vibration")) {
      TableReader vib(*v, r.where() + ".vibration");
      const std::optional<Vec3> amplitude = vib.vec3("amplitude");
      if (!amplitude) throw SceneError(vib.where() + ": missing required key 'amplitude'" + line_of(*v));
      m.amplitude = *amplitude;
      m.frequency = vib.positive("frequency");
      m.phase = vib.number("phase").value_or(0);
      vib.finish();
      out["vibration"] = {{"amplitude", to_json(m.amplitude)}, {"frequency", m.frequency}, {"phase", m.phase}};
    }
    if (r.has("table")) {
      for (const std::vector<Real>& v : r.rows("table", 4, "[time, x, y, z] (seconds, metres)")) {
        if (!m.table_times.empty() && !(v[0] > m.table_times.back())) r.fail("table", "times must increase");
        m.table_times.push_back(v[0]);
        m.table_displacements.push_back({v[1], v[2], v[3]});
      }
      Json table = Json::array();
      for (std::size_t k = 0; k < m.table_times.size(); ++k) {
        const Vec3& d = m.table_displacements[k];
        table.push_back({m.table_times[k], d.x, d.y, d.z});
      }
      out["table"] = table;
    }
    r.finish();
    j["motion"] = out;
    return building(*t, [&] { return builder_->add_motion(m, r.where()); });
  }

  void read_wall(TableReader& r) {
    const std::string type = r.required_string("type");
    const std::uint32_t material = material_of(r);
    Json j = {{"type", type}, {"material", r.required_string("material")}};
    const std::uint32_t motion = read_motion(r, j);
    if (type == "plane") {
      const Vec3 point = r.vec3("point").value_or(Vec3{});
      const std::optional<Vec3> normal = r.vec3("normal");
      if (!normal) throw SceneError(r.where() + ": missing required key 'normal'" + line_of(r.table_node()));
      building(r.table_node(), [&] { builder_->add_plane(point, *normal, material, r.where(), motion); });
      j["point"] = to_json(point);
      j["normal"] = to_json(*normal);  // as given; the builder makes it unit
    } else if (type == "box") {
      const std::optional<Vec3> lo = r.vec3("min"), hi = r.vec3("max");
      if (!lo || !hi) throw SceneError(r.where() + ": a box wall needs 'min' and 'max'" + line_of(r.table_node()));
      if (!(hi->x > lo->x && hi->y > lo->y && hi->z > lo->z)) r.fail("max", "must exceed 'min' on every axis");
      const bool open_top = r.boolean("open_top", false);
      const Vec3 size = *hi - *lo;
      const Real thick = r.positive("thickness", 0.5 * std::fmin(size.x, std::fmin(size.y, size.z)));
      building(r.table_node(), [&] { builder_->add_box_walls(*lo, *hi, open_top, thick, material, r.where(), motion); });
      j["min"] = to_json(*lo);
      j["max"] = to_json(*hi);
      j["open_top"] = open_top;
      j["thickness"] = thick;
    } else if (type == "mesh") {
      const std::filesystem::path file = file_of(r, "file");
      const Vec3 position = r.vec3("position").value_or(Vec3{});
      const Quat rotation = r.rotation("rotation").value_or(Quat{});
      const Real scale = r.positive("scale", 1.0);
      TriangleMesh mesh;
      try {
        mesh = read_mesh(file);
      } catch (const MeshError& e) {
        r.fail("file", e.what());
      }
      scale_mesh(r, mesh, scale, Transform::from(position, rotation));
      Vec3 lo{1e300, 1e300, 1e300}, hi = -lo;
      for (const Vec3& v : mesh.vertices) lo = min(lo, v), hi = max(hi, v);
      const Real thick = r.positive("thickness", 0.01 * length(hi - lo));
      building(r.table_node(),
               [&] { builder_->add_mesh_walls(mesh.vertices, mesh.triangles, thick, material, r.where(), motion); });
      mesh_walls_.push_back({r.where() + " (" + file.filename().string() + ")", std::move(mesh), {lo, hi}, std::nullopt});
      j["file"] = file.string();
      j["position"] = to_json(position);
      j["rotation"] = to_json(rotation);
      j["scale"] = scale;
      j["thickness"] = thick;
    } else if (type == "cylinder") {
      dem::CylinderWall c;
      c.base = r.vec3("base").value_or(Vec3{});
      c.axis = r.vec3("axis").value_or(Vec3{0, 0, 1});
      c.radius = r.positive("radius");
      c.height = r.positive("height");
      c.bottom = r.boolean("bottom", true);
      c.top = r.boolean("top", false);
      const std::int64_t segments = r.integer("segments").value_or(dem::CylinderWall{}.segments);
      if (const std::string why = dem::cylinder_segments_problem(segments); !why.empty()) r.fail("segments", why);
      c.segments = static_cast<int>(segments);
      if (r.has("thickness")) c.thickness = r.positive("thickness");
      TriangleMesh mesh;
      building(r.table_node(), [&] {
        dem::cylinder_wall_mesh(c, r.where(), mesh.vertices, mesh.triangles);
        builder_->add_cylinder_walls(c, material, r.where(), motion);
      });
      Vec3 lo{1e300, 1e300, 1e300}, hi = -lo;
      for (const Vec3& v : mesh.vertices) lo = min(lo, v), hi = max(hi, v);
      mesh_walls_.push_back({r.where() + " (cylinder)", std::move(mesh), {lo, hi}, std::nullopt});
      j["base"] = to_json(c.base);
      j["axis"] = to_json(c.axis);
      j["radius"] = c.radius;
      j["height"] = c.height;
      j["bottom"] = c.bottom;
      j["top"] = c.top;
      j["segments"] = c.segments;
      j["thickness"] = dem::cylinder_wall_thickness(c);
    } else {
      r.fail("type", "must be \"plane\", \"box\", \"mesh\" or \"cylinder\", not \"" + type + "\"");
    }
    resolved_["wall"].push_back(j);
  }

  void warn_of_bodies_outside_containers(const std::string& who, const std::vector<std::uint32_t>& placed) {
    std::vector<Vec3> positions;
    for (const std::uint32_t b : placed) positions.push_back(builder_->position_of(b));
    for (std::string& w : bodies_outside_containers(mesh_walls_, who, positions)) scene_.warnings.push_back(std::move(w));
  }

  std::string source_;
  std::filesystem::path base_;
  Scene scene_;
  dem::WorldSettings settings_;
  std::optional<dem::WorldBuilder> builder_;
  Json resolved_;
  std::map<std::pair<std::string, Real>, std::shared_ptr<const Surface>> surfaces_;  ///< by file and scale
  std::map<std::string, NamedShape> named_shapes_;  ///< the [shapes] table, by name
  std::map<std::uint32_t, std::uint32_t> body_lines_;  // explicit bodies: index -> line
  bool accept_overlaps_ = false;
  std::uint64_t generator_count_ = 0;
  std::uint64_t inflow_count_ = 0;
  std::vector<ContainerWall> mesh_walls_;  // for warn_of_bodies_outside_containers
};

}  // namespace

Scene load_scene(std::string_view toml_text, const std::string& source, const std::filesystem::path& base_dir) {
  detail::check_key_depth(toml_text, source);
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    throw SceneError(source + ": " + std::string(e.description()) + " (line " +
                     std::to_string(e.source().begin.line) + ")");
  }
  return SceneBuilder(source, base_dir).build(root);
}

SceneShape read_scene_shape(std::string_view toml_inline_table, const std::filesystem::path& base_dir,
                            const std::string& where, std::uint64_t seed) {
  const std::string text = "shape = " + std::string(toml_inline_table);
  detail::check_key_depth(text, where);
  toml::table root;
  try {
    root = toml::parse(text, where);
  } catch (const toml::parse_error& e) {
    throw SceneError(where + ": " + std::string(e.description()));
  }
  const toml::table* t = root["shape"].as_table();
  if (!t) throw SceneError(where + ": a SHAPE is a table");
  return SceneBuilder(where, base_dir).one_shape(*t, where, seed);
}

std::string read_text_file(const std::filesystem::path& file) {
  std::optional<std::string> text = read_file(file);
  if (!text) throw SceneError("cannot read " + file.string());
  return std::move(*text);
}

Scene load_scene_file(const std::filesystem::path& file) {
  return load_scene(read_text_file(file), file.string(), file.has_parent_path() ? file.parent_path() : ".");
}

}  // namespace gjkdem::io
