// Worlds from Python: settings, the builder, stepping and running with
// Python observers, zero-copy NumPy views of the bodies, the contacts of the
// last step, energies and checkpoints.
//
// Views alias World::bodies (an array of plain Body structs): each is an
// (N, 3) or (N, 4) float64 array with a row stride of sizeof(Body) that keeps
// the World alive. Positions, orientations, forces and torques are read-only
// (set_positions / set_orientations check what they are given); velocities
// and angular momenta may be written in place.
#include <array>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "bindings.hpp"
#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/dem/measure.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/io/run_observers.hpp"
#include "gjkdem/io/scene_run.hpp"
#include "gjkdem/tolerances.hpp"
#include "py_run.hpp"

namespace gjkdem::py_bind {
namespace {

// A gjkdem.Shape, a gjkdem.Surface (a surface grain) or a gjkdem.Shell (a
// thin shell) as a body's shape.
bool is_body_shape(const py::handle& shape) {
  return py::isinstance<PyShape>(shape) || py::isinstance<Surface>(shape) || py::isinstance<Shell>(shape);
}
dem::BodyShape body_shape(const py::handle& shape, const char* what) {
  dem::BodyShape s;
  if (py::isinstance<Surface>(shape)) {
    s.surface = shape.cast<std::shared_ptr<Surface>>();
    return s;
  }
  if (py::isinstance<Shell>(shape)) {
    s.shell = shape.cast<std::shared_ptr<Shell>>();
    return s;
  }
  if (!py::isinstance<PyShape>(shape)) fail(what, "expected a gjkdem.Shape, a gjkdem.Surface or a gjkdem.Shell");
  const PyShape& p = shape.cast<const PyShape&>();
  return {p.shape, p.offset, p.parts, p.surface_parts};
}

// A shape or a sequence of them, as the builder's variants (a shell is a
// body of its own: add_body, as a scene's generators and inflows refuse it).
std::vector<dem::BodyShape> body_shapes(const py::object& shapes) {
  const auto variant = [](const py::handle& item) {
    if (py::isinstance<Shell>(item))
      fail("shapes", "a gjkdem.Shell is a body of its own (add_body): fill_region and inflows do not make shells");
    if (!is_body_shape(item)) fail("shapes", "expected a gjkdem.Shape or gjkdem.Surface, or a list of them");
    return body_shape(item, "shapes");
  };
  if (is_body_shape(shapes)) return {variant(shapes)};
  std::vector<dem::BodyShape> out;
  for (const auto& item : shapes.cast<py::sequence>()) out.push_back(variant(item));
  return out;
}

using dem::Body;
using dem::World;

dem::ContactModel model_from(const std::string& name) {
  if (const auto m = dem::contact_model_named(name)) return *m;
  fail("model", std::string("must be ") + dem::kContactModelNames + ", not \"" + name + "\"");
}

// Runs `read`, a setter's reading of a Python value, turning pybind11's
// cast errors (their text names its internals) into a ValueError that says
// what `what` expects.
template <class F>
void recast(const char* what, const char* expected, F&& read) {
  try {
    read();
  } catch (const py::cast_error&) {
    fail(what, std::string("expected ") + expected);
  } catch (py::error_already_set& e) {  // a conversion Python itself refused (dict(5))
    if (!e.matches(PyExc_TypeError)) throw;
    fail(what, std::string("expected ") + expected);
  }
}

// A setter of one of the settings that applies the builder's rules at once
// (dem::check_settings): what a scene refuses, Python refuses.
template <class T>
auto checked(T dem::WorldSettings::*field) {
  return [field](dem::WorldSettings& s, T value) {
    dem::WorldSettings next = s;
    next.*field = value;
    dem::WorldSettings alone = next;  // the cell's rules wait for the builder: it may be set later
    alone.periodic = {}, alone.cell_control = {};
    dem::check_settings(alone);
    s = next;
  };
}
template <class T>
auto getter(T dem::WorldSettings::*field) {
  return [field](const dem::WorldSettings& s) { return s.*field; };
}

// A view of one field of every body: rows of `cols` values of T, `offset`
// bytes into each Body.
template <class T>
py::array body_view(World& w, const py::handle& owner, std::size_t offset, py::ssize_t cols, bool writeable) {
  const auto n = static_cast<py::ssize_t>(w.bodies.size());
  void* first = n ? reinterpret_cast<char*>(w.bodies.data()) + offset : nullptr;
  std::vector<py::ssize_t> shape{n}, strides{static_cast<py::ssize_t>(sizeof(Body))};
  if (cols > 0) shape.push_back(cols), strides.push_back(sizeof(T));
  py::array a(py::dtype::of<T>(), shape, strides, first, owner);
  if (!writeable) py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// Which bodies a setter changes: None (all) or an array of indices.
std::vector<std::size_t> body_indices(const World& w, const py::object& indices, py::ssize_t rows) {
  std::vector<std::size_t> out;
  if (indices.is_none()) {
    if (static_cast<std::size_t>(rows) != w.bodies.size())
      fail("values", "expected one row per body (" + std::to_string(w.bodies.size()) + "), got " +
                         std::to_string(rows) + "; pass indices= to set some");
    for (std::size_t k = 0; k < w.bodies.size(); ++k) out.push_back(k);
    return out;
  }
  const auto idx = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(indices);
  if (!idx || idx.ndim() != 1) fail("indices", "expected a 1-D array of body indices");
  if (idx.shape(0) != rows) fail("indices", "expected one index per row of values");
  for (py::ssize_t k = 0; k < rows; ++k) {
    const std::int64_t i = idx.data()[k];
    if (i < 0 || static_cast<std::size_t>(i) >= w.bodies.size())
      fail("indices", "body index " + std::to_string(i) + " out of range [0, " + std::to_string(w.bodies.size()) +
                          ")");
    out.push_back(static_cast<std::size_t>(i));
  }
  return out;
}

std::uint32_t material_index(const dem::WorldBuilder& b, const py::object& material) {
  if (py::isinstance<py::str>(material)) {
    const std::string name = material.cast<std::string>();
    const std::optional<std::uint32_t> m = b.find_material(name);
    if (!m) fail("material", "no material is named '" + name + "'");
    return *m;
  }
  if (!py::isinstance<py::int_>(material)) fail("material", "expected a material's name or index");
  const long long m = material.cast<long long>();
  if (m < 0 || m > 0xffffffffLL) fail("material", "index " + std::to_string(m) + " out of range");
  return static_cast<std::uint32_t>(m);
}

// A read-only or writable view property of the World class.
template <class T>
void def_view(py::class_<World>& c, const char* name, std::size_t offset, py::ssize_t cols, bool writeable,
              const char* doc) {
  c.def_property_readonly(
      name, [=](py::object self) { return body_view<T>(self.cast<World&>(), self, offset, cols, writeable); }, doc);
}

py::dict contacts_of(const World& w) {
  idle(w);
  std::size_t n = 0;
  for (const dem::StepContact& c : w.results.contacts) n += c.active;
  py::array_t<std::uint64_t> ids({static_cast<py::ssize_t>(n), py::ssize_t{2}});
  py::array_t<double> points({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  py::array_t<double> normals({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  py::array_t<double> forces({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  py::array_t<double> depth(static_cast<py::ssize_t>(n)), volume(static_cast<py::ssize_t>(n));
  std::uint64_t* id = ids.mutable_data();
  double *p = points.mutable_data(), *nn = normals.mutable_data(), *f = forces.mutable_data();
  double *d = depth.mutable_data(), *v = volume.mutable_data();
  std::size_t k = 0;
  for (const dem::StepContact& c : w.results.contacts) {
    if (!c.active) continue;
    id[2 * k] = c.a_is_plane ? w.planes[c.a].id : w.bodies[c.a].id;
    id[2 * k + 1] = w.bodies[c.b].id;
    const Vec3 rows[3] = {c.geometry.point, c.geometry.normal, c.force};
    double* outs[3] = {p, nn, f};
    for (int r = 0; r < 3; ++r) outs[r][3 * k] = rows[r].x, outs[r][3 * k + 1] = rows[r].y, outs[r][3 * k + 2] = rows[r].z;
    d[k] = c.geometry.depth, v[k] = c.geometry.volume;
    ++k;
  }
  py::dict out;
  out["ids"] = ids, out["points"] = points, out["normals"] = normals, out["forces"] = forces;
  out["depth"] = depth, out["overlap_volume"] = volume;
  return out;
}

}  // namespace

void bind_world(py::module_& m) {
  py::class_<dem::WorldSettings>(m, "Settings", "The settings of a world (docs/scenes.md, [contact] and [simulation]).")
      .def(py::init<>())
      .def_property(
          "model", [](const dem::WorldSettings& s) { return dem::name_of(s.model); },
          [](dem::WorldSettings& s, const std::string& v) { s.model = model_from(v); },
          "\"volume\" (default), \"hertz\" or \"linear\"")
      .def_property(
          "gravity", [](const dem::WorldSettings& s) { return from_vec3(s.gravity); },
          [](dem::WorldSettings& s, const py::object& v) { s.gravity = to_vec3(v, "gravity"); }, "m/s^2")
      .def_property("linear_stiffness", getter(&dem::WorldSettings::linear_stiffness),
                    checked(&dem::WorldSettings::linear_stiffness), "N/m; 0: from the materials")
      .def_property("volume_stiffness", getter(&dem::WorldSettings::volume_stiffness),
                    checked(&dem::WorldSettings::volume_stiffness), "N/m^3; 0: from the materials")
      .def_property(
          "volume_form",
          [](const dem::WorldSettings& s) { return dem::name_of(s.volume_form); },
          [](dem::WorldSettings& s, const std::string& v) {
            const auto form = dem::volume_form_named(v);
            if (!form) fail("volume_form", std::string("must be ") + dem::kVolumeFormNames + ", not \"" + v + "\"");
            s.volume_form = *form;
          })
      .def_readwrite("rocking_resistance", &dem::WorldSettings::rocking_resistance)
      .def_property("tessellation", getter(&dem::WorldSettings::tessellation),
                    checked(&dem::WorldSettings::tessellation),
                    ("support directions of curved shapes (" + std::to_string(dem::kMinTessellation) + " to " +
                     std::to_string(dem::kMaxTessellation) + ")")
                        .c_str())
      .def_property("box_skin", getter(&dem::WorldSettings::box_skin), checked(&dem::WorldSettings::box_skin))
      .def_property("threads", getter(&dem::WorldSettings::threads), checked(&dem::WorldSettings::threads),
                    ("OpenMP threads of a step (0: every core; up to " + std::to_string(dem::kMaxThreads) + ")").c_str())
      .def_property(
          "periodic",
          [](const dem::WorldSettings& s) {
            py::dict d;
            const char* names[3] = {"x", "y", "z"};
            for (int a = 0; a < 3; ++a)
              if (s.periodic.axes[a]) d[names[a]] = py::make_tuple(s.periodic.lo[a], s.periodic.hi[a]);
            return d;
          },
          [](dem::WorldSettings& s, const py::dict& d) {
            dem::PeriodicCell cell;
            recast("periodic", "a dict of \"x\", \"y\" or \"z\" to (min, max) pairs of numbers", [&] {
              for (const auto& [key, value] : d) {
                const std::string name = key.cast<std::string>();
                const int a = name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : -1;
                if (a < 0) fail("periodic", "keys are \"x\", \"y\" and \"z\", not \"" + name + "\"");
                const auto range = value.cast<std::array<double, 2>>();  // its rules: WorldBuilder's
                cell.axes[a] = true, cell.lo[a] = range[0], cell.hi[a] = range[1];
              }
            });
            s.periodic = cell;
          },
          "Periodic axes and their ranges, e.g. {\"x\": (0, 0.1), \"y\": (0, 0.1)} (docs/scenes.md); {}: none")
      .def_property(
          "cell_control",
          [](const dem::WorldSettings& s) {
            py::dict d, rates, stresses;
            const dem::CellControl& c = s.cell_control;
            for (int k = 0; k < 6; ++k) {
              if (c.mode[k] == dem::CellMode::StrainRate) rates[dem::kCellComponents[k]] = c.value[k];
              if (c.mode[k] == dem::CellMode::Stress) stresses[dem::kCellComponents[k]] = c.value[k];
            }
            if (rates.size()) d["strain_rate"] = rates;
            if (stresses.size()) d["stress"] = stresses, d["max_strain_rate"] = c.max_strain_rate;
            return d;
          },
          [](dem::WorldSettings& s, const py::dict& d) {
            dem::CellControl c;
            recast("cell_control", "a dict of \"strain_rate\" and \"stress\" dicts of numbers, and a number", [&] {
              for (const auto& [key, value] : d) {
                const std::string name = key.cast<std::string>();
                if (name == "max_strain_rate") {
                  c.max_strain_rate = value.cast<double>();
                  continue;
                }
                if (name != "strain_rate" && name != "stress")
                  fail("cell_control", "keys are \"strain_rate\", \"stress\" and \"max_strain_rate\", not \"" + name + "\"");
                for (const auto& [component, v] : value.cast<py::dict>()) {
                  const std::string cname = component.cast<std::string>();
                  int k = 0;
                  while (k < 6 && cname != dem::kCellComponents[k]) ++k;
                  if (k == 6) fail("cell_control", "components are x, y, z, xy, xz and yz, not \"" + cname + "\"");
                  if (c.mode[k] != dem::CellMode::Fixed) fail("cell_control", cname + " takes a strain rate or a stress, not both");
                  c.mode[k] = name == "stress" ? dem::CellMode::Stress : dem::CellMode::StrainRate;
                  c.value[k] = v.cast<double>();
                }
              }
            });
            s.cell_control = c;
          },
          "How the periodic cell deforms: {\"strain_rate\": {\"xz\": 1.0}} or {\"stress\": {\"x\": p, \"y\": p, "
          "\"z\": p}, \"max_strain_rate\": 1.0} (docs/scenes.md); {}: it does not");

  py::class_<dem::RunState>(m, "RunState", "Where a run stands (seen by observers).")
      .def_readonly("dt", &dem::RunState::dt)
      .def_readonly("steps_total", &dem::RunState::steps_total)
      .def_readonly("steps_per_output", &dem::RunState::steps_per_output)
      .def_readonly("step", &dem::RunState::step)
      .def_readonly("outputs", &dem::RunState::outputs)
      .def_readonly("initial_energy", &dem::RunState::initial_energy);

  py::class_<dem::WorldBuilder>(m, "WorldBuilder", py::dynamic_attr(),
                                "Makes a World: materials, bodies, walls, generated regions.")
      .def(py::init<const dem::WorldSettings&>(), py::arg("settings") = dem::WorldSettings{})
      .def(
          "add_material",
          [](dem::WorldBuilder& b, const std::string& name, double density, double youngs_modulus,
             double poisson_ratio, double restitution, double friction, double rolling_friction,
             double rolling_damping, double strength, double weibull_modulus, double strength_size,
             double unbreakable_below, std::uint64_t strength_seed, double bond_tensile_strength,
             double bond_shear_strength, double bond_normal_stiffness, double bond_shear_stiffness,
             double bond_damping, double bond_moment_strength) {
            return b.add_material({.name = name,
                                   .density = density,
                                   .youngs_modulus = youngs_modulus,
                                   .poisson_ratio = poisson_ratio,
                                   .restitution = restitution,
                                   .friction = friction,
                                   .rolling_friction = rolling_friction,
                                   .rolling_damping = rolling_damping,
                                   .strength = {.mean = strength,
                                                .weibull_modulus = weibull_modulus,
                                                .reference_size = strength_size,
                                                .smallest = unbreakable_below,
                                                .seed = strength_seed},
                                   .glue = {.tensile_strength = bond_tensile_strength,
                                            .shear_strength = bond_shear_strength,
                                            .moment_strength = bond_moment_strength,
                                            .normal_stiffness = bond_normal_stiffness,
                                            .shear_stiffness = bond_shear_stiffness,
                                            .damping = bond_damping}});
          },
          py::arg("name"), py::arg("density"), py::arg("youngs_modulus"),
          py::arg("poisson_ratio") = dem::Material{}.poisson_ratio, py::arg("restitution") = dem::Material{}.restitution,
          py::arg("friction") = dem::Material{}.friction, py::arg("rolling_friction") = dem::Material{}.rolling_friction,
          py::arg("rolling_damping") = dem::Material{}.rolling_damping, py::arg("strength") = 0.0,
          py::arg("weibull_modulus") = dem::Strength{}.weibull_modulus, py::arg("strength_size") = 0.0,
          py::arg("unbreakable_below") = 0.0, py::arg("strength_seed") = dem::Strength{}.seed,
          py::arg("bond_tensile_strength") = 0.0, py::arg("bond_shear_strength") = 0.0,
          py::arg("bond_normal_stiffness") = 0.0, py::arg("bond_shear_stiffness") = 0.0,
          py::arg("bond_damping") = dem::Glue{}.damping, py::arg("bond_moment_strength") = 0.0,
          "Returns the material's index (the defaults are a scene's: dem::Material). A strength > 0 (Pa, the "
          "mean at strength_size, m) lets its polyhedral grains break; a bond_tensile_strength > 0 (Pa, with a "
          "bond_shear_strength) glues the pieces of its bonded assemblies (docs/breakage.md).")
      .def(
          "add_bonded",
          [](dem::WorldBuilder& b, const py::object& shape_object, const py::object& material, std::int64_t pieces,
             std::int64_t seed, std::int64_t relaxations, const py::object& position, const py::object& rotation,
             const py::object& velocity, const py::object& angular_velocity, const std::string& label) {
            const std::string who = label.empty() ? "bonded assembly" : label;
            if (pieces < 2 || pieces > dem::kMaxBondedPieces)
              throw dem::BuildError(who, "pieces", "must be between 2 and " + std::to_string(dem::kMaxBondedPieces));
            if (seed < 0) throw dem::BuildError(who, "seed", "must be >= 0");
            if (relaxations < 0 || relaxations > 100) throw dem::BuildError(who, "relaxations", "must be between 0 and 100");
            return b.add_bonded({.shape = body_shape(shape_object, "shape"),
                                 .pieces = static_cast<std::uint32_t>(pieces),
                                 .seed = static_cast<std::uint64_t>(seed),
                                 .relaxations = static_cast<int>(relaxations),
                                 .material = material_index(b, material),
                                 .position = to_vec3(position, "position"),
                                 .rotation = to_quat(rotation, "rotation"),
                                 .velocity = to_vec3(velocity, "velocity"),
                                 .angular_velocity = to_vec3(angular_velocity, "angular_velocity"),
                                 .label = label});
          },
          py::arg("shape"), py::arg("material"), py::arg("pieces"), py::arg("seed") = 1, py::arg("relaxations") = 3,
          py::arg("position") = std::array<double, 3>{0, 0, 0}, py::arg("rotation") = std::array<double, 4>{1, 0, 0, 0},
          py::arg("velocity") = std::array<double, 3>{0, 0, 0},
          py::arg("angular_velocity") = std::array<double, 3>{0, 0, 0}, py::arg("label") = "",
          "A bonded assembly: the convex `shape` cut into `pieces` Voronoi pieces, each a body, glued at the faces\n"
          "they share by the material's bonds (docs/breakage.md). Returns the pieces' indices.")
      .def(
          "add_body",
          [](py::object self, const py::object& shape_object, const py::object& material, const py::object& position,
             const py::object& rotation, const py::object& velocity, const py::object& angular_velocity, bool fixed,
             std::uint32_t motion, const std::string& label, const std::string& name) {
            dem::WorldBuilder& b = self.cast<dem::WorldBuilder&>();
            dem::BodyDef def{.shape = body_shape(shape_object, "shape"),
                             .material = material_index(b, material),
                             .position = to_vec3(position, "position"),
                             .rotation = to_quat(rotation, "rotation"),
                             .velocity = to_vec3(velocity, "velocity"),
                             .angular_velocity = to_vec3(angular_velocity, "angular_velocity"),
                             .fixed = fixed,
                             .motion = motion,
                             .label = label,
                             .name = name};
            // Moving bodies given one Shape object share one template, as a
            // scene's do: the builder keeps, per Shape object (held alive
            // here, so its id stays its own), the shared shape it made.
            if (!fixed && !dem::is_compound(def.shape)) {
              if (!py::hasattr(self, "_shared_shapes")) self.attr("_shared_shapes") = py::dict();
              py::dict shared = self.attr("_shared_shapes");
              const py::int_ key(reinterpret_cast<std::uintptr_t>(shape_object.ptr()));
              if (!shared.contains(key))
                shared[key] = py::make_tuple(shape_object, b.add_shape(def.shape, label.empty() ? "shape" : label));
              def.shared_shape = shared[key].cast<py::tuple>()[1].cast<std::int64_t>();
            }
            return b.add_body(def);
          },
          py::arg("shape"), py::arg("material"), py::arg("position") = std::array<double, 3>{0, 0, 0},
          py::arg("rotation") = std::array<double, 4>{1, 0, 0, 0},
          py::arg("velocity") = std::array<double, 3>{0, 0, 0},
          py::arg("angular_velocity") = std::array<double, 3>{0, 0, 0}, py::arg("fixed") = false,
          py::arg("motion") = 0, py::arg("label") = "", py::arg("name") = "",
          "Adds a body whose frame (the shape's) is at `position`, turned by `rotation` [w, x, y, z]; returns its index.\n"
          "motion: a number from add_motion, for a fixed body that moves as prescribed. name: the body is traced\n"
          "(trace.csv of run(out=...), World.names) and messages call it so; label: a name for messages only.")
      .def(
          "add_motion",
          [](dem::WorldBuilder& b, const py::object& center, const py::object& velocity,
             const py::object& angular_velocity, const py::object& amplitude, double frequency, double phase,
             const py::object& table, const std::string& label) {
            dem::PrescribedMotion motion;
            motion.center = to_vec3(center, "center");
            motion.velocity = to_vec3(velocity, "velocity");
            motion.angular_velocity = to_vec3(angular_velocity, "angular_velocity");
            motion.amplitude = to_vec3(amplitude, "amplitude");
            motion.frequency = frequency;
            motion.phase = phase;
            if (!table.is_none()) {
              const auto rows = to_matrix(table, 4, "table");
              for (py::ssize_t k = 0; k < rows.shape(0); ++k) {
                motion.table_times.push_back(rows.at(k, 0));
                motion.table_displacements.push_back({rows.at(k, 1), rows.at(k, 2), rows.at(k, 3)});
              }
            }
            return b.add_motion(motion, label.empty() ? "motion" : label);
          },
          py::arg("center") = std::array<double, 3>{0, 0, 0}, py::arg("velocity") = std::array<double, 3>{0, 0, 0},
          py::arg("angular_velocity") = std::array<double, 3>{0, 0, 0},
          py::arg("amplitude") = std::array<double, 3>{0, 0, 0}, py::arg("frequency") = 0.0, py::arg("phase") = 0.0,
          py::arg("table") = py::none(), py::arg("label") = "",
          "A prescribed motion for walls and fixed bodies (docs/scenes.md): constant velocity, turning at\n"
          "angular_velocity about center, a vibration amplitude * sin(2 pi frequency t + phase), and a table of\n"
          "(K, 4) rows [t, dx, dy, dz] of displacements. Returns its number for the `motion` arguments.")
      .def(
          "add_plane",
          [](dem::WorldBuilder& b, const py::object& point, const py::object& normal, const py::object& material,
             std::uint32_t motion, const std::string& label) {
            b.add_plane(to_vec3(point, "point"), to_vec3(normal, "normal"), material_index(b, material),
                        label.empty() ? "plane" : label, motion);
          },
          py::arg("point"), py::arg("normal"), py::arg("material"), py::arg("motion") = 0, py::arg("label") = "",
          "An infinite plane wall; the material lies on the side opposite to `normal`.")
      .def(
          "add_box_walls",
          [](dem::WorldBuilder& b, const py::object& lo, const py::object& hi, const py::object& material,
             bool open_top, double thickness, std::uint32_t motion, const std::string& label) {
            const Vec3 l = to_vec3(lo, "lo"), h = to_vec3(hi, "hi");
            if (thickness <= 0) thickness = 0.5 * std::fmin(h.x - l.x, std::fmin(h.y - l.y, h.z - l.z));
            b.add_box_walls(l, h, open_top, thickness, material_index(b, material), label.empty() ? "box" : label,
                            motion);
          },
          py::arg("lo"), py::arg("hi"), py::arg("material"), py::arg("open_top") = false, py::arg("thickness") = 0.0,
          py::arg("motion") = 0, py::arg("label") = "", "A box container [lo, hi]; thickness 0: half its smallest side.")
      .def(
          "add_mesh_walls",
          [](dem::WorldBuilder& b, const py::object& vertices, const py::object& triangles, double thickness,
             const py::object& material, std::uint32_t motion, const std::string& label) {
            TriangleArrays mesh = triangles_from_arrays(vertices, triangles);
            b.add_mesh_walls(mesh.points, mesh.corners, thickness, material_index(b, material),
                             label.empty() ? "mesh" : label, motion);
          },
          py::arg("vertices"), py::arg("triangles"), py::arg("thickness"), py::arg("material"),
          py::arg("motion") = 0, py::arg("label") = "",
          "A triangle mesh wall (world coordinates, (N, 3) vertices, (M, 3) indices), one fixed piece per triangle.")
      .def(
          "add_cylinder_walls",
          [](dem::WorldBuilder& b, const py::object& base, const py::object& axis, double radius, double height,
             const py::object& material, bool bottom, bool top, int segments, double thickness, std::uint32_t motion,
             const std::string& label) {
            const dem::CylinderWall wall{.base = to_vec3(base, "base"),
                                         .axis = to_vec3(axis, "axis"),
                                         .radius = radius,
                                         .height = height,
                                         .bottom = bottom,
                                         .top = top,
                                         .segments = segments,
                                         .thickness = thickness};
            b.add_cylinder_walls(wall, material_index(b, material), label.empty() ? "cylinder" : label, motion);
          },
          py::arg("base"), py::arg("axis"), py::arg("radius"), py::arg("height"), py::arg("material"),
          py::arg("bottom") = true, py::arg("top") = false, py::arg("segments") = 48, py::arg("thickness") = 0.0,
          py::arg("motion") = 0, py::arg("label") = "",
          "A cylindrical container as a scene's type = \"cylinder\" wall: `segments` flat sides whose inner faces lie\n"
          "at `radius` from the axis through `base`, from base to base + height * axis, with a floor (bottom) and a\n"
          "roof (top); thickness 0: 2% of the radius.")
      .def(
          "fill_region",
          [](dem::WorldBuilder& b, const py::object& shapes, std::size_t count, const py::object& lo,
             const py::object& hi, const py::object& material, const py::object& velocity, std::uint64_t seed,
             const py::object& weights, const std::string& label, bool fixed, const py::object& cylinder,
             const py::object& sphere, std::int64_t pieces, std::int64_t pieces_seed, std::int64_t relaxations) {
            dem::RegionFill f;
            const std::string who = label.empty() ? "region" : label;
            if (pieces < 0 || pieces > dem::kMaxBondedPieces)
              throw dem::BuildError(who, "pieces", "must be between 2 and " + std::to_string(dem::kMaxBondedPieces) +
                                                       " (0: no bonded assemblies)");
            if (pieces_seed < 0) throw dem::BuildError(who, "pieces_seed", "must be >= 0");
            if (relaxations < 0 || relaxations > 100) throw dem::BuildError(who, "relaxations", "must be between 0 and 100");
            f.pieces = static_cast<std::uint32_t>(pieces);
            f.pieces_seed = static_cast<std::uint64_t>(pieces_seed);
            f.relaxations = static_cast<int>(relaxations);
            f.variants = body_shapes(shapes);
            if (!weights.is_none()) f.weights = weights.cast<std::vector<double>>();
            f.count = count;
            f.round = region_arg("fill_region", lo, hi, cylinder, sphere, f.lo, f.hi);
            f.material = material_index(b, material);
            f.velocity = to_vec3(velocity, "velocity");
            f.fixed = fixed;
            f.label = label.empty() ? "region" : label;
            std::mt19937_64 rng(seed);
            return b.fill_region(f, rng);
          },
          py::arg("shapes"), py::arg("count"), py::arg("lo") = py::none(), py::arg("hi") = py::none(),
          py::arg("material") = py::none(), py::arg("velocity") = std::array<double, 3>{0, 0, 0}, py::arg("seed") = 1,
          py::arg("weights") = py::none(), py::arg("label") = "", py::arg("fixed") = false,
          py::arg("cylinder") = py::none(), py::arg("sphere") = py::none(), py::arg("pieces") = 0,
          py::arg("pieces_seed") = 1, py::arg("relaxations") = 3,
          "Places `count` bodies, each one of `shapes` at random (number probabilities `weights`, default\n"
          "equal), without overlap in the box [lo, hi], or in cylinder={base, axis, radius, height} or\n"
          "sphere={centre, radius} (each body's bounding sphere inside); returns their indices. pieces > 0:\n"
          "each body is a bonded assembly of its shape cut into that many glued pieces, the k-th's sites drawn\n"
          "from pieces_seed and k (add_bonded; its indices are the pieces').")
      .def(
          "add_inflow",
          [](dem::WorldBuilder& b, const py::object& shapes, const py::object& lo, const py::object& hi,
             const py::object& material, double rate, double mass_rate, double start, double stop,
             std::uint64_t count, const py::object& velocity, const py::object& weights, std::uint64_t seed,
             const std::string& label, const py::object& cylinder, const py::object& sphere) {
            dem::InflowDef d;
            d.variants = body_shapes(shapes);
            if (!weights.is_none()) d.weights = weights.cast<std::vector<double>>();
            d.round = region_arg("add_inflow", lo, hi, cylinder, sphere, d.lo, d.hi);
            d.material = material_index(b, material);
            d.rate = rate, d.mass_rate = mass_rate;
            d.start = start, d.stop = stop;
            d.count = count;
            d.velocity = to_vec3(velocity, "velocity");
            d.seed = seed;
            d.label = label.empty() ? "inflow" : label;
            return b.add_inflow(d);
          },
          py::arg("shapes"), py::arg("lo") = py::none(), py::arg("hi") = py::none(), py::arg("material") = py::none(),
          py::arg("rate") = 0.0, py::arg("mass_rate") = 0.0, py::arg("start") = 0.0,
          py::arg("stop") = std::numeric_limits<double>::infinity(), py::arg("count") = 0,
          py::arg("velocity") = std::array<double, 3>{0, 0, 0}, py::arg("weights") = py::none(),
          py::arg("seed") = 1, py::arg("label") = "", py::arg("cylinder") = py::none(), py::arg("sphere") = py::none(),
          "A region [lo, hi] (or cylinder={base, axis, radius, height}, height 0 a disc, or sphere={centre,\n"
          "radius}) inserting bodies during runs at `rate` bodies/s or `mass_rate` kg/s, from `start`\n"
          "until `stop` s or `count` bodies (give one), each one of `shapes` (number probabilities `weights`) at\n"
          "a random place and orientation where it touches nothing. Returns its index. The world keeps room for\n"
          "every body its inflows can insert, so views stay valid; they show the bodies there when made.")
      .def("accept_initial_overlaps", &dem::WorldBuilder::accept_initial_overlaps)
      .def_property_readonly("body_count", &dem::WorldBuilder::body_count)
      .def("build", &dem::WorldBuilder::build, "Checks and prepares everything; the builder is empty afterwards.");

  py::class_<World> world(m, "World", "A DEM world: bodies, walls and their contacts. Made by WorldBuilder or a scene.");
  def_view<std::uint64_t>(world, "ids", offsetof(Body, id), 0, false, "Global ids (N,), read-only view.");
  world.def_property_readonly(
      "names",
      [](const World& w) {
        py::dict d;
        for (const io::TracedBody& t : io::traced_bodies(w)) d[py::str(t.name)] = t.body;
        return d;
      },
      "The named bodies (add_body's name, a scene body's name): {name: index}; run(out=...) traces them.");
  def_view<std::uint16_t>(world, "fixed", offsetof(Body, fixed), 0, false, "1 for fixed bodies (N,), read-only view.");
  def_view<std::uint16_t>(world, "motions", offsetof(Body, motion), 0, false,
                          "The motion number (add_motion) of driven bodies, 0 for others (N,), read-only view.");
  // A view per viewed body channel (body_channels.hpp); one of the applied
  // loads turns them on in the world (World::applied_loads).
  for (const dem::BodyChannel& ch : dem::kBodyChannels) {
    if (!(ch.use & dem::kChannelViewed)) continue;
    const bool writable = ch.use & dem::kChannelWritable;
    const bool applied = writable && (ch.use & dem::kChannelLoad);  // a load may be written: count it
    const std::size_t offset = ch.offset;
    const py::ssize_t cols = ch.components == 1 ? 0 : ch.components;
    world.def_property_readonly(
        std::string(ch.view).c_str(),
        [=](py::object self) {
          World& w = self.cast<World&>();
          if (applied) w.applied_loads = true;
          return body_view<double>(w, self, offset, cols, writable);
        },
        std::string(ch.doc).c_str());
  }
  world.def_readonly("time", &World::time)
      .def_property_readonly(
          "cell",
          [](const World& w) {
            idle(w);
            py::dict d;
            if (!w.cell.now.active()) return d;
            const auto tensor = [](const dem::CellTensor& t) {
              py::dict out;
              for (int k = 0; k < 6; ++k) out[dem::kCellComponents[k]] = t[k];
              return out;
            };
            d["lo"] = py::make_tuple(w.cell.now.lo.x, w.cell.now.lo.y, w.cell.now.lo.z);
            d["hi"] = py::make_tuple(w.cell.now.hi.x, w.cell.now.hi.y, w.cell.now.hi.z);
            d["tilt"] = py::make_tuple(w.cell.now.tilt.x, w.cell.now.tilt.y, w.cell.now.tilt.z);
            d["volume"] = dem::cell_volume(w.cell.now);
            d["strain_rate"] = tensor(w.cell.rate);
            d["stress"] = tensor(w.cell.stress);
            return d;
          },
          "The periodic cell now ({} without one): lo, hi, tilt (xy, xz, yz), volume, and the velocity gradient and "
          "the contacts' stress (compression positive) by component")
      .def_property_readonly("settings", [](const World& w) { return w.settings; })
      .def_property_readonly("body_count", [](const World& w) { return w.bodies.size(); })
      .def_property_readonly("template_count", [](const World& w) { return w.templates.size(); },
                             "Shape templates: moving bodies given one Shape object share one.")
      .def(
          "angular_velocities",
          [](const World& w) {
            idle(w);
            py::array_t<double> out({static_cast<py::ssize_t>(w.bodies.size()), py::ssize_t{3}});
            double* p = out.mutable_data();
            for (std::size_t k = 0; k < w.bodies.size(); ++k) {
              const Vec3 o = dem::angular_velocity_of(w, w.bodies[k]);
              p[3 * k] = o.x, p[3 * k + 1] = o.y, p[3 * k + 2] = o.z;
            }
            return out;
          },
          "Angular velocities (N, 3), a new array computed from the angular momenta.")
      .def(
          "masses",
          [](const World& w) {
            idle(w);
            py::array_t<double> out(static_cast<py::ssize_t>(w.bodies.size()));
            for (std::size_t k = 0; k < w.bodies.size(); ++k) out.mutable_data()[k] = dem::mass_of(w, w.bodies[k]);
            return out;
          },
          "Masses (kg; infinite for fixed bodies), a new array.")
      .def(
          "set_positions",
          [](World& w, const py::object& values, const py::object& indices) {
            idle(w);
            const auto v = to_matrix(values, 3, "positions");
            const std::vector<std::size_t> idx = body_indices(w, indices, v.shape(0));
            for (std::size_t k = 0; k < idx.size(); ++k) {
              const Vec3 p{v.at(k, 0), v.at(k, 1), v.at(k, 2)};
              if (!is_finite(p)) fail("positions", "row " + std::to_string(k) + " is not finite");
              if (!(max_abs(p) <= kMaxCoordinate))  // as add_body refuses it
                fail("positions", "row " + std::to_string(k) + " is outside the supported range [-1e100, 1e100] m");
              if (w.bodies[idx[k]].fixed) fail("positions", "body " + std::to_string(idx[k]) + " is fixed");
            }
            for (std::size_t k = 0; k < idx.size(); ++k) w.bodies[idx[k]].position = {v.at(k, 0), v.at(k, 1), v.at(k, 2)};
            w.forces_current = false;
          },
          py::arg("values"), py::arg("indices") = py::none(),
          "Moves bodies' centres of mass ((N, 3) values; indices None: every body). Fixed bodies cannot move.")
      .def(
          "set_orientations",
          [](World& w, const py::object& values, const py::object& indices) {
            idle(w);
            const auto v = to_matrix(values, 4, "orientations");
            const std::vector<std::size_t> idx = body_indices(w, indices, v.shape(0));
            std::vector<Quat> q(idx.size());
            for (std::size_t k = 0; k < idx.size(); ++k) {
              q[k] = quat_from_row(v.data(static_cast<py::ssize_t>(k), 0), "orientations", static_cast<std::ptrdiff_t>(k));
              if (w.bodies[idx[k]].fixed) fail("orientations", "body " + std::to_string(idx[k]) + " is fixed");
            }
            for (std::size_t k = 0; k < idx.size(); ++k) w.bodies[idx[k]].orientation = q[k];
            w.forces_current = false;
          },
          py::arg("values"), py::arg("indices") = py::none(),
          "Turns bodies' principal frames (unit quaternions [w, x, y, z], (N, 4)).")
      .def(
          "step",
          [](World& w, double dt) {
            const InUse in_use(w);
            if (!(dt > 0 && std::isfinite(dt))) fail("dt", "must be finite and > 0");
            dem::StepReport r;
            {
              py::gil_scoped_release release;
              r = dem::step(w, dt);
            }
            if (r.status != dem::StepStatus::Ok) throw RunError(dem::describe_failure(w, r));
          },
          py::arg("dt"), "Advances the world by dt seconds (RunError when a pair cannot be computed).")
      .def(
          "run",
          [](py::object self, double duration, std::optional<double> dt, std::optional<double> output_every,
             const py::object& observer, std::optional<std::string> out, bool overwrite, bool frames,
             int checkpoint_every, bool progress, const py::object& listener, std::int64_t listener_every) {
            World& w = self.cast<World&>();
            const InUse in_use(w);
            std::optional<PyListener> listening = make_listener(self, listener, listener_every);
            std::vector<dem::StepListener*> listeners;
            if (listening) listeners.push_back(&*listening), w.applied_loads = true;
            const double step = dt ? *dt : dem::critical_time_step(w);
            dem::RunState state;
            try {
              state = dem::plan_run(duration, step, output_every ? *output_every : duration);
            } catch (const std::invalid_argument& e) {
              throw py::value_error(e.what());
            }
            if (checkpoint_every < 0) fail("checkpoint_every", "must be >= 0");
            // A run folder written as `gjkdem run` writes one (no scene.toml: the world came from Python).
            std::optional<io::RunFolderLock> lock;
            std::unique_ptr<io::RunFolderWriters> writers;
            if (out) {
              const io::RunPaths folder{*out};
              std::filesystem::create_directories(folder.dir);
              lock.emplace(folder.dir);
              io::prepare_run_folder(folder, overwrite);
              writers = std::make_unique<io::RunFolderWriters>(
                  folder, w,
                  io::RunWriterOptions{.frames = frames, .checkpoint_every = checkpoint_every, .traced = io::traced_bodies(w),
                                       .fingerprint = 0, .info_json = io::run_info_json(w, step)});
              writers->info().started(w, state);
            }
            std::vector<dem::RunObserver*> outputs =
                writers ? writers->observers() : std::vector<dem::RunObserver*>{};
            std::optional<PyProgress> shown;
            if (progress) outputs.push_back(&shown.emplace(state.step, duration));
            PyObserver o(self, observer);
            return run_with(
                o, outputs,
                [&](std::span<dem::RunObserver* const> obs, const std::function<std::string()>& stop) {
                  return dem::run(
                      w, state, obs,
                      [&] {
                        const std::string why = stop();
                        if (writers) writers->info().stopped_by = why;
                        return !why.empty();
                      },
                      {}, listeners);
                },
                listening ? &*listening : nullptr);
          },
          py::arg("duration"), py::arg("dt") = py::none(), py::arg("output_every") = py::none(),
          py::arg("observer") = py::none(), py::arg("out") = py::none(), py::arg("overwrite") = false,
          py::arg("frames") = false, py::arg("checkpoint_every") = io::kDefaultCheckpointEvery, py::arg("progress") = false,
          py::arg("listener") = py::none(), py::arg("listener_every") = 1,
          "Runs for `duration` s in steps of dt (None: critical_time_step), calling observer(world, state) at the\n"
          "start, every output_every s and at the end; an observer returning False stops the run.\n"
          "out: a run folder to write as `gjkdem run` does (view/ frames for the viewer and analyze, energy.csv,\n"
          "trace.csv of the named bodies, checkpoint.bin, run.json; overwrite replaces an earlier run's files;\n"
          "frames=True adds the VTK frames, which weigh about ten times the rest). progress=True prints the\n"
          "command's progress line on sys.stderr. listener(world, state) is called before the force evaluations\n"
          "of every listener_every steps (the first at step 0): it may set applied_forces and applied_torques,\n"
          "which act from that evaluation on (a drag, a field, a coupling; their work is in energies()).\n"
          "Returns \"completed\" or \"stopped\"; raises RunError when the run fails (guards, unsupported pairs).")
      .def("critical_time_step", &dem::critical_time_step)
      .def("stable_time_step", &dem::stable_time_step)
      .def(
          "measure",
          [](const World& w, py::object lo, py::object hi, const py::object& cylinder, const py::object& sphere) {
            idle(w);
            dem::MeasureRegion region;
            region.round = region_arg("measure", lo, hi, cylinder, sphere, region.lo, region.hi);
            dem::MeasureWorkspace work;
            dem::Measures r;
            try {
              r = dem::measure(w, dem::touching_contacts(w), region, work);
            } catch (const std::invalid_argument& e) {
              throw py::value_error(e.what());
            }
            py::dict d;
            d["solid_fraction"] = r.solid_fraction, d["solid_volume"] = r.solid_volume;
            d["region_volume"] = r.region_volume, d["grains"] = r.grains, d["coordination"] = r.coordination;
            d["contacts"] = r.contacts, d["mean_normal_force"] = r.mean_normal_force, d["pressure"] = r.pressure;
            py::array_t<double> stress({py::ssize_t{3}, py::ssize_t{3}});
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j) stress.mutable_at(i, j) = r.stress.row[i][j];
            d["stress"] = stress;
            d["normal_forces"] = py::array_t<double>(static_cast<py::ssize_t>(r.normal_forces.size()), r.normal_forces.data());
            return d;
          },
          py::arg("lo") = py::none(), py::arg("hi") = py::none(), py::arg("cylinder") = py::none(),
          py::arg("sphere") = py::none(),
          "Measurements in the box [lo, hi] (or cylinder={base, axis, radius, height}, or sphere={centre,\n"
          "radius}) from the last force evaluation (docs/measurements.md): a dict of\n"
          "solid_fraction, solid_volume, region_volume, grains, coordination, contacts, mean_normal_force,\n"
          "stress (3, 3; Love-Weber, compression positive, Pa), pressure and normal_forces (the contacts' |F.n|).")
      .def("contacts", &contacts_of,
           "The touching contacts of the last force evaluation: a dict of arrays (ids (M, 2): a wall's or\n"
           "body's id then the body's; points, normals (a -> b) and forces on b (M, 3); depth, overlap_volume).")
      .def(
          "energies",
          [](const World& w) {
            idle(w);
            py::dict d;
            d["kinetic"] = dem::kinetic_energy(w), d["potential"] = dem::potential_energy(w);
            d["elastic"] = w.stats.elastic_energy;
            d["wall_work"] = w.wall_work;
            double inflow = 0;
            for (const dem::InflowState& f : w.inflow_states) inflow += f.energy;
            d["inflow_energy"] = inflow;
            double applied = 0;
            for (const Body& b : w.bodies) applied += b.applied_work;
            d["applied_work"] = applied;
            d["split_energy"] = w.split_energy;
            return d;
          },
          "Kinetic, gravitational potential (zero at z = 0 along gravity) and elastic energy, the work driven\n"
          "walls and bodies did on the others so far, the energy inserted bodies brought in, the work of\n"
          "the applied loads (applied_forces) and what splits of broken grains stored in their fragments'\n"
          "contacts so far (J).")
      .def_property_readonly("contact_count", [](const World& w) { return w.stats.contacts; })
      .def_property_readonly("bonds", [](const World& w) { return w.bonds.size(); },
                             "How many bonds the world's bonded assemblies hold (docs/breakage.md), intact or broken.")
      .def_property_readonly("bonds_broken", [](const World& w) { return dem::broken_bonds(w.bonds); },
                             "Bonds broken so far.")
      .def_property_readonly("grains_broken", [](const World& w) { return w.broken; },
                             "Grains that broke so far (docs/breakage.md); each added a body.")
      .def(
          "save_checkpoint",
          [](const World& w, const std::string& path, std::optional<double> dt) {
            const InUse in_use(w, InUse::Reads);  // from its own observer too
            // The format keeps a run's clock; a world saved between runs keeps the step to go on with.
            io::Checkpoint c;
            c.run.dt = dt ? *dt : dem::critical_time_step(w);
            if (!(c.run.dt > 0 && std::isfinite(c.run.dt))) fail("dt", "must be finite and > 0");
            {
              py::gil_scoped_release release;
              io::save_checkpoint(path, w, c, 0);
            }
          },
          py::arg("path"), py::arg("dt") = py::none(),
          "Saves the world's state (bodies, springs, warm starts, clock) in the portable, checksummed\n"
          "checkpoint format (docs/checkpoints.md), with the time step to go on with (None: critical_time_step).")
      .def(
          "load_checkpoint",
          [](World& w, const std::string& path, bool restart) {
            const InUse in_use(w);
            py::gil_scoped_release release;
            return io::load_checkpoint(path, w, 0, restart ? io::Restore::NewRun : io::Restore::SameRun).run.dt;
          },
          py::arg("path"), py::arg("restart") = false,
          "Restores a saved state into this world, which must have the same bodies, shapes and walls (ids, shapes,\n"
          "fixed bodies' places, plane walls: else CheckpointError naming what differs); its materials, contact\n"
          "law settings and gravity may differ and take effect from the next step. restart=False: the saved run\n"
          "goes on (its clock; a checkpoint saved from Python); restart=True: a new run from that state (time 0,\n"
          "no wall work yet, forces recomputed), from any checkpoint, a `gjkdem run` folder's included.\n"
          "Returns the saved time step.");
}

}  // namespace gjkdem::py_bind
