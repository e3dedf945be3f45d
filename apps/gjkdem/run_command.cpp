// gjkdem run: options, signals and the progress bar. The run itself (steps,
// outputs, energy balance, checkpoints, run.json) is the library's:
// dem::run with the observers of io/run_observers.hpp.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "commands.hpp"
#include "gjkdem/io/run_observers.hpp"
#include "gjkdem/io/scene.hpp"

namespace gjkdem::app {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t g_stop_signal = 0;  // set by the handler only
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

constexpr const char* kVersion = "0.1.0";

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw io::SceneError("cannot read " + file.string());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, s / 60 % 60);
  else std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  return buf;
}

// Progress on standard error: a bar redrawn in place on a terminal, a plain
// line every 10 s (and at the end) otherwise.
class Progress : public dem::RunObserver {
 public:
  Progress(bool quiet, std::uint64_t first_step, Real duration)
      : quiet_(quiet), tty_(isatty(STDERR_FILENO)), first_(first_step), duration_(duration), start_(Clock::now()),
        last_(start_) {}
  void on_output(const dem::World&, const dem::RunState&) override {}
  void on_step(const dem::World& w, const dem::RunState& s) override { update(w, s, false); }
  void on_stop(const dem::World& w, const dem::RunState& s, const dem::RunOutcome&) override { update(w, s, true); }
  void on_warning(const dem::World&, const dem::RunState&, const std::string& message) override {
    std::cerr << (tty_ ? "\n" : "") << "gjkdem: warning: " << message << "\n";
  }

 private:
  void update(const dem::World& w, const dem::RunState& s, bool final) {
    if (quiet_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (!final && since < (tty_ ? 0.25 : 10.0)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? static_cast<double>(s.step - first_) / elapsed : 0;
    const double eta = rate > 0 ? static_cast<double>(s.steps_total - s.step) / rate : NAN;
    const double frac = s.steps_total ? static_cast<double>(s.step) / static_cast<double>(s.steps_total) : 1;
    char line[200];
    std::snprintf(line, sizeof line, "t = %.4f / %.4g s  %5.1f%%  %.0f steps/s  ETA %s", w.time, duration_,
                  100 * frac, rate, duration_text(eta).c_str());
    if (tty_) {
      const int width = 24, done = static_cast<int>(frac * width);
      std::cerr << "\r[" << std::string(done, '#') << std::string(width - done, '.') << "] " << line << "   "
                << (final ? "\n" : "") << std::flush;
    } else {
      std::cerr << "gjkdem: " << line << "\n";
    }
  }

  bool quiet_, tty_;
  std::uint64_t first_;
  Real duration_;
  Clock::time_point start_, last_;
};

Json base_info(const io::Scene& s, const std::string& scene_file, const fs::path& base_dir) {
  Json info;
  info["version"] = kVersion;
  info["status"] = "starting";
  info["scene_file"] = scene_file;
  info["scene_base"] = fs::absolute(base_dir).string();
  info["scene"] = Json::parse(s.resolved_json);
  info["bodies"] = s.world.bodies.size();
  info["shape_templates"] = s.world.templates.size();
  info["threads"] = s.world.settings.threads;
  info["warnings"] = s.warnings;
  info["dt"] = s.dt;
  return info;
}

int resolve_threads(int requested) {
#ifdef _OPENMP
  if (requested <= 0) return omp_get_max_threads();
#endif
  return requested <= 0 ? 1 : requested;
}

void install_signal_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

}  // namespace

int run_simulation(const RunOptions& opt) {
  std::string text, source, scene_file;
  fs::path base;
  io::RunPaths folder;
  try {
    if (!opt.resume.empty()) {
      folder.dir = opt.resume;
      if (!fs::exists(folder.checkpoint()))
        throw io::SceneError(folder.dir.string() + " holds no checkpoint.bin to resume from");
      const Json previous = Json::parse(read_text(folder.run_json()), nullptr, false);
      if (previous.is_discarded() || !previous.contains("scene_base"))
        throw io::SceneError(folder.run_json().string() + " is missing or unreadable");
      if (previous.value("status", "") == "completed") {
        std::cerr << "gjkdem: the run in " << folder.dir.string() << " is already completed\n";
        return 0;
      }
      text = read_text(folder.scene());
      source = folder.scene().string();
      scene_file = previous.value("scene_file", "");
      base = previous["scene_base"].get<std::string>();
    } else if (!opt.scene.empty()) {
      text = read_text(opt.scene);
      source = scene_file = opt.scene;
      base = fs::path(opt.scene).parent_path();
      if (base.empty()) base = ".";
    } else {
      text = io::default_scene_toml();
      source = "(built-in default scene)";
      scene_file = "";
      base = fs::current_path();
    }
    io::Scene scene = io::load_scene(text, source, base);
    for (const std::string& w : scene.warnings) std::cerr << "gjkdem: warning: " << w << "\n";
    if (opt.threads >= 0) scene.world.settings.threads = opt.threads;
    scene.world.settings.threads = resolve_threads(scene.world.settings.threads);
    dem::RunState state;
    try {
      state = dem::plan_run(scene.duration, scene.dt, scene.output_every);
    } catch (const std::invalid_argument& e) {
      throw io::SceneError(source + ": " + e.what());
    }
    std::optional<io::RunFolderLock> lock;
    if (opt.resume.empty()) {
      folder.dir = opt.out.empty() ? fs::path(scene.output_dir) : fs::path(opt.out);
      fs::create_directories(folder.dir);
      lock.emplace(folder.dir);
      io::prepare_run_folder(folder, opt.overwrite || scene.overwrite);
      io::write_file_atomically(folder.scene(), text);
    } else {
      lock.emplace(folder.dir);
      io::remove_stale_temporaries(folder);
    }
    const std::uint64_t fingerprint = io::fnv1a64(text);
    io::FrameWriter frames(folder.frames(), scene.world, scene.write_frames);
    io::TraceWriter trace(scene.traced);
    io::EnergyWriter energy;
    double wall_before = 0;
    if (opt.resume.empty()) {
      trace.start(folder.trace(), io::trace_header());
      energy.start(folder.energy(), io::energy_header());
    } else {
      const io::Checkpoint c = io::load_checkpoint(folder.checkpoint(), scene.world, fingerprint);
      if (c.run.steps_total != state.steps_total || c.run.dt != state.dt ||
          c.run.steps_per_output != state.steps_per_output)
        throw io::CheckpointError(folder.checkpoint().string() + " does not match the scene's duration and steps");
      state = c.run;
      frames.frames = c.logs.frames;
      trace.resume(folder.trace(), c.logs.trace_bytes);
      energy.resume(folder.energy(), c.logs.energy_bytes);
      wall_before = c.logs.wall_seconds;
    }
    io::Checkpointer checkpoints(folder.checkpoint(), scene.checkpoint_every, fingerprint, frames, trace, energy,
                                 wall_before);
    io::RunInfoWriter info(folder.run_json(), base_info(scene, scene_file, base).dump(), checkpoints);
    // After a kill, run.json tells how far the last checkpoint got.
    checkpoints.saved = [&](const dem::World& w, const dem::RunState& s) { info.started(w, s); };
    Progress progress(opt.quiet, state.step, scene.duration);
    dem::RunObserver* observers[] = {&frames, &trace, &energy, &checkpoints, &info, &progress};
    if (!opt.quiet)
      std::cerr << "gjkdem: " << scene.world.bodies.size() << " bodies, " << scene.world.templates.size()
                << " shape templates, dt = " << scene.dt << " s, " << scene.world.settings.threads
                << " threads, output in " << folder.dir.string() << "\n";
    install_signal_handlers();
    info.started(scene.world, state);
    const auto stop = [&] {
      if (g_stop_signal) {
        info.stopped_by = g_stop_signal == SIGINT ? "SIGINT" : "SIGTERM";
        return true;
      }
      if (opt.stop_after >= 0 && state.step >= static_cast<std::uint64_t>(opt.stop_after)) {
        info.stopped_by = "--stop-after";
        return true;
      }
      return false;
    };
    const dem::RunOutcome outcome = dem::run(scene.world, state, observers, stop, scene.guards);
    switch (outcome.status) {
      case dem::RunStatus::Completed:
        if (!opt.quiet)
          std::cerr << "gjkdem: completed " << state.step << " steps (" << scene.world.bodies.size()
                    << " bodies) in " << duration_text(checkpoints.wall_seconds()) << "; results in "
                    << folder.dir.string() << "\n";
        return 0;
      case dem::RunStatus::Stopped:
        if (!opt.quiet)
          std::cerr << "gjkdem: stopped at t = " << scene.world.time << " s; continue with: gjkdem run --resume "
                    << folder.dir.string() << "\n";
        return 130;
      case dem::RunStatus::Failed:
        std::cerr << "\ngjkdem: run failed: " << outcome.error << "\n";
        return 1;
    }
    return 1;
  } catch (const io::SceneError& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  } catch (const io::CheckpointError& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  } catch (const io::RunFolderError& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  } catch (const fs::filesystem_error& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  } catch (const std::runtime_error& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gjkdem::app
