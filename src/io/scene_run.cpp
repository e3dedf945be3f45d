#include "gjkdem/io/scene_run.hpp"

#include <algorithm>
#include <sstream>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/io/scene_export.hpp"

namespace gjkdem::io {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// "Every core" (0) is every core this process may use: under mpirun, the
// node's cores shared among its ranks (Open MPI says how many there are).
int resolve_threads(int requested) {
  if (requested > 0) return requested;
  int cores = 1;
#ifdef _OPENMP
  cores = omp_get_max_threads();
#endif
  const char* local_ranks = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  const int ranks = local_ranks ? std::atoi(local_ranks) : 1;
  return ranks > 1 ? std::max(1, cores / ranks) : cores;
}

Json read_run_json(const RunPaths& folder) {
  std::string text;
  try {
    text = read_text_file(folder.run_json());
  } catch (const SceneError&) {
    throw SceneError(folder.run_json().string() + " is missing or unreadable");
  }
  Json j = Json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw SceneError(folder.run_json().string() + " is not a run's JSON");
  if (!j.contains("scene_base") || !j["scene_base"].is_string())
    throw SceneError(folder.run_json().string() + " names no scene to rebuild the world from (a folder written by "
                     "World.run(out=...) from Python keeps none: continue it with that World's load_checkpoint, "
                     "measure it with gjkdem.analyze(folder, world=that World))");
  return j;
}

// What a run folder keeps of its scene: the text (its checkpoints carry its
// fingerprint), where its files were read from and the scene file's name.
struct FolderScene {
  std::string text;
  fs::path base;
  std::string scene_file;
};

FolderScene read_folder_scene(const RunPaths& folder) {
  const Json info = read_run_json(folder);
  return {read_text_file(folder.scene()), info["scene_base"].get<std::string>(), info.value("scene_file", "")};
}

// The run of a scene, its errors named after `source`.
dem::RunState plan_scene(const Scene& scene, const std::string& source) {
  try {
    return dem::plan_run(scene.duration, scene.dt, scene.output_every);
  } catch (const std::invalid_argument& e) {  // named by the keys that set the run's length and cadence
    const std::string why = e.what();
    const char* keys = why.find("output") != std::string::npos ? "output.every" : "simulation.duration and dt";
    throw SceneError(source + ": " + keys + ": " + why);
  }
}

}  // namespace

const char* version() noexcept { return GJKDEM_VERSION; }

SceneRun::~SceneRun() = default;

bool SceneRun::completed(const fs::path& dir) {
  RunPaths folder{dir};
  std::error_code ec;
  if (!fs::exists(folder.run_json(), ec)) return false;
  const Json j = Json::parse(read_text_file(folder.run_json()), nullptr, false);
  return j.is_object() && j.value("status", "") == "completed";
}

std::unique_ptr<SceneRun> SceneRun::start(const std::string& scene_file, const SceneRunOptions& options) {
  std::unique_ptr<SceneRun> r(new SceneRun);
  std::string text, source;
  fs::path base;
  if (scene_file.empty()) {
    text = default_scene_toml();
    source = "(built-in default scene)";
    base = fs::current_path();
  } else {
    text = read_text_file(scene_file);
    source = scene_file;
    base = fs::path(scene_file).parent_path();
    if (base.empty()) base = ".";
  }
  r->scene = load_scene(text, source, base, options.on_build);
  if (options.threads >= 0) r->scene.world.settings.threads = options.threads;
  r->state = plan_scene(r->scene, source);
  r->folder.dir = options.out.empty() ? fs::path(r->scene.output_dir) : options.out;
  if (!options.start_from.empty()) {
    std::error_code ec;
    const fs::path file =
        fs::is_directory(options.start_from, ec) ? RunPaths{options.start_from}.checkpoint() : options.start_from;
    if (!fs::exists(file, ec))
      throw SceneError(file.string() + " does not exist: --from takes a run folder holding a checkpoint.bin, or a "
                       "checkpoint file");
    if (fs::equivalent(fs::absolute(r->folder.dir), fs::absolute(file.parent_path()), ec))
      throw SceneError("the run would write into " + r->folder.dir.string() + ", the folder it starts from: give "
                       "it another output folder (--out)");
    load_checkpoint(file, r->scene.world, 0, Restore::NewRun);
  }
  if (options.follower) {
    r->scene.world.settings.threads = resolve_threads(r->scene.world.settings.threads);
    return r;
  }
  fs::create_directories(r->folder.dir);
  r->lock_.emplace(r->folder.dir);
  prepare_run_folder(r->folder, options.overwrite || r->scene.overwrite);
  write_file_atomically(r->folder.scene(), text);
  r->open_writers(text, scene_file, base, false, options.start_from);
  return r;
}

std::unique_ptr<SceneRun> SceneRun::resume(const fs::path& dir, int threads, bool follower,
                                          const dem::BuildProgress& on_build) {
  std::unique_ptr<SceneRun> r(new SceneRun);
  r->folder.dir = dir;
  if (!fs::exists(r->folder.checkpoint()))
    throw SceneError(dir.string() + " holds no checkpoint.bin to resume from");
  const FolderScene saved = read_folder_scene(r->folder);
  r->scene = load_scene(saved.text, r->folder.scene().string(), saved.base, on_build);
  if (threads >= 0) r->scene.world.settings.threads = threads;
  r->state = plan_scene(r->scene, r->folder.scene().string());
  if (follower) {
    dem::World& world = r->scene.world;
    world.settings.threads = resolve_threads(world.settings.threads);
    const Checkpoint c = load_checkpoint(r->folder.checkpoint(), world, fnv1a64(saved.text));
    r->state = c.run;
    return r;
  }
  r->lock_.emplace(r->folder.dir);
  remove_stale_temporaries(r->folder);
  r->open_writers(saved.text, saved.scene_file, saved.base, true, {});
  return r;
}

Scene load_run_scene(const fs::path& dir) {
  const RunPaths folder{dir};
  const FolderScene saved = read_folder_scene(folder);
  return load_scene(saved.text, folder.scene().string(), saved.base);
}

Scene load_run_checkpoint(const fs::path& dir) {
  const RunPaths folder{dir};
  const FolderScene saved = read_folder_scene(folder);
  Scene scene = load_scene(saved.text, folder.scene().string(), saved.base);
  if (!fs::exists(folder.checkpoint()))
    throw SceneError(dir.string() + " holds no checkpoint.bin (the run kept none: output.checkpoint_every = 0, "
                     "or it ended before its first)");
  load_checkpoint(folder.checkpoint(), scene.world, fnv1a64(saved.text));
  return scene;
}

std::string export_run_scene(const fs::path& dir) {
  const RunPaths folder{dir};
  const FolderScene saved = read_folder_scene(folder);
  const Scene scene = load_run_checkpoint(dir);
  std::ostringstream header;
  header << "The state of the run in " << fs::absolute(dir).lexically_normal().string() << " at t = "
         << scene.world.time << " s (its last checkpoint), exported by gjkdem " << version() << ":\n"
         << "its moving bodies as they were then (generators and inflows removed), touching as they were\n"
         << "(simulation.initial_overlaps = \"accept\"); contact springs start at 0, motions at t = 0.";
  return export_scene(saved.text, saved.base, scene.world, header.str());
}

std::string run_info_json(const dem::World& world, Real dt) {
  Json info;
  info["version"] = version();
  info["status"] = "starting";
  info["bodies"] = world.bodies.size();
  info["shape_templates"] = world.templates.size();
  info["threads"] = world.settings.threads;
  info["dt"] = dt;
  return info.dump();
}

void SceneRun::open_writers(const std::string& text, const std::string& scene_file, const fs::path& base,
                            bool resuming, const fs::path& start_from) {
  dem::World& world = scene.world;
  world.settings.threads = resolve_threads(world.settings.threads);
  Json info = Json::parse(run_info_json(world, scene.dt));
  info["scene_file"] = scene_file;
  info["scene_base"] = fs::absolute(base).string();
  if (!start_from.empty()) info["started_from"] = fs::absolute(start_from).string();
  info["scene"] = Json::parse(scene.resolved_json);
  info["warnings"] = scene.warnings;
  const RunWriterOptions options{.frames = scene.write_frames,
                                 .view = scene.write_view,
                                 .checkpoint_every = scene.checkpoint_every,
                                 .traced = traced_bodies(scene.world),
                                 .fingerprint = fnv1a64(text),
                                 .info_json = info.dump()};
  if (!resuming) {
    writers_ = std::make_unique<RunFolderWriters>(folder, world, options);
    return;
  }
  const Checkpoint c = load_checkpoint(folder.checkpoint(), world, options.fingerprint);
  if (c.run.steps_total != state.steps_total || c.run.dt != state.dt ||
      c.run.steps_per_output != state.steps_per_output)
    throw CheckpointError(folder.checkpoint().string() + " does not match the scene's duration and steps");
  state = c.run;
  writers_ = std::make_unique<RunFolderWriters>(folder, world, options, c);
}

double SceneRun::wall_seconds() const { return writers_ ? writers_->wall_seconds() : 0.0; }

dem::RunOutcome SceneRun::run(std::span<dem::RunObserver* const> extra, const std::function<std::string()>& stop,
                              dem::DomainTransport* transport, std::span<dem::StepListener* const> listeners) {
  const bool domains = transport && transport->size() > 1;
  // A run with listeners has applied loads, set here before energy.csv
  // takes their column (a checkpoint written then must say so).
  if (!listeners.empty()) scene.world.applied_loads = true;
  if (scene.world.applied_loads && writers_) writers_->take_applied_work(scene.world, state);
  if (!writers_) {  // a follower: its own stop request counts too (a signal may reach it alone)
    if (!domains) throw std::logic_error("SceneRun: a follower runs only on domains");
    const auto asked = [&] { return stop && !stop().empty(); };
    return dem::run_domains(scene.world, state, {}, *transport, asked, scene.guards, {}, nullptr, listeners);
  }
  std::vector<dem::RunObserver*> observers = writers_->observers();
  observers.insert(observers.end(), extra.begin(), extra.end());
  RunInfoWriter& info = writers_->info();
  info.ranks = domains ? transport->size() : 1;
  info.started(scene.world, state);
  const auto stop_and_say = [&] {
    if (!stop) return false;
    info.stopped_by = stop();
    return !info.stopped_by.empty();
  };
  dem::OneRank alone;
  return dem::run_domains(scene.world, state, observers, transport ? *transport : alone, stop_and_say, scene.guards,
                          {}, &domain_report, listeners);
}

}  // namespace gjkdem::io
