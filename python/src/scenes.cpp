// TOML scenes from Python: read one into a World, or run one into a run
// folder exactly as `gjkdem run` does (io::SceneRun: the same files, the
// same bytes), with Python observers beside the writers.
#include <cmath>
#include <memory>

#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "gjkdem/io/analysis.hpp"
#include "gjkdem/io/scene_check.hpp"
#include "gjkdem/io/scene.hpp"
#include "gjkdem/io/scene_export.hpp"
#include "gjkdem/io/scene_run.hpp"
#include "py_run.hpp"

namespace gjkdem::py_bind {

void bind_scenes(py::module_& m) {
  py::class_<io::Scene>(m, "Scene", "A scene read from TOML (docs/scenes.md): its world and its run settings.")
      .def_property_readonly(
          "world", [](io::Scene& s) -> dem::World& { return s.world; }, py::return_value_policy::reference_internal)
      .def_readonly("duration", &io::Scene::duration)
      .def_readonly("dt", &io::Scene::dt)
      .def_readonly("output_every", &io::Scene::output_every)
      .def_readonly("output_dir", &io::Scene::output_dir)
      .def_readonly("warnings", &io::Scene::warnings)
      .def_property_readonly(
          "resolved", [](const io::Scene& s) { return py::module_::import("json").attr("loads")(s.resolved_json); },
          "The scene with every default filled in (a dict).");
  m.def(
      "load_scene",
      [](const std::string& path) { return io::load_scene_file(path); }, py::arg("path"),
      "Reads a TOML scene file (SceneError, a ValueError, names the line at fault).");
  m.def(
      "load_scene_text",
      [](const std::string& text, const std::string& base_dir) { return io::load_scene(text, "(scene text)", base_dir); },
      py::arg("text"), py::arg("base_dir") = ".", "Reads a scene from TOML text; mesh files are found from base_dir.");
  m.def("default_scene_text", [] { return std::string(io::default_scene_toml()); },
        "The TOML of the built-in default scene.");
  m.def(
      "load_run",
      [](const std::string& run_dir) { return io::load_run_checkpoint(run_dir); },
      py::arg("run_dir"),
      "The scene of a run folder (written by `gjkdem run` or SceneRun) with its world restored from the\n"
      "folder's checkpoint: the run's last saved state, to measure or continue from Python.");
  m.def(
      "export_scene",
      [](const std::string& run_dir, const std::optional<std::string>& path) {
        const std::string text = io::export_run_scene(run_dir);
        if (path) io::write_file_atomically(*path, text);
        return text;
      },
      py::arg("run_dir"), py::arg("path") = py::none(),
      "As `gjkdem export`: the run folder's last saved state as scene text (its moving bodies where they\n"
      "were, their shapes in a [shapes] table; settings, materials, walls and fixed bodies the run's own),\n"
      "written to `path` too when given. Edit it freely and run it as any scene.");
  m.def(
      "analyze",
      [](const std::string& run_dir, const std::optional<std::pair<py::object, py::object>>& region, std::uint64_t every,
         const dem::World* world, const py::object& cylinder, const py::object& sphere) {
        io::AnalysisOptions options;
        if (region || !cylinder.is_none() || !sphere.is_none()) {
          dem::MeasureRegion r;
          r.round = region_arg("analyze", region ? region->first : py::none(), region ? region->second : py::none(),
                               cylinder, sphere, r.lo, r.hi);
          options.region = r;
        }
        options.every = every;
        if (world) idle(*world);
        const io::AnalysisSummary s = io::analyze_run(run_dir, options, {}, world);
        py::dict d;
        d["frames"] = s.frames, d["seconds"] = s.seconds, d["largest_frame"] = s.largest_frame;
        return d;
      },
      py::arg("run_dir"), py::arg("region") = py::none(), py::arg("every") = 1, py::arg("world") = py::none(),
      py::arg("cylinder") = py::none(), py::arg("sphere") = py::none(),
      "As `gjkdem analyze`: measures every `every`th frame of a run's view/ in the box region = (lo, hi),\n"
      "or cylinder={base, axis, radius, height}, or sphere={centre, radius}\n"
      "(None: around the moving bodies, frame by frame) and writes run_dir/analysis/measures.csv and\n"
      "normal_forces.csv (docs/measurements.md). Returns {frames, seconds, largest_frame}. The shapes come\n"
      "from the folder's scene, or from `world`: the World whose run(out=...) wrote a folder from Python.");

  m.def(
      "check_scene",
      [](const std::optional<std::string>& scene, int threads, double sample_seconds) {
        if (!(sample_seconds >= 0) || !std::isfinite(sample_seconds))
          throw py::value_error("check_scene: sample_seconds must be finite and >= 0");
        io::SceneCheck c;
        {
          py::gil_scoped_release release;
          c = io::check_scene(scene.value_or(""), threads, sample_seconds);
        }
        py::dict d;
        d["bodies"] = c.bodies, d["moving"] = c.moving, d["fixed"] = c.fixed, d["templates"] = c.templates;
        d["inflow_room"] = c.inflow_room, d["threads"] = c.threads, d["duration"] = c.duration, d["dt"] = c.dt;
        d["dt_auto"] = c.dt_auto, d["steps"] = c.steps, d["outputs"] = c.outputs, d["out_dir"] = c.out_dir;
        d["sampled_steps"] = c.sampled_steps, d["seconds_per_step"] = c.seconds_per_step;
        d["estimated_seconds"] = c.estimated_seconds, d["output_bytes"] = c.output_bytes;
        d["checkpoint_bytes"] = c.checkpoint_bytes, d["estimated_bytes"] = c.estimated_bytes;
        d["warnings"] = c.warnings;
        d["failure"] = c.failure.empty() ? py::object(py::none()) : py::object(py::str(c.failure));
        d["summary"] = io::describe(c);
        return d;
      },
      py::arg("scene") = py::none(), py::arg("threads") = -1, py::arg("sample_seconds") = 2.0,
      "As `gjkdem run --check`: every check of the scene (SceneError) and of a run's start, then a few steps\n"
      "timed in a scratch folder (about sample_seconds of wall time); returns a dict: bodies, steps, dt,\n"
      "estimated_seconds (at the first steps' pace), estimated_bytes, failure (None, or why the run would\n"
      "fail), summary (the command's text). Nothing is written where the run would write.");
  py::class_<io::SceneRun, std::unique_ptr<io::SceneRun>>(
      m, "SceneRun",
      "A scene run into its folder as `gjkdem run` does: frames, trace.csv, energy.csv, checkpoints, run.json.\n"
      "SceneRun(scene=None, out=None, overwrite=False, threads=-1): a new run (scene None: the default scene;\n"
      "out None: the scene's output.directory). SceneRun.resume(folder): takes a run up from its checkpoint.\n"
      "start_from=FOLDER (or a checkpoint file): a new run from that run's last state, its clock at 0, as\n"
      "`gjkdem run SCENE --from FOLDER`: same bodies, shapes and walls (else CheckpointError naming what\n"
      "differs); materials, contact law settings, gravity, motions, duration and outputs may change.")
      .def(py::init([](const std::optional<std::string>& scene, const std::optional<std::string>& out, bool overwrite,
                       int threads, const std::optional<std::string>& start_from) {
             return io::SceneRun::start(scene.value_or(""), {.out = out.value_or(""),
                                                             .overwrite = overwrite,
                                                             .threads = threads,
                                                             .start_from = start_from.value_or("")});
           }),
           py::arg("scene") = py::none(), py::arg("out") = py::none(), py::arg("overwrite") = false,
           py::arg("threads") = -1, py::arg("start_from") = py::none())
      .def_static(
          "resume", [](const std::string& folder, int threads) { return io::SceneRun::resume(folder, threads); },
          py::arg("folder"), py::arg("threads") = -1)
      .def_static(
          "completed", [](const std::string& folder) { return io::SceneRun::completed(folder); }, py::arg("folder"),
          "True when the run in `folder` completed.")
      .def_property_readonly(
          "world", [](io::SceneRun& r) -> dem::World& { return r.scene.world; },
          py::return_value_policy::reference_internal)
      .def_property_readonly("scene", [](io::SceneRun& r) -> io::Scene& { return r.scene; },
                             py::return_value_policy::reference_internal)
      .def_property_readonly("state", [](const io::SceneRun& r) { return r.state; })
      .def_property_readonly("folder", [](const io::SceneRun& r) { return r.folder.dir.string(); })
      .def(
          "run",
          [](py::object self, const py::object& observer, std::optional<std::uint64_t> stop_after, bool progress,
             const py::object& listener, std::int64_t listener_every) {
            io::SceneRun& r = self.cast<io::SceneRun&>();
            const InUse in_use(r.scene.world);
            PyObserver o(self.attr("world"), observer);
            std::optional<PyListener> listening = make_listener(self.attr("world"), listener, listener_every);
            std::vector<dem::StepListener*> listeners;
            if (listening) listeners.push_back(&*listening);
            std::optional<PyProgress> shown;
            std::vector<dem::RunObserver*> extra;
            if (progress) extra.push_back(&shown.emplace(r.state.step, r.scene.duration));
            return run_with(
                o, extra,
                [&](std::span<dem::RunObserver* const> obs, const std::function<std::string()>& stop) {
                  return r.run(
                      obs,
                      [&]() -> std::string {
                        if (stop_after && r.state.step >= *stop_after) return "stop_after";
                        return stop();
                      },
                      nullptr, listeners);
                },
                listening ? &*listening : nullptr);
          },
          py::arg("observer") = py::none(), py::arg("stop_after") = py::none(), py::arg("progress") = false,
          py::arg("listener") = py::none(), py::arg("listener_every") = 1,
          "Runs to the end (or until step stop_after), calling observer(world, state) at each output;\n"
          "progress=True prints the command's progress line on sys.stderr. listener(world, state) is called\n"
          "before the force evaluations of every listener_every steps (the first at step 0): it may set the\n"
          "world's applied_forces and applied_torques (docs/python.md).\n"
          "Returns \"completed\" or \"stopped\" (resume with SceneRun.resume(folder)).");
}

}  // namespace gjkdem::py_bind
