#pragma once
// Running a world from Python: the run loop goes on with the GIL released;
// observers, warnings and Ctrl-C come back to Python between steps.
#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "convert.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/io/run_output.hpp"

namespace gjkdem::py_bind {

/// A run or step that failed (guards, a pair without a computation):
/// gjkdem.RunError, a RuntimeError.
struct RunError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Calls a Python callable observer(world, state) at each output; a False
/// return or a Python exception (kept, raised again after the run) stops it.
class PyObserver : public dem::RunObserver {
 public:
  PyObserver(py::object world, py::object callback) : world_(std::move(world)), callback_(std::move(callback)) {}
  void on_output(const dem::World&, const dem::RunState& state) override;
  void on_warning(const dem::World&, const dem::RunState&, const std::string& message) override;
  /// Asked between steps: an observer's stop, or Ctrl-C (checked every 256 steps).
  std::string stop_reason();
  /// Raises the observer's or the interrupt's Python exception, if any.
  void raise_if_failed();

 private:
  py::object world_, callback_;
  std::optional<py::error_already_set> error_;
  std::string stop_;
  unsigned polls_ = 0;
};

/// run(listener=f, listener_every=N): calls f(world, state) before the
/// force evaluations of every N steps (dem::StepListener), the GIL taken;
/// `world` is the Python World, whose applied_forces and applied_torques it
/// may write. A Python exception fails the run and is raised again after it.
class PyListener : public dem::StepListener {
 public:
  PyListener(py::object world, py::object callback, std::uint64_t every);
  std::uint64_t every() const override { return every_; }
  void before_forces(dem::OwnedBodies bodies, const dem::RunState& state) override;
  /// Raises the listener's Python exception, if any.
  void raise_if_failed();

 private:
  py::object world_, callback_;
  std::uint64_t every_;
  std::optional<py::error_already_set> error_;
};

/// The listener of run(listener=..., listener_every=...) (none for None),
/// checked: a callable, every >= 1.
std::optional<PyListener> make_listener(py::object world, const py::object& listener, std::int64_t every);

/// run(progress=True): the command's progress line (io::progress_line) on
/// Python's sys.stderr, redrawn in place every 0.25 s on a terminal, a line
/// every 10 s otherwise (a notebook, a log), and at the end.
class PyProgress : public dem::RunObserver {
 public:
  PyProgress(std::uint64_t first_step, Real duration);
  void on_output(const dem::World&, const dem::RunState&) override {}
  void on_step(const dem::World& world, const dem::RunState& state) override;
  void on_stop(const dem::World& world, const dem::RunState& state, const dem::RunOutcome&) override;

 private:
  void show(const dem::World& world, const dem::RunState& state, bool final);

  io::ProgressClock clock_;
  Real duration_;
};

/// A world a call is using with the GIL released (a step, a run, a
/// checkpoint), for the length of that call; kept under the GIL. Another
/// thread's call on it is refused (RuntimeError): two threads never step,
/// run or read one world at once. On the holding thread (its observer),
/// reading calls go on; a second step or run is refused.
class InUse {
 public:
  enum Kind { Changes, Reads };
  explicit InUse(const dem::World& world, Kind kind = Changes);
  ~InUse();
  InUse(const InUse&) = delete;
  InUse& operator=(const InUse&) = delete;

 private:
  const dem::World* world_ = nullptr;  ///< registered here; null when the thread held it already (a read)
};

/// Refuses a call on `world` from a thread other than the one using it.
void idle(const dem::World& world);

/// Runs `loop(observers, stop)` with the GIL released and maps the outcome:
/// "completed" or "stopped", RunError on failure, the observer's or the
/// listener's exception.
std::string run_with(PyObserver& observer, std::span<dem::RunObserver* const> extra,
                     const std::function<dem::RunOutcome(std::span<dem::RunObserver* const>,
                                                         const std::function<std::string()>&)>& loop,
                     PyListener* listener = nullptr);

}  // namespace gjkdem::py_bind
