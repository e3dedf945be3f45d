// gjkdem.Shape: made from the fields of the pair-query format
// (../shared/spec/query-format.md), read by the same reader as `gjkdem
// query`, so a shape means the same and is refused with the same message.
#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "gjkdem/dem/body.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "gjkdem/io/scene.hpp"
#include "gjkdem/shape/mass_properties.hpp"

namespace gjkdem::py_bind {
namespace {

using Json = nlohmann::json;

// Python numbers, strings, sequences, arrays and dicts as JSON, nested at
// most as deep as the query format reads (io::kMaxJsonDepth): a list that
// holds itself, or one nested tens of thousands deep, is refused, not
// followed until the stack runs out.
Json to_json(const py::handle& v, const std::string& what, int depth = 0) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
  if (py::isinstance<py::int_>(v)) {
    int overflow = 0;
    const long long i = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
    if (i == -1 && PyErr_Occurred()) throw py::error_already_set();
    if (!overflow) return i;
    const double x = PyLong_AsDouble(v.ptr());  // beyond 64 bits: as the nearest double
    if (x == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      fail(what, "integer too large for a double");
    }
    return x;
  }
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  const bool nests = py::isinstance<py::dict>(v) || py::isinstance<py::array>(v) || py::isinstance<py::sequence>(v);
  if (nests && depth >= io::kMaxJsonDepth)
    fail(what, "nested deeper than " + std::to_string(io::kMaxJsonDepth) + " levels (or holds itself)");
  if (py::isinstance<py::dict>(v)) {
    Json o = Json::object();
    for (const auto& [key, value] : v.cast<py::dict>()) {
      const std::string k = py::str(key);
      o[k] = to_json(value, k, depth + 1);
    }
    return o;
  }
  if (py::isinstance<py::array>(v)) return to_json(v.attr("tolist")(), what, depth);
  if (py::isinstance<py::sequence>(v)) {
    Json a = Json::array();
    for (const auto& item : v.cast<py::sequence>()) a.push_back(to_json(item, what, depth + 1));
    return a;
  }
  // Python floats, and NumPy's scalars (float32 is no float subclass).
  if (PyFloat_Check(v.ptr()) || PyNumber_Check(v.ptr())) {
    const double x = PyFloat_AsDouble(v.ptr());
    if (x == -1.0 && PyErr_Occurred()) throw py::error_already_set();
    if (!std::isfinite(x)) fail(what, "NaN or infinite number");
    return x;
  }
  fail(what, std::string("cannot be a ") + py::str(v.get_type().attr("__name__")).cast<std::string>());
}

// A shape from its JSON text, read as the query reader reads it (its depth
// checked before anything is parsed).
PyShape make_shape(const std::string& text, io::ShapeFrame frame = io::ShapeFrame::World) {
  try {
    const io::PlacedInput placed = io::parse_shape(text, frame);
    const Json j = Json::parse(text, nullptr, false);
    std::string type;
    if (j.is_object() && j.contains("type") && j["type"].is_string()) type = j["type"].get<std::string>();
    return {placed.shape, placed.pose, type, {}, {}};
  } catch (const io::QueryFormatError& e) {
    throw py::value_error(e.what());
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

MassProperties mass_of(const PyShape& s) {
  if (!s.compound()) return mass_properties(s.shape);
  return dem::make_compound_template(s.parts, false, s.surface_parts).unit_mass;
}

// JSON as TOML inline-table text: the scene reader's input. Strings keep
// JSON's escapes (TOML's basic strings share them); numbers and booleans
// read the same in both.
std::string toml_text(const Json& v) {
  if (v.is_object()) {
    std::string s = "{ ";
    bool first = true;
    for (const auto& [key, value] : v.items()) {
      s += (first ? "" : ", ") + Json(key).dump() + " = " + toml_text(value);
      first = false;
    }
    return s + " }";
  }
  if (v.is_array()) {
    std::string s = "[";
    for (std::size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + toml_text(v[k]);
    return s + "]";
  }
  return v.dump();
}

// A compound of these parts, its hull for where a bound will do.
PyShape compound_of(std::vector<PlacedShape> parts, std::vector<dem::PlacedSurface> surfaces) {
  PyShape c;
  c.type = "compound";
  c.parts = std::move(parts);
  c.surface_parts = std::move(surfaces);
  try {
    c.shape = dem::make_compound_template(c.parts, false, c.surface_parts).shape;
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  return c;
}

// A shape of the scenes' own types (platonic, random_polyhedron, compound,
// mesh from a file): read by the scene reader, files relative to the
// working directory; its warnings become Python warnings.
PyShape scene_shape(const std::string& type, Json fields) {
  std::uint64_t seed = 1;
  if (fields.contains("seed")) {
    if (!fields["seed"].is_number_integer() || fields["seed"].get<std::int64_t>() < 0)
      throw py::value_error("Shape: seed must be a non-negative integer");
    seed = fields["seed"].get<std::uint64_t>();
    fields.erase("seed");
  }
  fields["type"] = type;
  io::SceneShape s;
  try {
    s = io::read_scene_shape(toml_text(fields), std::filesystem::current_path(), "Shape(\"" + type + "\")", seed);
  } catch (const io::SceneError& e) {
    throw py::value_error(e.what());
  }
  for (const std::string& w : s.warnings)
    py::module_::import("warnings").attr("warn")("gjkdem: " + w, py::handle(PyExc_UserWarning));
  if (s.shape.surface) throw py::value_error("Shape: a surface grain is a gjkdem.Surface");
  if (dem::is_compound(s.shape)) return compound_of(std::move(s.shape.parts), std::move(s.shape.surface_parts));
  return {s.shape.shape, s.shape.pose, type, {}, {}};
}

}  // namespace

void bind_shapes(py::module_& m) {
  py::class_<PyShape>(m, "Shape", R"(A convex shape: a core and a margin (its Minkowski sum with a ball).

Shape(type, **fields) takes a scene's SHAPE fields (docs/scenes.md): those of
the pair-query format (../shared/spec/query-format.md), in the shape's own
frame, and the scenes' own types:
    Shape("sphere", radius=0.5)
    Shape("box", half_extents=[1, 2, 3], margin=0.1)
    Shape("polytope", vertices=points)           # an (N, 3) array
    Shape("cylinder", radius=1, half_height=2)   # axis along z
    Shape("platonic", name="cube", size=0.02)
    Shape("random_polyhedron", vertices=12, size=[0.012, 0.018], seed=3)   # one drawn from seed
    Shape("mesh", file="rock.stl", scale=0.001)  # its convex hull (files from the working directory)
    Shape("compound", parts=[{...}, {...}]) or Shape("compound", file="parts.obj")
Shape.from_json(dict or str) reads one SHAPE object as written in a query file.)")
      .def(py::init([](const std::string& type, const py::kwargs& fields) {
             Json j = to_json(fields, "shape");
             if (type == "surface")
               throw py::value_error("Shape(\"surface\"): a surface grain is a gjkdem.Surface (vertices, triangles)");
             if (type == "shell")
               throw py::value_error("Shape(\"shell\"): a thin shell is a gjkdem.Shell (vertices, triangles, thickness)");
             if (type == "platonic" || type == "random_polyhedron" || type == "compound" ||
                 (type == "mesh" && j.contains("file")))
               return scene_shape(type, std::move(j));
             j["type"] = type;
             return make_shape(j.dump(), io::ShapeFrame::Own);
           }),
           py::arg("type"))
      .def_static(
          "from_json",
          [](const py::object& value) {
            if (py::isinstance<py::str>(value)) return make_shape(value.cast<std::string>());
            return make_shape(to_json(value, "shape").dump());
          },
          py::arg("shape"))
      .def_static(
          "compound",
          [](const py::sequence& parts) {
            if (parts.size() == 0) throw py::value_error("a compound needs at least one part");
            std::vector<PlacedShape> placed;
            std::vector<dem::PlacedSurface> surfaces;
            for (const py::handle& p : parts) {
              if (py::isinstance<Surface>(p)) {
                surfaces.push_back({p.cast<std::shared_ptr<Surface>>(), Transform::identity()});
                continue;
              }
              if (!py::isinstance<PyShape>(p)) throw py::value_error("a compound's parts are gjkdem.Shape or gjkdem.Surface");
              const PyShape& s = p.cast<const PyShape&>();
              if (s.compound()) throw py::value_error("a part cannot itself be a compound");
              placed.push_back({s.shape, s.offset});
            }
            return compound_of(std::move(placed), std::move(surfaces));
          },
          py::arg("parts"),
          "A non-convex grain as a rigid union of parts, for WorldBuilder: convex Shapes (each placed by its\n"
          "own center and rotation) and closed Surfaces (in the compound's frame, met by their patches, after\n"
          "the Shapes in part order). Parts may touch, not overlap (checked when a body is added). Queries\n"
          "refuse it.")
      .def_property_readonly("parts", [](const PyShape& s) { return s.parts.size() + s.surface_parts.size(); },
                             "How many parts (0 for a convex shape).")
      .def_property_readonly("type", [](const PyShape& s) { return s.type; })
      .def_property_readonly("margin", [](const PyShape& s) { return s.shape.margin; })
      .def_property_readonly("volume", [](const PyShape& s) { return mass_of(s).volume; },
                             "Volume (flat shapes: 0).")
      .def_property_readonly(
          "centroid", [](const PyShape& s) { return from_vec3(apply(s.offset, mass_of(s).centroid)); },
          "Centre of volume, in the shape's frame.")
      .def_property_readonly(
          "bounding_radius", [](const PyShape& s) { return bounding_radius(s.shape) + length(s.offset.translation); },
          "Radius of a ball about the frame's origin that holds the shape.")
      .def("__repr__", [](const PyShape& s) { return "<gjkdem.Shape " + s.type + ">"; });
}

}  // namespace gjkdem::py_bind
