// Scene files (TOML, read with toml++) into a World. Every key is checked:
// unknown keys, wrong types and out-of-range values are refused with the key's
// line, before anything runs.
#include "gjkdem/io/scene.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/dem/generators.hpp"
#include "gjkdem/dem/half_space.hpp"
#include "gjkdem/io/mesh.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/tessellate.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::io {
namespace {

using Json = nlohmann::ordered_json;
using dem::Body;
using dem::World;

// Plane walls get ids above every body's, so that contact histories (kept by
// the smaller id) stay with the particle.
constexpr std::uint64_t kPlaneIdBase = std::uint64_t{1} << 62;
// Directions of the tessellation of curved shapes under the volume law.
constexpr int kDefaultTessellation = 96;

std::string line_of(const toml::node& n) {
  const auto line = n.source().begin.line;
  return line > 0 ? " (line " + std::to_string(line) + ")" : "";
}

// Reads one table: typed getters, then finish() refuses the keys nobody asked for.
class TableReader {
 public:
  TableReader(const toml::table& t, std::string where) : table_(t), where_(std::move(where)) {}

  const std::string& where() const { return where_; }
  const toml::node* find(const std::string& key) {
    used_.insert(key);
    return table_.get(key);
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const toml::node* n = table_.get(key);
    throw SceneError(where_ + "." + key + ": " + what + (n ? line_of(*n) : line_of(table_)));
  }
  bool has(const std::string& key) const { return table_.contains(key); }

  std::optional<Real> number(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    if (!n->is_number()) fail(key, "must be a number");
    const Real v = n->value<double>().value();
    if (!std::isfinite(v)) fail(key, "must be finite");
    return v;
  }
  Real required_number(const std::string& key) {
    const auto v = number(key);
    if (!v) throw SceneError(where_ + ": missing required key '" + key + "'" + line_of(table_));
    return *v;
  }
  Real positive(const std::string& key, std::optional<Real> fallback = std::nullopt) {
    const auto v = number(key);
    if (!v && fallback) return *fallback;
    if (!v) throw SceneError(where_ + ": missing required key '" + key + "'" + line_of(table_));
    if (!(*v > 0)) fail(key, "must be > 0");
    return *v;
  }
  std::optional<std::int64_t> integer(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    if (!n->is_integer()) fail(key, "must be an integer");
    return n->value<std::int64_t>().value();
  }
  std::optional<std::string> string(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(key, "must be a string");
    return n->value<std::string>().value();
  }
  std::string required_string(const std::string& key) {
    const auto v = string(key);
    if (!v) throw SceneError(where_ + ": missing required key '" + key + "'" + line_of(table_));
    return *v;
  }
  bool boolean(const std::string& key, bool fallback) {
    const toml::node* n = find(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, "must be true or false");
    return n->value<bool>().value();
  }
  std::vector<Real> numbers(const std::string& key, std::size_t count) {
    const toml::node* n = find(key);
    const toml::array* a = n ? n->as_array() : nullptr;
    if (n && !a) fail(key, "must be an array of " + std::to_string(count) + " numbers");
    if (!a) return {};
    if (a->size() != count) fail(key, "must have " + std::to_string(count) + " numbers");
    std::vector<Real> out;
    for (const toml::node& e : *a) {
      if (!e.is_number()) fail(key, "must hold numbers only");
      out.push_back(e.value<double>().value());
      if (!std::isfinite(out.back())) fail(key, "must be finite");
    }
    return out;
  }
  std::optional<Vec3> vec3(const std::string& key) {
    const auto v = numbers(key, 3);
    if (v.empty()) return std::nullopt;
    return Vec3{v[0], v[1], v[2]};
  }
  std::optional<Quat> rotation(const std::string& key) {
    const auto v = numbers(key, 4);
    if (v.empty()) return std::nullopt;
    const Quat q{v[0], v[1], v[2], v[3]};
    const Real norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (std::fabs(norm - 1) > kUnitQuaternionTol) fail(key, "must be a unit quaternion [w, x, y, z]");
    return normalized(q);
  }
  const toml::table* table(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(key, "must be a table, e.g. { type = \"box\", ... }");
    return n->as_table();
  }
  void finish() const {
    for (const auto& [k, v] : table_)
      if (!used_.count(std::string(k.str())))
        throw SceneError(where_ + ": unknown key '" + std::string(k.str()) + "'" + line_of(v));
  }

 private:
  const toml::table& table_;
  std::string where_;
  std::set<std::string> used_;
};

Json to_json(const Vec3& v) { return Json::array({v.x, v.y, v.z}); }
Json to_json(const Quat& q) { return Json::array({q.w, q.x, q.y, q.z}); }

// A shape read from a SHAPE table: its core in a local frame and that frame's
// pose in the body's frame.
struct ShapeSpec {
  Shape shape;
  Transform pose;
  Real diameter = 0;  // of a sphere about the body frame's origin holding it
};

class SceneBuilder {
 public:
  SceneBuilder(const std::string& source, std::filesystem::path base) : source_(source), base_(std::move(base)) {}

  Scene build(const toml::table& root) {
    TableReader top(root, source_);
    read_simulation(top);
    read_output(top);
    read_contact(top);
    for_each_table(top, "material", [&](TableReader& r) { read_material(r); });
    for_each_table(top, "wall", [&](TableReader& r) { read_wall(r); });
    for_each_table(top, "body", [&](TableReader& r) { read_body(r); });
    check_explicit_bodies();
    for_each_table(top, "generator", [&](TableReader& r) { read_generator(r); });
    top.finish();
    if (scene_.world.bodies.empty() || std::all_of(scene_.world.bodies.begin(), scene_.world.bodies.end(),
                                                   [](const Body& b) { return b.fixed; }))
      throw SceneError(source_ + ": the scene has no moving body (add a [[body]] or a [[generator]])");
    prepare_for_volume_law();
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
    scene_.world.gravity = r.vec3("gravity").value_or(Vec3{0, 0, -9.81});
    const std::int64_t threads = r.integer("threads").value_or(0);
    if (threads < 0 || threads > 4096) r.fail("threads", "must be 0 (all cores) or a thread count");
    scene_.world.threads = static_cast<int>(threads);
    const std::int64_t seed = r.integer("seed").value_or(1);
    if (seed < 0) r.fail("seed", "must be >= 0");
    scene_.seed = static_cast<std::uint64_t>(seed);
    r.finish();
    resolved_["simulation"] = {{"duration", scene_.duration}, {"gravity", to_json(scene_.world.gravity)},
                               {"threads", threads}, {"seed", seed}};
  }

  void read_output(TableReader& top) {
    scene_.output_every = scene_.duration / 100;
    if (const toml::table* t = sub_table(top, "output")) {
      TableReader r(*t, "output");
      scene_.output_dir = r.string("dir").value_or("out");
      if (scene_.output_dir.empty()) r.fail("dir", "must not be empty");
      scene_.output_every = r.positive("every", scene_.output_every);
      scene_.overwrite = r.boolean("overwrite", false);
      const std::int64_t every = r.integer("checkpoint_every").value_or(10);
      if (every < 0) r.fail("checkpoint_every", "must be >= 0 (0: no checkpoints)");
      scene_.checkpoint_every = static_cast<int>(every);
      scene_.write_frames = r.boolean("frames", true);
      r.finish();
    }
    resolved_["output"] = {{"dir", scene_.output_dir}, {"every", scene_.output_every},
                           {"overwrite", scene_.overwrite}, {"checkpoint_every", scene_.checkpoint_every},
                           {"frames", scene_.write_frames}};
  }

  void read_contact(TableReader& top) {
    std::string model = "volume", form = "normalized";
    World& w = scene_.world;
    if (const toml::table* t = sub_table(top, "contact")) {
      TableReader r(*t, "contact");
      model = r.string("model").value_or("volume");
      if (model == "volume") w.model = dem::ContactModel::Volume;
      else if (model == "hertz") w.model = dem::ContactModel::Hertz;
      else if (model == "linear") w.model = dem::ContactModel::Linear;
      else r.fail("model", "must be \"volume\", \"hertz\" or \"linear\", not \"" + model + "\"");
      w.volume_stiffness = r.positive("volume_stiffness", 0.0);
      form = r.string("volume_form").value_or("normalized");
      if (form == "normalized") w.volume_form = dem::VolumeForm::Normalized;
      else if (form == "potential") w.volume_form = dem::VolumeForm::Potential;
      else r.fail("volume_form", "must be \"normalized\" or \"potential\", not \"" + form + "\"");
      w.linear_stiffness = r.positive("linear_stiffness", 0.0);
      w.rocking_resistance = r.boolean("rocking_resistance", true);
      const std::int64_t dirs = r.integer("tessellation").value_or(kDefaultTessellation);
      if (dirs < 8 || dirs > 100000) r.fail("tessellation", "must be between 8 and 100000 directions");
      tessellation_ = static_cast<int>(dirs);
      r.finish();
    } else {
      w.model = dem::ContactModel::Volume;
    }
    resolved_["contact"] = {{"model", model}, {"volume_form", form},
                            {"rocking_resistance", w.rocking_resistance}, {"tessellation", tessellation_}};
    if (w.volume_stiffness > 0) resolved_["contact"]["volume_stiffness"] = w.volume_stiffness;
    if (w.linear_stiffness > 0) resolved_["contact"]["linear_stiffness"] = w.linear_stiffness;
  }

  void read_material(TableReader& r) {
    dem::Material m;
    m.name = r.required_string("name");
    if (materials_.count(m.name)) r.fail("name", "material '" + m.name + "' is defined twice");
    m.density = r.positive("density");
    m.youngs_modulus = r.positive("youngs_modulus");
    m.poisson_ratio = r.number("poisson_ratio").value_or(0.25);
    if (!(m.poisson_ratio > -1 && m.poisson_ratio < 0.5)) r.fail("poisson_ratio", "must lie in (-1, 0.5)");
    m.restitution = r.number("restitution").value_or(0.5);
    if (!(m.restitution > 0 && m.restitution <= 1)) r.fail("restitution", "must lie in (0, 1]");
    m.friction = r.number("friction").value_or(0.5);
    if (!(m.friction >= 0)) r.fail("friction", "must be >= 0");
    materials_[m.name] = static_cast<std::uint32_t>(scene_.world.materials.size());
    scene_.world.materials.push_back(m);
    resolved_["material"].push_back({{"name", m.name}, {"density", m.density}, {"youngs_modulus", m.youngs_modulus},
                                     {"poisson_ratio", m.poisson_ratio}, {"restitution", m.restitution},
                                     {"friction", m.friction}});
  }

  std::uint32_t material_of(TableReader& r) {
    const std::string name = r.required_string("material");
    const auto it = materials_.find(name);
    if (it == materials_.end()) r.fail("material", "no [[material]] is named '" + name + "'");
    return it->second;
  }

  std::filesystem::path file_of(TableReader& r, const std::string& key) {
    const std::filesystem::path f = base_ / r.required_string(key);
    if (!std::filesystem::exists(f)) r.fail(key, "file not found: " + f.string());
    return f;
  }

  Polytope mesh_hull(TableReader& r, Real scale) {
    const std::filesystem::path file = file_of(r, "file");
    try {
      TriangleMesh mesh = read_mesh(file);
      for (Vec3& v : mesh.vertices) v *= scale;
      ConvexMesh c = convex_from_mesh(mesh, file.string());
      for (std::string& w : c.warnings) scene_.warnings.push_back(r.where() + ": " + w);
      return c.polytope;
    } catch (const MeshError& e) {
      r.fail("file", e.what());
    }
  }

  // A SHAPE table: the types of query-format.md, plus platonic and mesh, and
  // for generators random_polyhedron (drawn per variant by the caller).
  ShapeSpec read_shape(TableReader& owner, const std::string& key) {
    const toml::table* t = owner.table(key);
    if (!t) throw SceneError(owner.where() + ": missing required key '" + key + "'");
    TableReader r(*t, owner.where() + "." + key);
    const std::string type = r.required_string("type");
    ShapeSpec s;
    if (type == "platonic") {
      const std::string name = r.required_string("name");
      const Real size = r.positive("size");
      try {
        s.shape = dem::platonic(name, size);
      } catch (const std::invalid_argument& e) {
        r.fail("name", e.what());
      }
      r.finish();
    } else if (type == "mesh") {
      const Real scale = r.positive("scale", 1.0);
      s.shape = Shape{mesh_hull(r, scale)};
      r.finish();
    } else {
      std::ostringstream json;
      json << toml::json_formatter{*t};
      try {
        const PlacedInput p = parse_shape(json.str());
        s.shape = p.shape;
        s.pose = p.pose;
      } catch (const std::exception& e) {
        throw SceneError(owner.where() + "." + key + ": " + e.what() + line_of(*t));
      }
    }
    s.diameter = 2 * (length(s.pose.translation) + bounding_radius(s.shape));
    return s;
  }

  dem::ShapeTemplate make_particle(const Shape& shape, TableReader& r) {
    try {
      return dem::make_template(shape);
    } catch (const std::invalid_argument& e) {
      r.fail("shape", std::string("cannot be a particle: ") + e.what());
    }
  }

  // A body whose author frame sits at (position, rotation), holding `s`.
  void place_body(Body& b, const ShapeSpec& s, const Vec3& position, const Quat& rotation, const Vec3& velocity,
                  const Vec3& spin) {
    const World& w = scene_.world;
    const dem::ShapeTemplate& t = w.templates[b.shape];
    const Transform author = Transform::from(position, rotation);
    const Quat shape_q = rotation * quat_from_matrix(s.pose.rotation);
    b.orientation = normalized(shape_q * t.principal.rotation);
    b.position = apply(author, apply(s.pose, t.unit_mass.centroid));
    b.velocity = velocity;
    if (!b.fixed) {  // L = R I R^T w, with I the principal moments
      const Vec3 moments = t.principal.moments * w.materials[b.material].density;
      const Vec3 local = rotate(conjugate(b.orientation), spin);
      b.angular_momentum = rotate(b.orientation, Vec3{moments.x * local.x, moments.y * local.y, moments.z * local.z});
    }
  }

  void read_body(TableReader& r) {
    Body b;
    b.id = next_id_++;
    const std::optional<std::string> name = r.string("name");
    const ShapeSpec s = read_shape(r, "shape");
    b.material = material_of(r);
    b.fixed = r.boolean("fixed", false);
    const Vec3 position = r.vec3("position").value_or(Vec3{});
    const Quat rotation = r.rotation("rotation").value_or(Quat{});
    const Vec3 velocity = r.vec3("velocity").value_or(Vec3{});
    const Vec3 spin = r.vec3("angular_velocity").value_or(Vec3{});
    if (b.fixed && (length(velocity) > 0 || length(spin) > 0))
      r.fail("velocity", "a fixed body cannot move (velocity and angular_velocity must be 0)");
    // Fixed bodies have no mass: their template's principal frame is the shape's.
    scene_.world.templates.push_back(b.fixed ? dem::make_wall_template(s.shape) : make_particle(s.shape, r));
    b.shape = static_cast<std::uint32_t>(scene_.world.templates.size() - 1);
    place_body(b, s, position, rotation, velocity, spin);
    const std::uint32_t index = static_cast<std::uint32_t>(scene_.world.bodies.size());
    if (name) {
      if (names_.count(*name)) r.fail("name", "two bodies are named '" + *name + "'");
      names_.insert(*name);
      scene_.traced.push_back({*name, index});
    }
    explicit_.push_back({index, r.where()});
    scene_.world.bodies.push_back(b);
    Json j = {{"shape", "(as given)"}, {"material", scene_.world.materials[b.material].name},
              {"position", to_json(position)}, {"rotation", to_json(rotation)}, {"velocity", to_json(velocity)},
              {"angular_velocity", to_json(spin)}, {"fixed", b.fixed}};
    if (name) j["name"] = *name;
    resolved_["body"].push_back(j);
  }

  // Explicit moving bodies must not overlap each other, fixed bodies or planes
  // (touching is fine: stacks start touching).
  void check_explicit_bodies() {
    const World& w = scene_.world;
    for (std::size_t i = 0; i < explicit_.size(); ++i) {
      const Body& a = w.bodies[explicit_[i].first];
      const Shape& sa = w.templates[a.shape].shape;
      const Transform pa = dem::shape_pose(w, a);
      const Real tol = 1e-9 * bounding_radius(sa);
      for (const dem::PlaneWall& p : w.planes)
        if (!a.fixed && dem::half_space_contact(sa, pa, p.point, p.normal).depth > tol)
          throw SceneError(explicit_[i].second + " starts inside a plane wall");
      for (std::size_t j = 0; j < w.bodies.size(); ++j) {
        const Body& b = w.bodies[j];
        if (j == explicit_[i].first || (a.fixed && b.fixed)) continue;
        if (!b.fixed && j < explicit_[i].first) continue;  // that pair was checked from the other side
        const Shape& sb = w.templates[b.shape].shape;
        const PenetrationResult pr = penetration(sa, pa, sb, dem::shape_pose(w, b));
        if (pr.intersect && pr.depth > tol) {
          std::string other = "a wall";
          for (const auto& [k, where] : explicit_)
            if (k == j) other = where;
          throw SceneError(explicit_[i].second + " overlaps " + other + " by " + std::to_string(pr.depth) +
                           " m at the start");
        }
      }
    }
  }

  void read_generator(TableReader& r) {
    const std::int64_t count = r.integer("count").value_or(-1);
    if (count <= 0 || count > 100'000'000) r.fail("count", "must be a positive integer");
    const std::uint32_t material = material_of(r);
    const toml::table* region_table = r.table("region");
    if (!region_table) throw SceneError(r.where() + ": missing required key 'region'" );
    TableReader region(*region_table, r.where() + ".region");
    const Vec3 lo = region.vec3("min").value_or(Vec3{}), hi = region.vec3("max").value_or(Vec3{});
    if (!region.has("min") || !region.has("max")) throw SceneError(region.where() + ": needs 'min' and 'max'" + line_of(*region_table));
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) region.fail("max", "must exceed 'min' on every axis");
    region.finish();
    const Vec3 velocity = r.vec3("velocity").value_or(Vec3{});
    const std::int64_t variants = r.integer("variants").value_or(std::min<std::int64_t>(count, 50));
    if (variants <= 0) r.fail("variants", "must be a positive integer");
    std::mt19937_64 rng(scene_.seed * 1000003 + generator_count_++);

    // The shapes: random polyhedra come in `variants` draws, shared by the bodies.
    std::vector<ShapeSpec> shapes;
    const toml::table* st = r.table("shape");
    if (!st) throw SceneError(r.where() + ": missing required key 'shape'");
    Json shape_json;
    if (st->get("type") && st->get("type")->value<std::string>() == std::optional<std::string>("random_polyhedron")) {
      TableReader s(*st, r.where() + ".shape");
      s.required_string("type");
      const std::int64_t vertices = s.integer("vertices").value_or(12);
      if (vertices < 4 || vertices > 10000) s.fail("vertices", "must be between 4 and 10000");
      Real size_lo, size_hi;
      if (const toml::node* n = s.find("size"); n && n->is_number()) {
        size_lo = size_hi = s.positive("size");
      } else {
        const std::vector<Real> range = s.numbers("size", 2);
        if (range.empty()) throw SceneError(s.where() + ": missing required key 'size'" + line_of(*st));
        size_lo = range[0];
        size_hi = range[1];
        if (!(size_lo > 0 && size_hi >= size_lo)) s.fail("size", "must be [min, max] with 0 < min <= max");
      }
      s.finish();
      std::uniform_real_distribution<double> draw(size_lo, size_hi);
      for (std::int64_t k = 0; k < variants; ++k) {
        ShapeSpec spec;
        spec.shape = dem::random_polyhedron(static_cast<int>(vertices), draw(rng), rng);
        spec.diameter = 2 * bounding_radius(spec.shape);
        shapes.push_back(spec);
      }
      shape_json = {{"type", "random_polyhedron"}, {"vertices", vertices}, {"size", {size_lo, size_hi}},
                    {"variants", variants}};
    } else {
      shapes.push_back(read_shape(r, "shape"));
      std::ostringstream json;
      json << toml::json_formatter{*st};
      shape_json = Json::parse(json.str());
    }
    const std::uint32_t first_template = static_cast<std::uint32_t>(scene_.world.templates.size());
    Real diameter = 0;
    for (const ShapeSpec& s : shapes) {
      scene_.world.templates.push_back(make_particle(s.shape, r));
      diameter = std::fmax(diameter, s.diameter);
    }
    const std::vector<dem::Placement> spots =
        dem::place_in_region(scene_.world, lo, hi, diameter, static_cast<std::size_t>(count), rng);
    if (spots.size() < static_cast<std::size_t>(count))
      throw SceneError(r.where() + ": the region holds only " + std::to_string(spots.size()) + " of the " +
                       std::to_string(count) + " bodies (each needs a free cube of side " + std::to_string(diameter) +
                       " m); enlarge 'region' or lower 'count'" + line_of(*region_table));
    std::uniform_int_distribution<std::size_t> pick(0, shapes.size() - 1);
    for (const dem::Placement& p : spots) {
      Body b;
      b.id = next_id_++;
      const std::size_t v = pick(rng);
      b.shape = first_template + static_cast<std::uint32_t>(v);
      b.material = material;
      place_body(b, shapes[v], p.position - rotate(p.rotation, shapes[v].pose.translation), p.rotation, velocity, {});
      scene_.world.bodies.push_back(b);
    }
    resolved_["generator"].push_back({{"count", count}, {"shape", shape_json},
                                      {"material", scene_.world.materials[material].name},
                                      {"region", {{"min", to_json(lo)}, {"max", to_json(hi)}}},
                                      {"velocity", to_json(velocity)}, {"variants", variants}});
  }

  void read_wall(TableReader& r) {
    World& w = scene_.world;
    const std::string type = r.required_string("type");
    const std::uint32_t material = material_of(r);
    Json j = {{"type", type}, {"material", w.materials[material].name}};
    if (type == "plane") {
      const Vec3 point = r.vec3("point").value_or(Vec3{});
      const std::optional<Vec3> normal = r.vec3("normal");
      if (!normal) throw SceneError(r.where() + ": missing required key 'normal'");
      if (!(length(*normal) > 0)) r.fail("normal", "must not be zero");
      w.planes.push_back({kPlaneIdBase + w.planes.size(), point, normalized(*normal), material});
      j["point"] = to_json(point);
      j["normal"] = to_json(normalized(*normal));
    } else if (type == "box") {
      const std::optional<Vec3> lo = r.vec3("min"), hi = r.vec3("max");
      if (!lo || !hi) throw SceneError(r.where() + ": a box wall needs 'min' and 'max'");
      if (!(hi->x > lo->x && hi->y > lo->y && hi->z > lo->z)) r.fail("max", "must exceed 'min' on every axis");
      const bool open_top = r.boolean("open_top", false);
      const Vec3 size = *hi - *lo;
      const Real thick = r.positive("thickness", 0.5 * std::fmin(size.x, std::fmin(size.y, size.z)));
      add_box_walls(*lo, *hi, open_top, thick, material);
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
      Vec3 lo{1e300, 1e300, 1e300}, hi = -lo;
      for (Vec3& v : mesh.vertices) {
        v = apply(Transform::from(position, rotation), v * scale);
        lo = min(lo, v);
        hi = max(hi, v);
      }
      const Real thick = r.positive("thickness", 0.01 * length(hi - lo));
      add_mesh_walls(mesh, thick, material);
      j["file"] = file.string();
      j["position"] = to_json(position);
      j["rotation"] = to_json(rotation);
      j["scale"] = scale;
      j["thickness"] = thick;
    } else {
      r.fail("type", "must be \"plane\", \"box\" or \"mesh\", not \"" + type + "\"");
    }
    resolved_["wall"].push_back(j);
  }

  void add_fixed(const Shape& shape, const Vec3& position, std::uint32_t material, std::uint32_t group) {
    World& w = scene_.world;
    w.templates.push_back(dem::make_wall_template(shape));
    Body b;
    b.id = next_id_++;
    b.shape = static_cast<std::uint32_t>(w.templates.size() - 1);
    b.material = material;
    b.group = group;
    b.fixed = true;
    b.position = position;
    w.bodies.push_back(b);
  }

  // A box container: one slab per side, outside [lo, hi], the slabs of the
  // floor and roof spanning the side slabs so the corners are closed.
  void add_box_walls(const Vec3& lo, const Vec3& hi, bool open_top, Real t, std::uint32_t material) {
    const std::uint32_t group = ++groups_;
    const Vec3 c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
    add_fixed(Shape{Box{{h.x + 2 * t, h.y + 2 * t, t / 2}}}, {c.x, c.y, lo.z - t / 2}, material, group);
    if (!open_top) add_fixed(Shape{Box{{h.x + 2 * t, h.y + 2 * t, t / 2}}}, {c.x, c.y, hi.z + t / 2}, material, group);
    add_fixed(Shape{Box{{t / 2, h.y + t, h.z}}}, {lo.x - t / 2, c.y, c.z}, material, group);
    add_fixed(Shape{Box{{t / 2, h.y + t, h.z}}}, {hi.x + t / 2, c.y, c.z}, material, group);
    add_fixed(Shape{Box{{h.x, t / 2, h.z}}}, {c.x, lo.y - t / 2, c.z}, material, group);
    add_fixed(Shape{Box{{h.x, t / 2, h.z}}}, {c.x, hi.y + t / 2, c.z}, material, group);
  }

  // Mesh walls: one fixed body per triangle. The penetration laws see the
  // seed's triangle with a margin (thickness / 2 on each side); the volume law
  // sees the prism of that thickness, so the pieces of a flat region tile it
  // and their overlap volumes add up exactly.
  void add_mesh_walls(const TriangleMesh& mesh, Real thick, std::uint32_t material) {
    const std::uint32_t group = ++groups_;
    for (const auto& tri : mesh.triangles) {
      const Vec3 a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
      const Vec3 n3 = cross(b - a, c - a);
      if (!(length(n3) > 0)) continue;  // degenerate triangles hold nothing
      const Vec3 centre = (a + b + c) / 3.0, n = normalized(n3) * (thick / 2);
      Shape shape;
      if (scene_.world.model == dem::ContactModel::Volume) {
        const Vec3 prism[6] = {a - centre + n, b - centre + n, c - centre + n,
                               a - centre - n, b - centre - n, c - centre - n};
        shape = Shape{make_polytope(prism)};
      } else {
        shape = Shape{Triangle{{a - centre, b - centre, c - centre}}, thick / 2};
      }
      add_fixed(shape, centre, material, group);
    }
  }

  // The volume law clips polytopes: curved moving shapes get an inscribed
  // tessellation for contacts (their mass properties stay exact).
  void prepare_for_volume_law() {
    World& w = scene_.world;
    if (w.model != dem::ContactModel::Volume) return;
    std::vector<bool> moving(w.templates.size(), false);
    for (const Body& b : w.bodies)
      if (!b.fixed) moving[b.shape] = true;
    for (std::size_t t = 0; t < w.templates.size(); ++t) {
      Shape& s = w.templates[t].shape;
      const bool clipped = s.margin == 0 && (std::holds_alternative<Polytope>(s.core) || std::holds_alternative<Box>(s.core));
      const bool sphere = std::holds_alternative<Point>(s.core);
      if (clipped || (!moving[t] && !sphere)) continue;
      if (sphere && !moving[t]) continue;
      s = Shape{tessellate(s, tessellation_).polytope};
    }
  }

  std::string source_;
  std::filesystem::path base_;
  Scene scene_;
  Json resolved_;
  std::map<std::string, std::uint32_t> materials_;
  std::set<std::string> names_;
  std::vector<std::pair<std::uint32_t, std::string>> explicit_;  // explicit bodies and where they were given
  std::uint64_t next_id_ = 0;
  std::uint32_t groups_ = 0;
  std::uint64_t generator_count_ = 0;
  int tessellation_ = kDefaultTessellation;
};

}  // namespace

Scene load_scene(std::string_view toml_text, const std::string& source, const std::filesystem::path& base_dir) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    throw SceneError(source + ": " + std::string(e.description()) + " (line " +
                     std::to_string(e.source().begin.line) + ")");
  }
  return SceneBuilder(source, base_dir).build(root);
}

Scene load_scene_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError("cannot read scene file " + file.string());
  std::stringstream text;
  text << in.rdbuf();
  return load_scene(text.str(), file.string(), file.has_parent_path() ? file.parent_path() : ".");
}

}  // namespace gjkdem::io
