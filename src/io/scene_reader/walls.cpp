// The scene reader's walls and motions (scene_reader.hpp): planes, boxes,
// meshes and cylinders, and the warning of bodies outside a container.
#include "scene_reader/scene_reader.hpp"

namespace gjkdem::io::detail {

std::uint32_t SceneReader::read_motion(TableReader& owner, Json& j) {
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

void SceneReader::read_wall(TableReader& r) {
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

void SceneReader::warn_of_bodies_outside_containers(const std::string& who, const std::vector<std::uint32_t>& placed) {
  std::vector<Vec3> positions;
  for (const std::uint32_t b : placed) positions.push_back(builder_->position_of(b));
  for (std::string& w : bodies_outside_containers(mesh_walls_, who, positions)) scene_.warnings.push_back(std::move(w));
}

}  // namespace gjkdem::io::detail
