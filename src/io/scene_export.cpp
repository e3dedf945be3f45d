#include "gjkdem/io/scene_export.hpp"

#include <cmath>
#include <sstream>

#include <toml++/toml.h>

#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/io/scene.hpp"

namespace gjkdem::io {
namespace {

namespace fs = std::filesystem;

toml::array array_of(const Vec3& v) { return toml::array{v.x, v.y, v.z}; }
toml::array array_of(const Quat& q) { return toml::array{q.w, q.x, q.y, q.z}; }

// A convex shape as a SHAPE table of the query format, its frame at `pose`
// in the body's frame.
toml::table shape_table(const Shape& s, const Transform& pose) {
  toml::table t;
  const Real m = s.margin;
  std::visit(
      [&](const auto& core) {
        using T = std::decay_t<decltype(core)>;
        if constexpr (std::is_same_v<T, Point>) {
          t.insert("type", "sphere"), t.insert("radius", m);
        } else if constexpr (std::is_same_v<T, Segment>) {
          t.insert("type", "capsule"), t.insert("p0", array_of(apply(pose, core.a)));
          t.insert("p1", array_of(apply(pose, core.b))), t.insert("radius", m);
        } else if constexpr (std::is_same_v<T, Triangle>) {
          toml::array points;
          for (const Vec3& v : core.v) points.push_back(array_of(apply(pose, v)));
          t.insert("type", "triangle"), t.insert("vertices", std::move(points));
        } else if constexpr (std::is_same_v<T, Polytope>) {
          toml::array points;
          for (const Vec3& v : core.data->vertices) points.push_back(array_of(apply(pose, v)));
          t.insert("type", "polytope"), t.insert("vertices", std::move(points));
        } else if constexpr (std::is_same_v<T, Box>) {
          t.insert("type", "box"), t.insert("half_extents", array_of(core.half_extents));
        } else if constexpr (std::is_same_v<T, Ellipsoid>) {
          t.insert("type", "ellipsoid"), t.insert("radii", array_of(core.radii));
        } else if constexpr (std::is_same_v<T, Cylinder> || std::is_same_v<T, Cone>) {
          t.insert("type", std::is_same_v<T, Cylinder> ? "cylinder" : "cone");
          t.insert("radius", core.radius), t.insert("half_height", core.half_height);
        } else if constexpr (std::is_same_v<T, Superellipsoid>) {
          t.insert("type", "superellipsoid"), t.insert("radii", array_of(core.radii));
          t.insert("exponents", toml::array{core.e1, core.e2});
        }
      },
      s.core);
  // Cores given by their points carry the pose in them; the others by centre and rotation.
  const bool by_points = std::holds_alternative<Segment>(s.core) || std::holds_alternative<Triangle>(s.core) ||
                         std::holds_alternative<Polytope>(s.core);
  if (!by_points) {
    t.insert("center", array_of(pose.translation));
    t.insert("rotation", array_of(quat_from_matrix(pose.rotation)));
  }
  if (m > 0 && !std::holds_alternative<Point>(s.core) && !std::holds_alternative<Segment>(s.core))
    t.insert("margin", m);
  return t;
}

// Triangles as the scene gives them (a surface's or a shell's), their
// vertices in their own frame.
toml::table triangles_table(const char* type, std::span<const Vec3> points, std::span<const TriangleIndices> tris) {
  toml::array vertices, triangles;
  for (const Vec3& v : points) vertices.push_back(array_of(v));
  for (const TriangleIndices& tri : tris)
    triangles.push_back(toml::array{std::int64_t{tri[0]}, std::int64_t{tri[1]}, std::int64_t{tri[2]}});
  toml::table out;
  out.insert("type", type), out.insert("vertices", std::move(vertices));
  out.insert("triangles", std::move(triangles));
  return out;
}

// A surface as the scene gives it, its vertices in its own frame; placed
// by `pose` where given (a compound's surface part).
toml::table surface_table(const Surface& s, const Transform* pose) {
  toml::table out = triangles_table("surface", s.vertices, s.triangles);
  if (pose) {
    out.insert("center", array_of(pose->translation));
    out.insert("rotation", array_of(quat_from_matrix(pose->rotation)));
  }
  return out;
}

// A template as the scene gives it, in its own shape frame.
toml::table template_table(const dem::ShapeTemplate& t) {
  if (t.surface_grain) return surface_table(*t.surface, nullptr);
  if (t.shell) {
    toml::table out = triangles_table("shell", t.shell->vertices, t.shell->triangles);
    out.insert("thickness", 2 * t.shell->margin);
    return out;
  }
  if (!t.parts.empty()) {
    toml::array parts;
    for (const dem::TemplatePart& p : t.parts)
      parts.push_back(p.surface_grain ? surface_table(*p.surface, &p.pose)
                                      : shape_table(p.given ? *p.given : p.shape, p.pose));
    toml::table out;
    out.insert("type", "compound"), out.insert("parts", std::move(parts));
    return out;
  }
  return shape_table(t.given ? *t.given : t.shape, Transform::identity());
}

// Every `file` key names a path relative to the scene's folder: made
// absolute, so the exported scene reads the same files from anywhere.
void absolute_files(toml::node& n, const fs::path& base) {
  if (toml::table* t = n.as_table()) {
    for (auto&& [key, value] : *t) {
      if (key.str() == "file" && value.is_string()) {
        const fs::path file = value.value<std::string>().value();
        if (file.is_relative()) value.as_string()->get() = fs::absolute(base / file).lexically_normal().string();
      } else {
        absolute_files(value, base);
      }
    }
  } else if (toml::array* a = n.as_array()) {
    for (toml::node& e : *a) absolute_files(e, base);
  }
}

}  // namespace

std::string export_scene(std::string_view scene_text, const fs::path& base_dir, const dem::World& w,
                         std::string_view header) {
  if (!w.bonds.empty())
    throw SceneError("a world of bonded assemblies cannot be written as a scene yet: its pieces would be written, "
                     "their bonds lost (continue the run with --resume, or start a new one from it with --from)");
  toml::table scene;
  try {
    scene = toml::parse(scene_text);
  } catch (const toml::parse_error& e) {
    throw SceneError(std::string("the scene to export is not valid TOML: ") + std::string(e.description()));
  }
  scene.erase("generator"), scene.erase("inflow");
  // Driven bodies stay as the scene gives them (their motions with them);
  // every other body, moving or fixed (a generator's rough floor), is the
  // world's. Wall pieces come from the scene's walls.
  if (toml::array* bodies = scene["body"].as_array()) {
    toml::array driven;
    for (toml::node& b : *bodies)
      if (const toml::table* t = b.as_table(); t && t->get("motion") && t->get("fixed") && t->get("fixed")->value_or(false))
        driven.push_back(b);
    if (driven.empty()) scene.erase("body");
    else scene.insert_or_assign("body", std::move(driven));
  }
  absolute_files(scene, base_dir);
  // A bed in contact overlaps its neighbours and walls a little: that is its start.
  if (toml::table* simulation = scene["simulation"].as_table()) simulation->insert_or_assign("initial_overlaps", "accept");

  if (w.cell.now.active()) {
    if (w.cell.now.tilt.x != 0 || w.cell.now.tilt.y != 0 || w.cell.now.tilt.z != 0)
      throw SceneError("a sheared periodic cell (tilt " + std::to_string(w.cell.now.tilt.x) + ", " +
                       std::to_string(w.cell.now.tilt.y) + ", " + std::to_string(w.cell.now.tilt.z) +
                       ") cannot be a scene's start yet");
    toml::table* periodic = scene["simulation"]["periodic"].as_table();
    const char* names[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a)
      if (w.cell.now.axes[a] && periodic) periodic->insert_or_assign(names[a], toml::array{w.cell.now.lo[a], w.cell.now.hi[a]});
  }

  toml::table* named = scene["shapes"].as_table();
  if (!named) named = scene.insert_or_assign("shapes", toml::table{}).first->second.as_table();
  std::vector<bool> written(w.templates.size());
  toml::array bodies = scene["body"].as_array() ? *scene["body"].as_array() : toml::array{};
  for (const dem::Body& b : w.bodies) {
    if (b.fixed && (b.group != 0 || b.motion != 0)) continue;
    const dem::ShapeTemplate& t = w.templates[b.shape];
    const std::string shape = "state_" + std::to_string(b.shape);
    if (!written[b.shape]) {
      if (named->contains(shape)) throw SceneError("the scene already has a shape named " + shape);
      named->insert(shape, template_table(t));
      written[b.shape] = true;
    }
    const Transform pose = dem::shape_pose(t, b);
    toml::table body;
    for (const dem::BodyName& n : w.names)
      if (n.id == b.id) body.insert("name", n.name);
    body.insert("shape", shape);
    body.insert("material", w.materials[b.material].name);
    body.insert("position", array_of(pose.translation));
    body.insert("rotation", array_of(quat_from_matrix(pose.rotation)));
    if (b.fixed) body.insert("fixed", true);
    Real values[dem::kMaxChannelComponents];
    for (const dem::BodyChannel& ch : dem::kBodyChannels) {
      if (!(ch.use & dem::kChannelExported) || !ch.in_outputs_of(w)) continue;
      // A fixed body takes no motion or load: only its other given channels.
      if (b.fixed && (!(ch.use & dem::kChannelGiven) || (ch.use & dem::kChannelLoad))) continue;
      ch.read(w, b, values);
      if (ch.components == 1) {
        body.insert(ch.name, values[0]);
      } else {
        toml::array a;
        for (std::uint32_t k = 0; k < ch.components; ++k) a.push_back(values[k]);
        body.insert(ch.name, std::move(a));
      }
    }
    bodies.push_back(std::move(body));
  }
  if (named->empty()) scene.erase("shapes");
  scene.insert_or_assign("body", std::move(bodies));

  std::ostringstream out;
  std::istringstream lines{std::string(header)};
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  out << toml::toml_formatter{scene} << "\n";
  return out.str();
}

}  // namespace gjkdem::io
