// OBJ and STL readers (only what particles need: positions and triangles;
// OBJ polygons cut into triangles, texture/normal indices ignored) and the convexification of a mesh with an honest report.
#include "gjkdem/io/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "gjkdem/shape/convex_hull.hpp"
#include "gjkdem/shape/surface.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::io {
namespace {

// Mesh files above this are refused (a million triangles of binary STL is 50 MB).
constexpr std::uintmax_t kMaxMeshBytes = std::uintmax_t{1} << 30;

[[noreturn]] void fail(const std::string& file, const std::string& what) { throw MeshError(file + ": " + what); }

Vec3 finite_point(const std::string& file, const std::string& where, Real x, Real y, Real z) {
  const Vec3 p{x, y, z};
  if (!is_finite(p)) fail(file, where + ": coordinate is not finite");
  return p;
}

std::string at_line(long line) { return "line " + std::to_string(line); }

// Six significant digits: a 1 cm grain's volume is 1e-06, not "0.000001".
std::string significant(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

// Three coordinates from a text line; strtod also reads "nan" and "inf", so
// those are refused by name instead of as a parse error.
Vec3 read_point(std::istringstream& ls, const std::string& file, long line, const char* tag) {
  Real xyz[3];
  for (Real& c : xyz) {
    std::string tok;
    char* end = nullptr;
    if (!(ls >> tok) || (c = std::strtod(tok.c_str(), &end), *end != '\0'))
      fail(file, at_line(line) + ": '" + tag + "' needs three numbers");
  }
  return finite_point(file, at_line(line), xyz[0], xyz[1], xyz[2]);
}

// A polygon face's triangles. A convex polygon is a fan from its first
// corner; any other is cut by ear clipping in the plane it spans (Newell's
// normal), so a notch stays open. A face with no area, or one that crosses
// itself (no ear to cut), throws naming its line (add_face fans it then).
void cut_polygon(const std::vector<Vec3>& vertices, const std::vector<std::uint32_t>& poly,
                 std::vector<std::array<std::uint32_t, 3>>& out, const std::string& where) {
  const std::size_t n = poly.size();
  if (n == 3) {
    out.push_back({poly[0], poly[1], poly[2]});
    return;
  }
  const Vec3 origin = vertices[poly[0]];
  Vec3 normal;
  for (std::size_t i = 0; i < n; ++i) normal += cross(vertices[poly[i]] - origin, vertices[poly[(i + 1) % n]] - origin);
  if (!(length(normal) > 0)) throw MeshError(where + ": the face's polygon has no area (its corners are on a line)");
  // The plane's two coordinates, in the order that keeps the polygon counter-clockwise.
  const int axis = std::fabs(normal.x) >= std::fabs(normal.y) && std::fabs(normal.x) >= std::fabs(normal.z) ? 0
                   : std::fabs(normal.y) >= std::fabs(normal.z)                                       ? 1
                                                                                                       : 2;
  int u = (axis + 1) % 3, v = (axis + 2) % 3;
  if (normal[axis] < 0) std::swap(u, v);
  std::vector<std::array<Real, 2>> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = {vertices[poly[i]][u] - origin[u], vertices[poly[i]][v] - origin[v]};
  const auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
    return (p[b][0] - p[a][0]) * (p[c][1] - p[a][1]) - (p[b][1] - p[a][1]) * (p[c][0] - p[a][0]);
  };
  // Convex: every corner turns left and the turns add up to one turn.
  bool convex = true;
  Real turned = 0;
  for (std::size_t i = 0; i < n && convex; ++i) {
    const std::size_t a = (i + n - 1) % n, c = (i + 1) % n;
    convex = turn(a, i, c) > 0;
    const Real dx0 = p[i][0] - p[a][0], dy0 = p[i][1] - p[a][1], dx1 = p[c][0] - p[i][0], dy1 = p[c][1] - p[i][1];
    turned += std::atan2(dx0 * dy1 - dy0 * dx1, dx0 * dx1 + dy0 * dy1);
  }
  if (convex && std::fabs(turned - 2 * kPi) < 1) {
    for (std::size_t i = 1; i + 1 < n; ++i) out.push_back({poly[0], poly[i], poly[i + 1]});
    return;
  }
  // Simple: no two edges meet but neighbours at their corner (quadratic, for
  // the few faces that are not convex).
  const auto side = [&](std::size_t a, std::size_t b, std::size_t c) {
    const Real t = turn(a, b, c);
    return (t > 0) - (t < 0);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      const std::size_t i1 = (i + 1) % n, j1 = (j + 1) % n;
      if (j1 == i) continue;  // neighbours across the last corner
      const int s1 = side(i, i1, j), s2 = side(i, i1, j1), s3 = side(j, j1, i), s4 = side(j, j1, i1);
      if (s1 * s2 <= 0 && s3 * s4 <= 0 && (s1 | s2 | s3 | s4) != 0)
        throw MeshError(where + ": the face's polygon crosses itself (edges " + std::to_string(i + 1) + " and " +
                        std::to_string(j + 1) + " meet): give it as triangles");
    }
  std::vector<std::size_t> left(n);
  for (std::size_t i = 0; i < n; ++i) left[i] = i;
  const auto inside = [&](std::size_t q, std::size_t a, std::size_t b, std::size_t c) {
    if (p[q] == p[a] || p[q] == p[b] || p[q] == p[c]) return false;
    return turn(a, b, q) >= 0 && turn(b, c, q) >= 0 && turn(c, a, q) >= 0;
  };
  while (left.size() > 3) {
    const std::size_t m = left.size();
    bool cut = false;
    for (std::size_t s = 1; s <= m && !cut; ++s) {  // from the second corner: a fan where it can be
      const std::size_t k = s % m, a = left[(k + m - 1) % m], b = left[k], c = left[(k + 1) % m];
      if (!(turn(a, b, c) > 0)) continue;
      bool ear = true;
      for (const std::size_t q : left) ear = ear && (q == a || q == b || q == c || !inside(q, a, b, c));
      if (!ear) continue;
      out.push_back({poly[a], poly[b], poly[c]});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(k));
      cut = true;
    }
    if (!cut) throw MeshError(where + ": the face's polygon has no corner to cut off: give it as triangles");
  }
  if (!(turn(left[0], left[1], left[2]) > 0))
    throw MeshError(where + ": the face's polygon has no corner to cut off: give it as triangles");
  out.push_back({poly[left[0]], poly[left[1]], poly[left[2]]});
}

// A face's triangles: cut_polygon's, or where it cannot cut the polygon, a
// fan from its first corner, and the problem kept (TriangleMesh::uncut_polygon).
void add_face(TriangleMesh& m, const std::vector<std::uint32_t>& poly, const std::string& where) {
  std::vector<std::array<std::uint32_t, 3>> cut;
  try {
    cut_polygon(m.vertices, poly, cut, where);
  } catch (const MeshError& e) {
    if (m.uncut_polygon.empty()) m.uncut_polygon = e.what();
    cut.clear();
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) cut.push_back({poly[0], poly[i], poly[i + 1]});
  }
  m.triangles.insert(m.triangles.end(), cut.begin(), cut.end());
}

TriangleMesh read_obj(std::istream& in, const std::string& file) {
  TriangleMesh m;
  std::string line;
  long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    if (!(ls >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      m.vertices.push_back(read_point(ls, file, line_no, "v"));
    } else if (tag == "o" || tag == "g") {
      if (m.triangles.size() > m.object_begin.back()) m.object_begin.push_back(m.triangles.size());
    } else if (tag == "f") {
      std::vector<std::uint32_t> poly;
      std::string item;
      while (ls >> item) {
        // The whole vertex field must be an integer ("1.9" or "2x" are not).
        const std::string field = item.substr(0, item.find('/'));
        long idx = 0;
        std::size_t used = 0;
        try {
          idx = std::stol(field, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != field.size())
          fail(file, "line " + std::to_string(line_no) + ": bad face index '" + item + "'");
        const long n = static_cast<long>(m.vertices.size());
        const long k = idx < 0 ? n + idx : idx - 1;  // OBJ: 1-based, negative = relative
        if (idx == 0 || k < 0 || k >= n)
          fail(file, "line " + std::to_string(line_no) + ": face index " + item + " out of range");
        poly.push_back(static_cast<std::uint32_t>(k));
      }
      if (poly.size() < 3) fail(file, "line " + std::to_string(line_no) + ": a face needs at least 3 vertices");
      add_face(m, poly, file + ": line " + std::to_string(line_no));
    }
  }
  return m;
}

// STL stores each triangle's corners; equal corners are welded into one vertex.
struct Welder {
  TriangleMesh& mesh;
  std::map<std::array<Real, 3>, std::uint32_t> index;
  std::uint32_t add(const Vec3& p) {
    const auto [it, inserted] = index.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back(p);
    return it->second;
  }
};

TriangleMesh read_stl_ascii(std::istream& in, const std::string& file) {
  TriangleMesh m;
  Welder weld{m, {}};
  std::string line;
  long line_no = 0;
  std::vector<std::uint32_t> corners;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    if (!(ls >> tag)) continue;
    if (tag == "vertex") {
      corners.push_back(weld.add(read_point(ls, file, line_no, "vertex")));
    } else if (tag == "endloop") {
      if (corners.size() != 3) fail(file, "line " + std::to_string(line_no) + ": a facet needs exactly 3 vertices");
      m.triangles.push_back({corners[0], corners[1], corners[2]});
      corners.clear();
    } else if (tag != "solid" && tag != "facet" && tag != "outer" && tag != "endfacet" && tag != "endsolid") {
      fail(file, "line " + std::to_string(line_no) + ": unexpected '" + tag + "' in ASCII STL");
    }
  }
  return m;
}

TriangleMesh read_stl_binary(const std::string& bytes, const std::string& file) {
  if (bytes.size() < 84) fail(file, "binary STL shorter than its 84-byte header");
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  if (bytes.size() != 84 + 50ull * count)
    fail(file, "binary STL says " + std::to_string(count) + " triangles but holds " + std::to_string(bytes.size()) + " bytes");
  TriangleMesh m;
  Welder weld{m, {}};
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* rec = bytes.data() + 84 + 50ull * t + 12;  // skip the stored normal
    std::array<std::uint32_t, 3> tri;
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, rec + 12 * k, 12);
      tri[k] = weld.add(finite_point(file, "triangle " + std::to_string(t + 1), xyz[0], xyz[1], xyz[2]));
    }
    m.triangles.push_back(tri);
  }
  return m;
}

}  // namespace

void refuse_uncut_polygons(const TriangleMesh& mesh) {
  if (!mesh.uncut_polygon.empty()) throw MeshError(mesh.uncut_polygon);
}

TriangleMesh read_mesh(const std::filesystem::path& path) {
  const std::string file = path.string();
  // Only regular files of a sane size: a directory, a FIFO or /dev/zero would
  // fail late, block, or read until memory runs out.
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec) fail(file, "cannot open the file (" + ec.message() + ")");
  if (!std::filesystem::is_regular_file(status)) fail(file, "is not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxMeshBytes)
    fail(file, "is larger than " + std::to_string(kMaxMeshBytes >> 20) + " MiB (or its size cannot be read)");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(file, "cannot open the file");
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  TriangleMesh m;
  if (ext == ".obj") {
    m = read_obj(in, file);
  } else if (ext == ".stl") {
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bool binary = true;
    if (bytes.compare(0, 5, "solid") == 0) {
      // Some binary files also start with "solid": trust the size when it matches.
      std::uint32_t count = 0;
      if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);
      binary = bytes.size() >= 84 && bytes.size() == 84 + 50ull * count;
    }
    if (binary) {
      m = read_stl_binary(bytes, file);
    } else {
      std::istringstream text(bytes);
      m = read_stl_ascii(text, file);
    }
  } else {
    fail(file, "unknown mesh format '" + ext + "' (use .obj or .stl)");
  }
  if (m.triangles.empty()) fail(file, "the mesh has no triangles");
  return m;
}

bool is_watertight(const TriangleMesh& mesh) {
  // Each directed edge once, and its reverse present.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, count] : edges) {
    const auto rev = edges.find({e.second, e.first});
    if (count != 1 || rev == edges.end() || rev->second != 1) return false;
  }
  return !mesh.triangles.empty();
}

Real winding_number(const TriangleMesh& mesh, const Vec3& p) {
  return gjkdem::winding_number(mesh.vertices, mesh.triangles, p);
}

ConvexMesh convex_from_mesh(const TriangleMesh& mesh, const std::string& name) {
  if (mesh.triangles.empty()) fail(name, "the mesh has no triangles");
  const ConvexHull hull = convex_hull(mesh.vertices);
  if (hull.dimension != HullDimension::Solid) fail(name, "the mesh is flat (its points span no volume)");
  ConvexMesh out;
  out.watertight = is_watertight(mesh);
  Real mesh_volume = 0;
  for (const auto& t : mesh.triangles)
    mesh_volume += dot(mesh.vertices[t[0]], cross(mesh.vertices[t[1]], mesh.vertices[t[2]])) / 6;
  out.polytope = make_polytope(mesh.vertices);
  const Real hull_volume = out.polytope.data->volume;
  out.convex = out.watertight && std::fabs(std::fabs(mesh_volume) - hull_volume) <= kMeshConvexRelTol * hull_volume;
  if (!out.watertight)
    out.warnings.push_back(name + ": the mesh is not watertight (open or non-manifold edges): using its convex hull");
  else if (!out.convex)
    out.warnings.push_back(name + ": the mesh is not convex (volume " + significant(std::fabs(mesh_volume)) +
                           ", hull " + significant(hull_volume) + "): using its convex hull" +
                           (mesh.object_begin.size() <= 1 ? " (for the grain's true shape give it as type \"surface\", "
                                                            "docs/scenes.md)"
                                                          : ""));
  return out;
}

std::vector<ConvexMesh> convex_parts_from_mesh(const TriangleMesh& mesh, const std::string& name) {
  std::vector<ConvexMesh> parts;
  for (std::size_t k = 0; k < mesh.object_begin.size(); ++k) {
    const std::size_t end = k + 1 < mesh.object_begin.size() ? mesh.object_begin[k + 1] : mesh.triangles.size();
    TriangleMesh object;  // the object's triangles, on its own vertices
    std::map<std::uint32_t, std::uint32_t> index;
    for (std::size_t t = mesh.object_begin[k]; t < end; ++t) {
      std::array<std::uint32_t, 3> tri;
      for (int c = 0; c < 3; ++c) {
        const auto [it, added] = index.try_emplace(mesh.triangles[t][c], static_cast<std::uint32_t>(object.vertices.size()));
        if (added) object.vertices.push_back(mesh.vertices[mesh.triangles[t][c]]);
        tri[c] = it->second;
      }
      object.triangles.push_back(tri);
    }
    parts.push_back(convex_from_mesh(object, name + ", object " + std::to_string(k)));
  }
  return parts;
}

}  // namespace gjkdem::io
