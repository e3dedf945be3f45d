// The scene reader's walls and motions (scene_reader.hpp): planes, boxes,
// meshes and cylinders, and the warning of bodies outside a container.
#include "scene_reader/scene_reader.hpp"

namespace gjkdem::io::detail {

std::uint32_t SceneReader::read_motion(TableReader& owner) {
  const toml::table* t = owner.table("motion");
  if (!t) return 0;
  TableReader r(*t, owner.where() + ".motion", owner, "motion");
  dem::PrescribedMotion m;
  m.center = r.vec3_or("center", Vec3{});
  m.velocity = r.vec3_or("velocity", Vec3{});
  m.angular_velocity = r.vec3_or("angular_velocity", Vec3{});
  if (const toml::table* v = r.table("vibration")) {
    TableReader vib(*v, r.where() + ".vibration", r, "vibration");
    const std::optional<Vec3> amplitude = vib.vec3("amplitude");
    if (!amplitude) throw SceneError(vib.where() + ": missing required key 'amplitude'" + line_of(*v));
    m.amplitude = *amplitude;
    m.frequency = vib.positive("frequency");
    m.phase = vib.number_or("phase", 0);
    vib.finish();
  }
  if (r.has("table")) {
    for (const std::vector<Real>& v : r.rows("table", 4, "[time, x, y, z] (seconds, metres)")) {
      if (!m.table_times.empty() && !(v[0] > m.table_times.back())) r.fail("table", "times must increase");
      m.table_times.push_back(v[0]);
      m.table_displacements.push_back({v[1], v[2], v[3]});
    }
  }
  r.finish();
  return building(*t, [&] { return builder_->add_motion(m, r.where()); });
}

void SceneReader::read_wall(TableReader& r) {
  const std::string type = r.required_string("type");
  const std::uint32_t material = material_of(r);
  const std::uint32_t motion = read_motion(r);
  if (type == "plane") {
    const Vec3 point = r.vec3_or("point", Vec3{});
    const std::optional<Vec3> normal = r.vec3("normal");
    if (!normal) throw SceneError(r.where() + ": missing required key 'normal'" + line_of(r.table_node()));
    building(r.table_node(), [&] { builder_->add_plane(point, *normal, material, r.where(), motion); });
  } else if (type == "box") {
    const std::optional<Vec3> lo = r.vec3("min"), hi = r.vec3("max");
    if (!lo || !hi) throw SceneError(r.where() + ": a box wall needs 'min' and 'max'" + line_of(r.table_node()));
    if (!(hi->x > lo->x && hi->y > lo->y && hi->z > lo->z)) r.fail("max", "must exceed 'min' on every axis");
    const bool open_top = r.boolean("open_top", false);
    const Vec3 size = *hi - *lo;
    const Real thick = r.positive("thickness", 0.5 * std::fmin(size.x, std::fmin(size.y, size.z)));
    building(r.table_node(), [&] { builder_->add_box_walls(*lo, *hi, open_top, thick, material, r.where(), motion); });
  } else if (type == "mesh") {
    const std::filesystem::path file = file_of(r, "file");
    const Vec3 position = r.vec3_or("position", Vec3{});
    const Quat rotation = r.rotation_or("rotation", Quat{});
    const Real scale = r.positive("scale", 1.0);
    TriangleMesh mesh;
    try {
      mesh = read_mesh(file);
      refuse_uncut_polygons(mesh);
    } catch (const MeshError& e) {
      r.fail("file", e.what());
    }
    scale_mesh(r, mesh, scale, Transform::from(position, rotation));
    // An STL facet whose corners weld into fewer than three vertices has no
    // area and holds nothing (CAD files have such slivers): left out, said.
    const std::size_t facets = mesh.triangles.size();
    std::erase_if(mesh.triangles, repeats_a_vertex);
    if (mesh.triangles.size() < facets)
      scene_.warnings.push_back(r.where() + ": " + std::to_string(facets - mesh.triangles.size()) + " triangles of " +
                                file.filename().string() + " name a vertex twice (no area): left out");
    Vec3 lo{1e300, 1e300, 1e300}, hi = -lo;
    for (const Vec3& v : mesh.vertices) lo = min(lo, v), hi = max(hi, v);
    const Real thick = r.positive("thickness", 0.01 * length(hi - lo));
    building(r.table_node(),
             [&] { builder_->add_mesh_walls(mesh.vertices, mesh.triangles, thick, material, r.where(), motion); });
    mesh_walls_.push_back({r.where() + " (" + file.filename().string() + ")", std::move(mesh), {lo, hi}, std::nullopt});
  } else if (type == "cylinder") {
    dem::CylinderWall c;
    c.base = r.vec3_or("base", Vec3{});
    c.axis = r.vec3_or("axis", Vec3{0, 0, 1});
    c.radius = r.positive("radius");
    c.height = r.positive("height");
    c.bottom = r.boolean("bottom", true);
    c.top = r.boolean("top", false);
    const std::int64_t segments = r.integer_or("segments", dem::CylinderWall{}.segments);
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
    r.record("thickness", dem::cylinder_wall_thickness(c));  // its default made from the radius
  } else {
    r.fail("type", "must be \"plane\", \"box\", \"mesh\" or \"cylinder\", not \"" + type + "\"");
  }
}

void SceneReader::warn_of_bodies_outside_containers(const std::string& who, const std::vector<std::uint32_t>& placed) {
  std::vector<Vec3> positions;
  for (const std::uint32_t b : placed) positions.push_back(builder_->position_of(b));
  for (std::string& w : bodies_outside_containers(mesh_walls_, who, positions)) scene_.warnings.push_back(std::move(w));
}

}  // namespace gjkdem::io::detail
