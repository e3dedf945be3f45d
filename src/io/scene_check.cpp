#include "gjkdem/io/scene_check.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "gjkdem/dem/inflow.hpp"
#include "gjkdem/io/scene_run.hpp"

namespace gjkdem::io {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A fresh folder under the system's temporary directory, removed with it.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "gjkdem-check-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw SceneError("cannot make a scratch folder for the check under " +
                                                   fs::temp_directory_path().string());
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::uint64_t file_bytes(const fs::path& file) {
  std::error_code e;
  const auto n = fs::file_size(file, e);
  return e ? 0 : static_cast<std::uint64_t>(n);
}

std::uint64_t folder_bytes(const fs::path& dir) {
  std::uint64_t total = 0;
  std::error_code e;
  for (const auto& entry : fs::recursive_directory_iterator(dir, e))
    if (entry.is_regular_file(e)) total += file_bytes(entry.path());
  return total;
}

// Times the steps after the first: the first output's writing is not a step's cost.
class StepClock : public dem::RunObserver {
 public:
  void on_output(const dem::World&, const dem::RunState&) override {}
  void on_step(const dem::World&, const dem::RunState&) override {
    const auto now = Clock::now();
    if (steps_ == 0) first_ = now;
    last_ = now;
    ++steps_;
  }
  std::uint64_t steps() const { return steps_; }
  double seconds_since_first() const { return std::chrono::duration<double>(last_ - first_).count(); }

 private:
  std::uint64_t steps_ = 0;
  Clock::time_point first_, last_;
};

std::string bytes_text(std::uint64_t n) {
  char buf[32];
  if (n >= 1'000'000'000) std::snprintf(buf, sizeof buf, "%.1f GB", n / 1e9);
  else if (n >= 1'000'000) std::snprintf(buf, sizeof buf, "%.1f MB", n / 1e6);
  else if (n >= 1'000) std::snprintf(buf, sizeof buf, "%.1f kB", n / 1e3);
  else std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(n));
  return buf;
}

std::string seconds_text(double s) {
  char buf[48];
  if (!(s >= 0)) return "?";
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  else if (s >= 60) std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else std::snprintf(buf, sizeof buf, "%.2g s", s);
  return buf;
}

}  // namespace

SceneCheck check_scene(const std::string& scene_file, int threads, double sample_seconds,
                       const dem::BuildProgress& on_build) {
  const ScratchFolder scratch;
  std::unique_ptr<SceneRun> run = SceneRun::start(
      scene_file, {.out = scratch.path() / "run", .overwrite = true, .threads = threads, .on_build = on_build});
  const dem::World& w = run->scene.world;
  SceneCheck c;
  c.bodies = w.bodies.size();
  for (const dem::Body& b : w.bodies) (b.fixed ? c.fixed : c.moving) += 1;
  c.templates = w.templates.size();
  for (std::size_t k = 0; k < w.inflows.size(); ++k) {
    const std::uint64_t most = dem::inflow_capacity(w.inflows[k], {w.templates, w.materials});
    c.inflow_room += most - std::min(most, w.inflow_states[k].inserted);
  }
  c.threads = w.settings.threads;
  c.duration = run->scene.duration;
  c.dt = run->state.dt;
  c.dt_auto = run->scene.dt_auto;
  c.steps = run->state.steps_total;
  const std::uint64_t every = std::max<std::uint64_t>(run->state.steps_per_output, 1);
  c.outputs = c.steps / every + 1 + (c.steps % every != 0);
  c.out_dir = run->scene.output_dir;
  c.warnings = run->scene.warnings;

  StepClock clock;
  dem::RunObserver* observers[] = {&clock};
  const auto started = Clock::now();
  const dem::RunOutcome outcome = run->run(observers, [&]() -> std::string {
    const double elapsed = std::chrono::duration<double>(Clock::now() - started).count();
    return clock.steps() >= 2 && elapsed >= sample_seconds ? "check" : "";
  });
  if (outcome.status == dem::RunStatus::Failed) c.failure = outcome.error;
  c.sampled_steps = clock.steps();
  if (c.sampled_steps >= 2) {
    c.seconds_per_step = clock.seconds_since_first() / static_cast<double>(c.sampled_steps - 1);
  } else if (c.sampled_steps == 1) {
    c.seconds_per_step = std::chrono::duration<double>(Clock::now() - started).count();
  }
  c.estimated_seconds = c.seconds_per_step * static_cast<double>(c.steps);

  const RunPaths& folder = run->folder;
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d", 0);
  c.output_bytes = file_bytes(folder.frames() / (std::string(name) + ".vtk")) +
                   file_bytes(folder.view() / (std::string(name) + ".bin"));
  c.checkpoint_bytes = file_bytes(folder.checkpoint());
  run.reset();  // the writers close their files
  const std::uint64_t written = folder_bytes(scratch.path() / "run");
  // What the folder holds besides the sample's outputs (shapes, the scene,
  // the tables' heads), then every output and a checkpoint.
  const std::uint64_t sampled_outputs = c.output_bytes;  // the sample wrote step 0's output
  const std::uint64_t fixed_part = written - std::min(written, sampled_outputs + c.checkpoint_bytes);
  c.estimated_bytes = fixed_part + c.outputs * c.output_bytes + c.checkpoint_bytes;
  return c;
}

std::string describe(const SceneCheck& c) {
  std::string s;
  char line[320];
  std::snprintf(line, sizeof line, "bodies: %zu (%zu moving, %zu fixed); %zu shape templates", c.bodies, c.moving,
                c.fixed, c.templates);
  s += line;
  if (c.inflow_room > 0) s += "; inflows may add up to " + std::to_string(c.inflow_room);
  s += "\n";
  std::snprintf(line, sizeof line, "time: %g s in %llu steps of %.6g s (%s), %llu outputs; threads: %d%s\n", c.duration,
                static_cast<unsigned long long>(c.steps), c.dt, c.dt_auto ? "auto" : "given",
                static_cast<unsigned long long>(c.outputs), c.threads, c.threads == 0 ? " (every core)" : "");
  s += line;
  if (!c.failure.empty()) return s + "the run would fail after " + std::to_string(c.sampled_steps) +
                                 " steps: " + c.failure + "\n";
  if (c.sampled_steps >= c.steps) {
    std::snprintf(line, sizeof line, "estimate: the sample ran the whole run, %.3g ms a step: %s of wall time\n",
                  1e3 * c.seconds_per_step, seconds_text(c.estimated_seconds).c_str());
  } else {
    std::snprintf(line, sizeof line,
                  "estimate: %s of wall time at the pace of the first %llu steps (%.3g ms a step); more as "
                  "contacts form%s\n",
                  seconds_text(c.estimated_seconds).c_str(), static_cast<unsigned long long>(c.sampled_steps),
                  1e3 * c.seconds_per_step, c.inflow_room > 0 ? " and inflows add bodies" : "");
  }
  s += line;
  s += "output: about " + bytes_text(c.estimated_bytes) + " in " + c.out_dir + " (" + bytes_text(c.output_bytes) +
       " an output at the start's bodies" +
       (c.checkpoint_bytes > 0 ? ", " + bytes_text(c.checkpoint_bytes) + " a checkpoint)\n" : ")\n");
  for (const std::string& w : c.warnings) s += "warning: " + w + "\n";
  return s;
}

}  // namespace gjkdem::io
