// gjkdem run: a DEM simulation from a scene, its outputs, progress, clean
// stops on Ctrl-C / SIGTERM, checkpoints and --resume.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "commands.hpp"
#include "gjkdem/io/run_output.hpp"
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

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
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
class Progress {
 public:
  Progress(bool quiet, std::uint64_t first_step, std::uint64_t total)
      : quiet_(quiet), tty_(isatty(STDERR_FILENO)), first_(first_step), total_(total), start_(Clock::now()),
        last_(start_) {}
  void update(std::uint64_t step, Real time, Real duration, bool final = false) {
    if (quiet_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (!final && since < (tty_ ? 0.25 : 10.0)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? static_cast<double>(step - first_) / elapsed : 0;
    const double eta = rate > 0 ? static_cast<double>(total_ - step) / rate : NAN;
    const double frac = total_ ? static_cast<double>(step) / static_cast<double>(total_) : 1;
    char line[200];
    std::snprintf(line, sizeof line, "t = %.4f / %.4g s  %5.1f%%  %.0f steps/s  ETA %s", time, duration, 100 * frac,
                  rate, duration_text(eta).c_str());
    if (tty_) {
      const int width = 24, done = static_cast<int>(frac * width);
      std::cerr << "\r[" << std::string(done, '#') << std::string(width - done, '.') << "] " << line << "   "
                << (final ? "\n" : "") << std::flush;
    } else {
      std::cerr << "gjkdem: " << line << "\n";
    }
  }

 private:
  bool quiet_, tty_;
  std::uint64_t first_, total_;
  Clock::time_point start_, last_;
};

struct RunFolder {
  fs::path dir;
  fs::path frames() const { return dir / "frames"; }
  fs::path checkpoint() const { return dir / "checkpoint.bin"; }
  fs::path trace() const { return dir / "trace.csv"; }
  fs::path energy() const { return dir / "energy.csv"; }
  fs::path run_json() const { return dir / "run.json"; }
  fs::path scene() const { return dir / "scene.toml"; }
};

class Runner {
 public:
  Runner(io::Scene scene, RunFolder folder, Json info, const RunOptions& opt)
      : s_(std::move(scene)), f_(std::move(folder)), info_(std::move(info)), opt_(opt) {
    for (const dem::ShapeTemplate& t : s_.world.templates) meshes_.push_back(io::display_mesh(t.shape));
    total_ = static_cast<std::uint64_t>(std::ceil(s_.duration / s_.dt - 1e-9));
    per_frame_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(s_.output_every / s_.dt)));
  }

  // A new run: headers, frame 0.
  void start() {
    write_text(f_.trace(), io::trace_header());
    write_text(f_.energy(), io::energy_header());
    p_.initial_energy = dem::kinetic_energy(s_.world) + dem::potential_energy(s_.world);
    open_logs();
    write_frame();
  }

  // A stopped run: the checkpoint's state, the logs cut back to it.
  void resume() {
    p_ = io::load_checkpoint(f_.checkpoint(), s_.world);
    fs::resize_file(f_.trace(), p_.trace_bytes);
    fs::resize_file(f_.energy(), p_.energy_bytes);
    open_logs();
  }

  int run() {
    write_info("running");
    Progress progress(opt_.quiet, p_.step, total_);
    const auto t0 = Clock::now();
    const double wall_before = p_.wall_seconds;
    auto wall = [&] { return wall_before + std::chrono::duration<double>(Clock::now() - t0).count(); };
    try {
      while (p_.step < total_) {
        if (g_stop_signal || (opt_.stop_after >= 0 && p_.step >= static_cast<std::uint64_t>(opt_.stop_after))) {
          p_.wall_seconds = wall();
          checkpoint();
          progress.update(p_.step, s_.world.time, s_.duration, true);
          info_["stopped_by"] = g_stop_signal ? (g_stop_signal == SIGINT ? "SIGINT" : "SIGTERM") : "--stop-after";
          write_info("interrupted", wall());
          if (!opt_.quiet)
            std::cerr << "gjkdem: stopped at t = " << s_.world.time << " s; continue with: gjkdem run --resume "
                      << f_.dir.string() << "\n";
          return 130;
        }
        dem::step(s_.world, s_.dt);
        ++p_.step;
        if (p_.step % per_frame_ == 0 || p_.step == total_) {
          check_finite();
          write_frame();
          p_.wall_seconds = wall();
          if (s_.checkpoint_every > 0 && p_.frame % static_cast<std::uint64_t>(s_.checkpoint_every) == 0) checkpoint();
        }
        progress.update(p_.step, s_.world.time, s_.duration);
      }
    } catch (const std::exception& e) {
      info_["error"] = e.what();
      write_info("failed", wall());
      std::cerr << "\ngjkdem: run failed: " << e.what() << "\n";
      return 1;
    }
    progress.update(p_.step, s_.world.time, s_.duration, true);
    p_.wall_seconds = wall();
    write_info("completed", wall());
    if (!opt_.quiet)
      std::cerr << "gjkdem: completed " << p_.step << " steps (" << s_.world.bodies.size() << " bodies) in "
                << duration_text(wall()) << "; results in " << f_.dir.string() << "\n";
    return 0;
  }

 private:
  void open_logs() {
    trace_.open(f_.trace(), std::ios::binary | std::ios::app);
    energy_.open(f_.energy(), std::ios::binary | std::ios::app);
    if (!trace_ || !energy_) throw std::runtime_error("cannot open the logs in " + f_.dir.string());
  }

  void check_finite() const {
    for (const dem::Body& b : s_.world.bodies)
      if (!is_finite(b.position) || !is_finite(b.velocity) || !is_finite(b.angular_momentum))
        throw std::runtime_error("body " + std::to_string(b.id) + " has a non-finite state at t = " +
                                 std::to_string(s_.world.time) + " s (time step too large for the stiffness?)");
  }

  void write_frame() {
    const dem::World& w = s_.world;
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06llu.vtk", static_cast<unsigned long long>(p_.frame));
    if (s_.write_frames) {
      io::write_vtk_frame(f_.frames() / name, w, meshes_);
      p_.frames.emplace_back(name, w.time);
      io::write_frame_series(f_.frames() / "frames.vtk.series", p_.frames);
    }
    for (const io::TracedBody& t : s_.traced) trace_ << io::trace_row(w, t.name, w.bodies[t.body]);
    const Real kinetic = dem::kinetic_energy(w), potential = dem::potential_energy(w), elastic = w.elastic_energy;
    energy_ << io::energy_row(w.time, kinetic, potential, elastic, p_.initial_energy - kinetic - potential - elastic,
                              w.last_contacts);
    trace_.flush();
    energy_.flush();
    if (!trace_ || !energy_) throw std::runtime_error("cannot write the logs in " + f_.dir.string());
    ++p_.frame;
  }

  void checkpoint() {
    trace_.flush();
    energy_.flush();
    p_.trace_bytes = fs::file_size(f_.trace());
    p_.energy_bytes = fs::file_size(f_.energy());
    io::save_checkpoint(f_.checkpoint(), s_.world, p_);
  }

  void write_info(const std::string& status, double wall_seconds = 0) {
    info_["status"] = status;
    info_["steps"] = p_.step;
    info_["steps_total"] = total_;
    info_["simulated_time"] = s_.world.time;
    info_["frames"] = p_.frame;
    info_["wall_time_s"] = wall_seconds;
    write_text(f_.run_json(), info_.dump(2) + "\n");
  }

  io::Scene s_;
  RunFolder f_;
  Json info_;
  const RunOptions& opt_;
  std::vector<io::DisplayMesh> meshes_;
  io::RunProgress p_;
  std::uint64_t total_ = 0, per_frame_ = 1;
  std::ofstream trace_, energy_;
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
  info["threads"] = s.world.threads;
  info["warnings"] = s.warnings;
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
  RunFolder folder;
  Json previous;
  try {
    if (!opt.resume.empty()) {
      folder.dir = opt.resume;
      if (!fs::exists(folder.checkpoint()))
        throw io::SceneError(folder.dir.string() + " holds no checkpoint.bin to resume from");
      previous = Json::parse(read_text(folder.run_json()), nullptr, false);
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
    if (opt.threads >= 0) scene.world.threads = opt.threads;
    scene.world.threads = resolve_threads(scene.world.threads);
    if (opt.resume.empty()) {
      folder.dir = opt.out.empty() ? fs::path(scene.output_dir) : fs::path(opt.out);
      if (fs::exists(folder.run_json()) && !(opt.overwrite || scene.overwrite))
        throw io::SceneError(folder.dir.string() + " already holds a run; choose another [output].dir or --out, "
                             "or set [output].overwrite = true (or --overwrite)");
      for (const fs::path& p : {folder.frames(), folder.checkpoint(), folder.trace(), folder.energy()})
        fs::remove_all(p);
      fs::create_directories(folder.frames());
      write_text(folder.scene(), text);
    }
    Json info = base_info(scene, scene_file, base);
    info["dt"] = scene.dt;
    if (!opt.quiet)
      std::cerr << "gjkdem: " << scene.world.bodies.size() << " bodies, " << scene.world.templates.size()
                << " shape templates, dt = " << scene.dt << " s, " << scene.world.threads << " threads, output in "
                << folder.dir.string() << "\n";
    install_signal_handlers();
    Runner runner(std::move(scene), folder, info, opt);
    if (opt.resume.empty()) runner.start();
    else runner.resume();
    return runner.run();
  } catch (const io::SceneError& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  } catch (const io::CheckpointError& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  } catch (const fs::filesystem_error& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace gjkdem::app
