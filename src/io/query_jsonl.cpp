// The query format (JSON Lines) read and written with nlohmann/json.
#include "gjkdem/io/query_jsonl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <nlohmann/json.hpp>

#include "gjkdem/io/number_text.hpp"
#include "gjkdem/tolerances.hpp"
#include <vector>

namespace gjkdem::io {
namespace {

using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& msg) { throw QueryFormatError(msg); }

// Never write nan or inf (not JSON): the caller makes such an answer an
// error line, naming its input line.
[[noreturn]] void refuse_not_finite() {
  throw std::range_error("the answer is not finite (the pair is beyond what double precision resolves)");
}

// Lengths and coordinates beyond this cannot be answered in double precision
// (squared distances overflow near 1e154): such lines are refused.
// Deeper JSON is refused before parsing (the parser recurses per level).

Real number(const Json& j, const std::string& what) {
  if (!j.is_number()) fail(what + " must be a number");
  const Real v = j.get<Real>();
  if (!std::isfinite(v)) fail(what + " must be finite");
  if (std::fabs(v) > kMaxCoordinate) fail(what + " is outside the supported range [-1e100, 1e100]");
  return v;
}

// Refuses text nesting arrays and objects deeper than kMaxJsonDepth.
void check_depth(std::string_view text) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) fail("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// Ratios of a shape's sizes beyond this cannot be resolved in double
// precision (the thin direction vanishes in the round-off of the long one).
constexpr Real kMaxAspectRatio = 1e12;

void check_aspect(Real smallest, Real largest, const std::string& what) {
  if (smallest > 0 && largest / smallest > kMaxAspectRatio)
    fail(what + " spans more than 1e12 between its smallest and largest size: not resolvable in double precision");
}

Vec3 vec3(const Json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) fail(what + " must be an array of 3 numbers");
  return {number(j[0], what + "[0]"), number(j[1], what + "[1]"), number(j[2], what + "[2]")};
}

const Json& field(const Json& obj, const char* key, const std::string& where) {
  const auto it = obj.find(key);
  if (it == obj.end()) fail(where + " is missing '" + key + "'");
  return *it;
}

Real positive(const Json& obj, const char* key, const std::string& where) {
  const Real v = number(field(obj, key, where), where + "." + key);
  if (!(v > 0)) fail(where + "." + key + " must be > 0 (got " + Json(v).dump() + ")");
  return v;
}

Real non_negative(const Json& obj, const char* key, const std::string& where) {
  const Real v = number(field(obj, key, where), where + "." + key);
  if (v < 0) fail(where + "." + key + " must be >= 0 (got " + Json(v).dump() + ")");
  return v;
}

Vec3 positive_vec(const Json& obj, const char* key, const std::string& where) {
  const Vec3 v = vec3(field(obj, key, where), where + "." + key);
  for (int k = 0; k < 3; ++k)
    if (!(v[k] > 0)) fail(where + "." + key + " must have entries > 0");
  return v;
}

Quat rotation(const Json& obj, const std::string& where) {
  const auto it = obj.find("rotation");
  if (it == obj.end()) return {};
  const std::string what = where + ".rotation";
  if (!it->is_array() || it->size() != 4) fail(what + " must be a quaternion [w,x,y,z]");
  Quat q{number((*it)[0], what), number((*it)[1], what), number((*it)[2], what), number((*it)[3], what)};
  const Real n = norm(q);
  // Accept rounding in printed quaternions; refuse anything that is not a rotation.
  if (!(std::fabs(n - 1) <= kUnitQuaternionTol)) fail(what + " must be a unit quaternion (norm " + Json(n).dump() + ")");
  return normalized(q);
}

void check_keys(const Json& obj, std::initializer_list<const char*> allowed, const std::string& where) {
  for (const auto& item : obj.items()) {
    bool ok = false;
    for (const char* k : allowed) ok |= item.key() == k;
    if (!ok) fail(where + " has unknown key '" + item.key() + "'");
  }
}

std::vector<Vec3> point_list(const Json& obj, const std::string& where) {
  const Json& arr = field(obj, "vertices", where);
  if (!arr.is_array() || arr.empty()) fail(where + ".vertices must be a non-empty array of [x,y,z]");
  std::vector<Vec3> pts;
  pts.reserve(arr.size());
  for (std::size_t i = 0; i < arr.size(); ++i) pts.push_back(vec3(arr[i], where + ".vertices[" + std::to_string(i) + "]"));
  return pts;
}

PlacedInput shape_from_json(const Json& s, const std::string& where) {
  if (!s.is_object()) fail(where + " must be a shape object");
  const auto t = s.find("type");
  if (t == s.end() || !t->is_string()) fail(where + " needs a string 'type'");
  const std::string type = t->get<std::string>();
  static constexpr const char* kTypes[] = {"polytope", "triangle", "sphere", "box", "ellipsoid",
                                           "capsule", "cylinder", "cone", "superellipsoid", "mesh"};
  if (std::find(std::begin(kTypes), std::end(kTypes), type) == std::end(kTypes))
    fail(where + " has unknown type '" + type + "'");
  PlacedInput out;
  if (type == "mesh") {
    if (s.contains("margin")) fail(where + ": a mesh takes no 'margin'");
    check_keys(s, {"type", "vertices", "triangles"}, where);
    std::vector<Vec3> pts = point_list(s, where);
    const Json& arr = field(s, "triangles", where);
    if (!arr.is_array() || arr.empty()) fail(where + ".triangles must be a non-empty array of [i,j,k]");
    std::vector<TriangleIndices> triangles;
    triangles.reserve(arr.size());
    for (std::size_t n = 0; n < arr.size(); ++n) {
      const std::string at = where + ".triangles[" + std::to_string(n) + "]";
      const Json& tri = arr[n];
      if (!tri.is_array() || tri.size() != 3) fail(at + " must be [i,j,k]");
      TriangleIndices ids{};
      for (int k = 0; k < 3; ++k) {
        const Json& i = tri[k];
        if (!i.is_number_integer() || (i.is_number_integer() && !i.is_number_unsigned() && i.get<std::int64_t>() < 0) ||
            i.get<std::uint64_t>() >= pts.size())
          fail(at + " must hold indices of vertices (integers from 0 to " + std::to_string(pts.size() - 1) + ")");
        ids[k] = static_cast<std::uint32_t>(i.get<std::uint64_t>());
      }
      triangles.push_back(ids);
    }
    try {
      out.surface = std::make_shared<const Surface>(make_surface(std::move(pts), std::move(triangles)));
    } catch (const SurfaceError& e) {
      fail(where + " is not a closed surface: " + e.what());
    }
    return out;
  }
  Real margin = 0;
  if (s.contains("margin")) margin = non_negative(s, "margin", where);
  if (type == "polytope" || type == "triangle") {
    check_keys(s, {"type", "vertices", "margin"}, where);
    std::vector<Vec3> pts = point_list(s, where);
    if (type == "triangle" && pts.size() != 3) fail(where + ".vertices must hold exactly 3 points for a triangle");
    Vec3 lo = pts[0], hi = pts[0];
    for (const Vec3& p : pts)
      for (int k = 0; k < 3; ++k) { lo[k] = std::fmin(lo[k], p[k]); hi[k] = std::fmax(hi[k], p[k]); }
    const Vec3 centre = (lo + hi) * 0.5;
    for (Vec3& p : pts) p -= centre;
    out.pose.translation = centre;
    if (type == "triangle") out.shape.core = Triangle{{pts[0], pts[1], pts[2]}};
    else out.shape.core = make_polytope(pts);
    out.shape.margin = margin;
    return out;
  }
  if (type == "capsule") {
    check_keys(s, {"type", "p0", "p1", "radius", "margin"}, where);
    const Vec3 p0 = vec3(field(s, "p0", where), where + ".p0"), p1 = vec3(field(s, "p1", where), where + ".p1");
    const Real r = non_negative(s, "radius", where);
    const Vec3 centre = (p0 + p1) * 0.5;
    out.pose.translation = centre;
    out.shape = make_capsule(p0 - centre, p1 - centre, r + margin);
    return out;
  }
  const Vec3 centre = vec3(field(s, "center", where), where + ".center");
  out.pose = Transform::from(centre, rotation(s, where));
  if (type == "sphere") {
    check_keys(s, {"type", "center", "radius", "rotation", "margin"}, where);
    out.shape = make_sphere(non_negative(s, "radius", where) + margin);
    return out;
  }
  out.shape.margin = margin;
  if (type == "box") {
    check_keys(s, {"type", "center", "half_extents", "rotation", "margin"}, where);
    const Vec3 h = vec3(field(s, "half_extents", where), where + ".half_extents");
    if (h.x < 0 || h.y < 0 || h.z < 0) fail(where + ".half_extents must be >= 0");
    out.shape.core = Box{h};
  } else if (type == "ellipsoid") {
    check_keys(s, {"type", "center", "radii", "rotation", "margin"}, where);
    const Vec3 radii = positive_vec(s, "radii", where);
    check_aspect(std::fmin(radii.x, std::fmin(radii.y, radii.z)), max_abs(radii), where + ".radii");
    out.shape.core = Ellipsoid{radii};
  } else if (type == "cylinder" || type == "cone") {
    check_keys(s, {"type", "center", "radius", "half_height", "rotation", "margin"}, where);
    const Real r = positive(s, "radius", where), h = positive(s, "half_height", where);
    check_aspect(std::fmin(r, h), std::fmax(r, h), where);
    if (type == "cylinder") out.shape.core = Cylinder{r, h};
    else out.shape.core = Cone{r, h};
  } else if (type == "superellipsoid") {
    check_keys(s, {"type", "center", "radii", "exponents", "rotation", "margin"}, where);
    const Vec3 radii = positive_vec(s, "radii", where);
    check_aspect(std::fmin(radii.x, std::fmin(radii.y, radii.z)), max_abs(radii), where + ".radii");
    const Json& e = field(s, "exponents", where);
    if (!e.is_array() || e.size() != 2) fail(where + ".exponents must be [e1, e2]");
    const Real e1 = number(e[0], where + ".exponents[0]"), e2 = number(e[1], where + ".exponents[1]");
    if (!(e1 > 0 && e1 <= 2 && e2 > 0 && e2 <= 2))
      fail(where + ".exponents must lie in (0, 2] (convex superellipsoids only)");
    out.shape.core = Superellipsoid{radii, e1, e2};
  } else {
    fail(where + " has unknown type '" + type + "'");
  }
  return out;
}

// Answers print no "-0" (io::append_number keeps the sign): a zero is the
// same text whichever side it came from.
void append_value(std::string& s, Real v) { append_number(s, v == 0 ? Real{0} : v); }

void append_vec(std::string& s, const Vec3& v) {
  s += '[';
  append_value(s, v.x);
  s += ',';
  append_value(s, v.y);
  s += ',';
  append_value(s, v.z);
  s += ']';
}

}  // namespace

bool is_skipped_line(std::string_view line) {
  const auto first = line.find_first_not_of(" \t\r\n");
  return first == std::string_view::npos || line[first] == '#';
}

PlacedInput parse_shape(std::string_view json_text, ShapeFrame frame) {
  check_depth(json_text);
  Json j = Json::parse(json_text, nullptr, false);
  if (j.is_discarded()) fail("shape is not valid JSON");
  if (j.is_object() && j.contains("type") && j["type"] == "mesh")
    fail("shape: a mesh is a surface, not a convex shape (in Python: gjkdem.Surface(vertices, triangles); scenes read "
         "meshes from files)");
  if (frame == ShapeFrame::Own && j.is_object() && !j.contains("center")) {
    const Json* type = j.contains("type") ? &j["type"] : nullptr;
    const bool by_points = type && type->is_string() &&
                           (*type == "polytope" || *type == "triangle" || *type == "capsule");
    if (!by_points) j["center"] = Json::array({0.0, 0.0, 0.0});
  }
  return shape_from_json(j, "shape");
}

namespace {

// A polytope or box without margin as a closed surface in world
// coordinates (its hull's triangles), to pair it with a mesh.
Surface surface_of_polyhedron(const PlacedInput& in) {
  const Shape& shape = in.shape;
  const auto* polytope = std::get_if<Polytope>(&shape.core);
  const auto* box = std::get_if<Box>(&shape.core);
  if (!polytope && !box)
    throw std::invalid_argument("a mesh pairs only with another mesh, a polytope or a box (solids bounded by flat faces) in this version");
  if (shape.margin > 0) throw std::invalid_argument("a mesh pairs with shapes without margin");
  try {
    return moved(polytope ? polytope_surface(*polytope) : box_surface(*box), in.pose);
  } catch (const SurfaceError&) {
    throw std::invalid_argument("a flat polytope bounds no solid to pair with a mesh");
  }
}

}  // namespace

PairInput parse_pair(std::string_view line, std::string& id_json) {
  check_depth(line);
  Json j = Json::parse(line, nullptr, false);
  if (j.is_discarded()) fail("not valid JSON");
  if (!j.is_object()) fail("a pair must be a JSON object");
  PairInput pair;
  if (const auto id = j.find("id"); id != j.end()) id_json = id->dump();
  pair.id_json = id_json;
  check_keys(j, {"id", "a", "b"}, "pair");
  if (!j.contains("id")) fail("pair is missing 'id'");
  if (!j.contains("a") || !j.contains("b")) fail("pair needs shapes 'a' and 'b'");
  try {
    pair.a = shape_from_json(j["a"], "a");
    pair.b = shape_from_json(j["b"], "b");
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
  if (!pair.a.surface != !pair.b.surface) {
    PlacedInput& other = pair.a.surface ? pair.b : pair.a;
    const std::string name = pair.a.surface ? "b" : "a";
    try {
      other.surface = std::make_shared<const Surface>(surface_of_polyhedron(other));
    } catch (const std::invalid_argument& e) {
      fail(name + ": " + e.what());
    }
  }
  return pair;
}

std::string format_result(const std::string& id_json, const PenetrationResult& r, const OverlapFields& o) {
  const bool finite = std::isfinite(r.distance) && std::isfinite(r.depth) && is_finite(r.witness_a) &&
                      is_finite(r.witness_b) && is_finite(r.normal) && (!o.computed || std::isfinite(o.volume)) &&
                      (!o.has_centroid || is_finite(o.centroid)) && (!o.has_normal || is_finite(o.contact_normal));
  if (!finite) refuse_not_finite();
  std::string s;
  s.reserve(400);
  s += "{\"id\":" + id_json + ",\"intersect\":" + (r.intersect ? "true" : "false") + ",\"distance\":";
  append_value(s, r.distance);
  s += ",\"witness_a\":";
  append_vec(s, r.witness_a);
  s += ",\"witness_b\":";
  append_vec(s, r.witness_b);
  s += ",\"depth\":";
  append_value(s, r.depth);
  s += ",\"normal\":";
  append_vec(s, r.normal);
  s += ",\"overlap_volume\":";
  if (o.computed) append_value(s, o.volume);
  else s += "null";
  s += ",\"overlap_centroid\":";
  if (o.has_centroid) append_vec(s, o.centroid);
  else s += "null";
  s += ",\"contact_normal\":";
  if (o.has_normal) append_vec(s, o.contact_normal);
  else s += "null";
  s += ",\"iterations\":" + std::to_string(r.iterations) + "}";
  return s;
}

std::string format_surface_result(const std::string& id_json, const SurfaceOverlap& o, const SurfaceDistance* d,
                                  Real smaller_volume) {
  bool finite = std::isfinite(o.volume) && is_finite(o.centroid) && is_finite(o.area_a) && is_finite(o.area_b) &&
                      (!d || (std::isfinite(d->distance) && is_finite(d->witness_a) && is_finite(d->witness_b)));
  for (const SurfacePatch& p : o.patches)
    finite = finite && std::isfinite(p.volume) && is_finite(p.centroid) && is_finite(p.area_a) && is_finite(p.area_b);
  if (!finite) refuse_not_finite();
  std::string s;
  s.reserve(400);
  s += "{\"id\":" + id_json + ",\"intersect\":" + (o.intersect ? "true" : "false") + ",\"distance\":";
  append_value(s, d ? d->distance : 0);
  s += ",\"witness_a\":";
  if (d) append_vec(s, d->witness_a);
  else s += "null";
  s += ",\"witness_b\":";
  if (d) append_vec(s, d->witness_b);
  else s += "null";
  s += ",\"depth\":null,\"normal\":null,\"overlap_volume\":";
  append_value(s, o.volume);
  s += ",\"overlap_centroid\":";
  if (o.volume > 0) append_vec(s, o.centroid);
  else s += "null";
  s += ",\"contact_normal\":";
  // normalize(S_A - S_B), none where it is zero or where one solid lies
  // wholly inside the other (piece_meeting: its round-off is no direction).
  const auto normal_of = [&](const Vec3& m, Real volume) -> std::optional<Vec3> {
    if (!(volume > 0) || !(length(m) > 0) ||
        piece_meeting(0.5 * length(m), volume, smaller_volume) == PieceMeeting::WhollyInside)
      return std::nullopt;
    return m / length(m);
  };
  if (const std::optional<Vec3> n = normal_of(o.area_a - o.area_b, o.volume)) append_vec(s, *n);
  else s += "null";
  s += ",\"patches\":[";
  for (std::size_t k = 0; k < o.patches.size(); ++k) {
    const SurfacePatch& p = o.patches[k];
    const Vec3 m = p.area_a - p.area_b;
    s += k ? ",{\"volume\":" : "{\"volume\":";
    append_value(s, p.volume);
    s += ",\"centroid\":";
    append_vec(s, p.centroid);
    s += ",\"normal\":";
    if (const std::optional<Vec3> n = normal_of(m, p.volume)) append_vec(s, *n);
    else s += "null";
    s += ",\"area\":";
    append_value(s, 0.5 * length(m));
    s += "}";
  }
  s += "]}";
  return s;
}

std::string format_error(const std::string& id_json, const std::string& message) {
  return "{\"id\":" + id_json + ",\"error\":" + Json(message).dump(-1, ' ', false, Json::error_handler_t::replace) + "}";
}

}  // namespace gjkdem::io
