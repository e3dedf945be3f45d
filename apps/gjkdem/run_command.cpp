// gjkdem run: options, signals and the progress bar. The run itself (run
// folder, steps, outputs, energy balance, checkpoints, run.json) is the
// library's io::SceneRun.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include <unistd.h>

#include "commands.hpp"
#include "gjkdem/io/scene_check.hpp"
#include "gjkdem/io/scene_export.hpp"
#include "gjkdem/io/scene_run.hpp"
#include "gjkdem/mpi/mpi_transport.hpp"

namespace gjkdem::app {
namespace {

namespace fs = std::filesystem;

volatile std::sig_atomic_t g_stop_signal = 0;  // set by the handler only
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

// Progress on standard error: a bar redrawn in place on a terminal, a plain
// line every 10 s (and at the end) otherwise.
class Progress : public dem::RunObserver {
 public:
  Progress(bool quiet, std::uint64_t first_step, Real duration)
      : quiet_(quiet), clock_(isatty(STDERR_FILENO), first_step), duration_(duration) {}
  void on_output(const dem::World&, const dem::RunState&) override {}
  void on_step(const dem::World& w, const dem::RunState& s) override { update(w, s, false); }
  void on_stop(const dem::World& w, const dem::RunState& s, const dem::RunOutcome&) override { update(w, s, true); }
  void on_warning(const dem::World&, const dem::RunState&, const std::string& message) override {
    std::cerr << (clock_.terminal() ? "\n" : "") << "gjkdem: warning: " << message << "\n";
  }

 private:
  void update(const dem::World& w, const dem::RunState& s, bool final) {
    if (quiet_) return;
    const std::string line = clock_.due(w.time, duration_, s.step, s.steps_total, final);
    if (line.empty()) return;
    const double frac = s.steps_total ? static_cast<double>(s.step) / static_cast<double>(s.steps_total) : 1;
    if (clock_.terminal()) {
      const int width = 24, done = static_cast<int>(frac * width);
      std::cerr << "\r[" << std::string(done, '#') << std::string(width - done, '.') << "] " << line << "   "
                << (final ? "\n" : "") << std::flush;
    } else {
      std::cerr << "gjkdem: " << line << "\n";
    }
  }

  bool quiet_;
  io::ProgressClock clock_;
  Real duration_;
};

// Per rank, means per step (docs/scaling.md reads these).
void print_domain_report(const dem::DomainReport& r) {
  std::cerr << "gjkdem: " << r.ranks.size() << " ranks, " << r.steps << " steps, regions drawn again "
            << r.rebalances << " times; per rank and step:\n";
  for (std::size_t k = 0; k < r.ranks.size(); ++k) {
    const dem::DomainReport::Rank& d = r.ranks[k];
    char line[240];
    std::snprintf(line, sizeof line,
                  "gjkdem:   rank %zu: %.0f bodies, %.0f ghosts (%.0f%%), %.2f moved out, %.1f kB sent, "
                  "%.3f ms in its stages, %.3f ms exchanging, %.3f ms in all\n",
                  k, d.owned, d.ghosts, d.owned > 0 ? 100 * d.ghosts / d.owned : 0.0, d.moved_out, d.bytes_sent / 1e3,
                  1e3 * d.step_seconds, 1e3 * d.exchange_seconds, 1e3 * d.loop_seconds);
    std::cerr << line;
  }
}

void install_signal_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

// A long build's progress on standard error (rank 0, not --quiet): nothing
// in its first second, then what it starts on, at most a line a second.
dem::BuildProgress build_printer(bool quiet) {
  if (quiet) return {};
  using Clock = std::chrono::steady_clock;
  struct Printer {
    Clock::time_point start = Clock::now(), last{};
    bool printed = false;
  };
  return [p = std::make_shared<Printer>()](const std::string& what) {
    const Clock::time_point now = Clock::now();
    const double since = std::chrono::duration<double>(now - p->start).count();
    if (since < 1 || (p->printed && std::chrono::duration<double>(now - p->last).count() < 1)) return;
    p->printed = true, p->last = now;
    std::cerr << "gjkdem: building (" << static_cast<long>(since) << " s): " << what << "\n";
  };
}

// The run this rank takes part in (on a follower, one that writes
// nothing); null when the run to resume is already completed.
std::unique_ptr<io::SceneRun> open_run(const RunOptions& opt, bool follower) {
  const dem::BuildProgress on_build = build_printer(opt.quiet || follower);
  if (!opt.resume.empty()) {
    if (io::SceneRun::completed(opt.resume)) return nullptr;
    return io::SceneRun::resume(opt.resume, opt.threads, follower, on_build);
  }
  return io::SceneRun::start(opt.scene, {.out = opt.out,
                                         .overwrite = opt.overwrite,
                                         .threads = opt.threads,
                                         .follower = follower,
                                         .start_from = opt.start_from,
                                         .on_build = on_build});
}

// More ranks on this node than it has cores: each of the many exchanges of
// a step waits for the ranks the scheduler has set aside (measured here: the
// hopper example's first second took 4.3 s on 2 ranks of 2 cores, 6 minutes
// on 3).
void warn_if_oversubscribed() {
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  const unsigned cores = std::thread::hardware_concurrency();
  const int ranks = local ? std::atoi(local) : 0;
  if (cores == 0 || ranks <= static_cast<int>(cores)) return;
  std::cerr << "gjkdem: warning: " << ranks << " ranks share the " << cores
            << " cores of this node: every step waits for ranks the scheduler has set aside, which can make the run"
               " many times slower than on "
            << cores << " ranks\n";
}

// A rank other than 0: its domain of the run rank 0 writes; silent, rank 0
// reports for all (its exit status follows the run's).
int run_follower(const RunOptions& opt, dem::DomainTransport& transport,
                 const std::function<bool(const std::string&)>& started) {
  std::unique_ptr<io::SceneRun> run;
  try {
    run = open_run(opt, true);
  } catch (const std::exception& e) {
    started(e.what());
    return 2;
  }
  if (!run) return started("completed"), 0;
  if (!started("")) return 2;
  install_signal_handlers();  // a signal to this rank stops every rank at a step's end
  try {
    const auto stop = [&]() -> std::string {
      if (g_stop_signal) return g_stop_signal == SIGINT ? "SIGINT" : "SIGTERM";
      return "";
    };
    const dem::RunOutcome outcome = run->run({}, stop, &transport);
    return outcome.status == dem::RunStatus::Completed ? 0 : outcome.status == dem::RunStatus::Stopped ? 130 : 1;
  } catch (const std::exception& e) {
    std::cerr << "gjkdem: error on rank " << transport.rank() << ": " << e.what() << "\n";
    mpi::abort_job(2);  // the other ranks may be waiting for this one
  }
}

}  // namespace

// Under mpirun every rank reads the scene (and the checkpoint) and runs its
// domain; rank 0 alone writes the folder and speaks. A rank that cannot
// start tells the others, so that none waits for it.
// gjkdem run --check: the scene's summary, a time and size estimate.
int check_simulation(const RunOptions& opt) {
  if (!opt.resume.empty() || !opt.out.empty() || opt.stop_after >= 0 || !opt.start_from.empty()) {
    std::cerr << "gjkdem: --check takes a scene and --threads only\n";
    return 2;
  }
  try {
    const io::SceneCheck c = io::check_scene(opt.scene, opt.threads, 2.0, build_printer(opt.quiet));
    std::cout << io::describe(c);
    return c.failure.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  }
}

int run_simulation(const RunOptions& opt) {
  const std::unique_ptr<dem::DomainTransport> transport = mpi::launched_transport();
  if (opt.check) return transport && transport->rank() > 0 ? 0 : check_simulation(opt);  // rank 0 checks, on one rank
  const bool follower = transport && transport->rank() > 0;
  const bool domains = transport && transport->size() > 1;
  auto started = [&](const std::string& error) {
    if (!domains) return true;
    const std::vector<std::string> all = dem::all_gather(*transport, error);
    return std::all_of(all.begin(), all.end(), [](const std::string& e) { return e.empty(); });
  };
  if (follower) return run_follower(opt, *transport, started);
  try {
    std::unique_ptr<io::SceneRun> run;
    try {
      run = open_run(opt, false);
    } catch (const std::exception& e) {
      started(e.what());
      throw;
    }
    if (!run) {
      started("completed");
      std::cerr << "gjkdem: the run in " << opt.resume << " is already completed\n";
      return 0;
    }
    if (!started("")) {
      std::cerr << "gjkdem: error: another rank could not start the run\n";
      return 2;
    }
    const dem::World& world = run->scene.world;
    for (const std::string& w : run->scene.warnings) std::cerr << "gjkdem: warning: " << w << "\n";
    if (domains) warn_if_oversubscribed();
    Progress progress(opt.quiet, run->state.step, run->scene.duration);
    dem::RunObserver* observers[] = {&progress};
    if (!opt.quiet)
      std::cerr << "gjkdem: " << world.bodies.size() << " bodies, " << world.templates.size()
                << " shape templates, dt = " << run->scene.dt << " s, " << world.settings.threads
                << " threads" << (domains ? " on each of " + std::to_string(transport->size()) + " ranks" : "")
                << ", output in " << run->folder.dir.string() << "\n";
    install_signal_handlers();
    const auto stop = [&]() -> std::string {
      if (g_stop_signal) return g_stop_signal == SIGINT ? "SIGINT" : "SIGTERM";
      if (opt.stop_after >= 0 && run->state.step >= static_cast<std::uint64_t>(opt.stop_after)) return "--stop-after";
      return "";
    };
    dem::RunOutcome outcome;
    try {
      outcome = run->run(observers, stop, transport.get());
    } catch (const std::exception& e) {
      if (!domains) throw;
      std::cerr << "gjkdem: error: " << e.what() << "\n";
      mpi::abort_job(2);  // the other ranks may be waiting for this one
    }
    if (domains && !opt.quiet) print_domain_report(run->domain_report);
    switch (outcome.status) {
      case dem::RunStatus::Completed:
        if (!opt.quiet)
          std::cerr << "gjkdem: completed " << run->state.step << " steps (" << world.bodies.size() << " bodies"
                    << (world.broken > 0 ? ", " + std::to_string(world.broken) + " grains broken" : std::string())
                    << (world.bonds.empty() ? std::string()
                                            : ", " + std::to_string(dem::broken_bonds(world.bonds)) + " of " +
                                                  std::to_string(world.bonds.size()) + " bonds broken")
                    << ") in " << io::duration_text(run->wall_seconds()) << "; results in "
                    << run->folder.dir.string() << "\n";
        return 0;
      case dem::RunStatus::Stopped:
        if (!opt.quiet)
          std::cerr << "gjkdem: stopped at t = " << world.time << " s; continue with: gjkdem run --resume "
                    << run->folder.dir.string() << "\n";
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

int export_state(const ExportOptions& opt) {
  try {
    const std::string text = io::export_run_scene(opt.run);
    if (opt.out.empty()) {
      std::cout << text;
    } else {
      io::write_file_atomically(opt.out, text);
      std::cerr << "gjkdem: wrote " << opt.out << "\n";
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "gjkdem: error: " << e.what() << "\n";
    return 2;
  }
}

}  // namespace gjkdem::app
