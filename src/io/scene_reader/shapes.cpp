// The scene reader's shapes (scene_reader.hpp): SHAPE tables, meshes and
// surfaces from files or inline, compounds, shells and the [shapes] table.
#include "scene_reader/scene_reader.hpp"

namespace gjkdem::io::detail {

std::filesystem::path SceneReader::file_of(TableReader& r, const std::string& key) {
  const std::filesystem::path f = base_ / r.required_string(key);
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(f, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    r.fail(key, "cannot read " + f.string() + " (" + ec.message() + ")");
  if (!std::filesystem::exists(status)) r.fail(key, "file not found: " + f.string());
  if (!std::filesystem::is_regular_file(status)) r.fail(key, f.string() + " is not a regular file");
  return f;
}

void SceneReader::scale_mesh(TableReader& r, TriangleMesh& mesh, Real scale, const Transform& place) {
  Real extent = 0;
  for (const Vec3& v : mesh.vertices) extent = std::fmax(extent, max_abs(v));
  if (!mesh.vertices.empty() && !(extent * scale >= kMinMeshSize))
    r.fail("scale", "shrinks the mesh below 1e-100 m (not resolvable)");
  for (Vec3& v : mesh.vertices) {
    v = apply(place, v * scale);
    if (!(max_abs(v) <= kMaxCoordinate)) r.fail("scale", "puts the mesh beyond 1e100 m (not resolvable)");
  }
}

Polytope SceneReader::mesh_hull(TableReader& r, Real scale) {
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

std::shared_ptr<const Surface> SceneReader::mesh_surface(TableReader& r, Real scale) {
  if (!r.has("file")) return inline_surface(r, scale);
  if (r.has("vertices") || r.has("triangles")) r.fail("file", "give either a 'file' or 'vertices' and 'triangles'");
  const std::filesystem::path file = file_of(r, "file");
  std::shared_ptr<const Surface>& known = surfaces_[{file.string(), scale}];
  if (known) return known;
  try {
    TriangleMesh mesh = read_mesh(file);
    refuse_uncut_polygons(mesh);
    scale_mesh(r, mesh, scale);
    known = std::make_shared<const Surface>(make_surface(std::move(mesh.vertices), std::move(mesh.triangles)));
    return known;
  } catch (const MeshError& e) {
    r.fail("file", e.what());
  } catch (const SurfaceError& e) {
    r.fail("file", file.string() + " is not a closed surface a grain can have: " + e.what());
  }
}

std::shared_ptr<const Surface> SceneReader::inline_surface(TableReader& r, Real scale) {
  TriangleMesh mesh = inline_triangles(r, scale, "a surface");
  try {
    return std::make_shared<const Surface>(make_surface(std::move(mesh.vertices), std::move(mesh.triangles)));
  } catch (const SurfaceError& e) {
    r.fail("triangles", std::string("not a closed surface a grain can have: ") + e.what());
  }
}

TriangleMesh SceneReader::inline_triangles(TableReader& r, Real scale, const std::string& what) {
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

std::shared_ptr<const Shell> SceneReader::mesh_shell(TableReader& r, Real scale) {
  const Real thickness = r.positive("thickness");
  TriangleMesh mesh;
  const bool from_file = r.has("file");
  if (from_file) {
    if (r.has("vertices") || r.has("triangles")) r.fail("file", "give either a 'file' or 'vertices' and 'triangles'");
    const std::filesystem::path file = file_of(r, "file");
    try {
      mesh = read_mesh(file);
      refuse_uncut_polygons(mesh);
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

void SceneReader::read_compound_parts(TableReader& r, const toml::table& t, ShapeSpec& s) {
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

ShapeSpec SceneReader::read_shape(TableReader& owner, const std::string& key) {
  if (const NamedShape* named = named_shape(owner, key)) {
    if (!named->spec) owner.fail(key, "names a random_polyhedron, which generators and inflows draw: a body needs a shape");
    return *named->spec;
  }
  const toml::table* t = owner.table(key);
  if (!t) throw SceneError(owner.where() + ": missing required key '" + key + "'" + line_of(owner.table_node()));
  return read_shape_table(*t, owner.where() + "." + key);
}

const toml::table* SceneReader::shape_table_at(TableReader& owner, const std::string& key) {
  if (const NamedShape* named = named_shape(owner, key)) return named->table;
  return owner.table(key);
}

SceneReader::NamedShape* SceneReader::named_shape(TableReader& owner, const std::string& key) {
  const toml::node* n = owner.find(key);
  if (!n || !n->is_string()) return nullptr;
  const std::string name = **n->as_string();
  const auto it = named_shapes_.find(name);
  if (it == named_shapes_.end())
    owner.fail(key, "names no shape of the [shapes] table ('" + name + "')");
  return &it->second;
}

void SceneReader::read_named_shapes(TableReader& top) {
  const toml::table* shapes = top.table("shapes");
  if (!shapes) return;
  for (const auto& [key, node] : *shapes) {
    const std::string name(key.str()), where = "shapes." + name;
    if (!node.is_table())
      throw SceneError(where + ": must be a SHAPE table, e.g. { type = \"box\", ... }" + line_of(node));
    NamedShape& named = named_shapes_[name];
    named.table = node.as_table();
    if (!is_random_polyhedron(*named.table)) named.spec = read_shape_table(*named.table, where);
  }
}

ShapeSpec SceneReader::read_shape_table(const toml::table& table, const std::string& where) {
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
    s.pose = Transform::from(r.vec3_or("center", Vec3{}), r.rotation_or("rotation", Quat{}));
    r.finish();
  } else if (type == "shell") {
    const Real scale = r.positive("scale", 1.0);
    s.shell = mesh_shell(r, scale);
    s.pose = Transform::from(r.vec3_or("center", Vec3{}), r.rotation_or("rotation", Quat{}));
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

}  // namespace gjkdem::io::detail
