#include "py_run.hpp"

#include <map>
#include <thread>
#include <vector>


namespace gjkdem::py_bind {
namespace {

std::map<const dem::World*, std::thread::id>& worlds_in_use() {
  static std::map<const dem::World*, std::thread::id> in_use;
  return in_use;
}

const char* const kOtherThread = "this World is being stepped, run or saved by another thread: wait for that call";

}  // namespace

void idle(const dem::World& w) {
  const auto it = worlds_in_use().find(&w);
  if (it != worlds_in_use().end() && it->second != std::this_thread::get_id()) throw std::runtime_error(kOtherThread);
}

InUse::InUse(const dem::World& w, Kind kind) {
  const auto it = worlds_in_use().find(&w);
  if (it == worlds_in_use().end()) {
    worlds_in_use().emplace(&w, std::this_thread::get_id());
    world_ = &w;
    return;
  }
  if (it->second != std::this_thread::get_id()) throw std::runtime_error(kOtherThread);
  if (kind == Changes) throw std::runtime_error("this World is already being stepped or run (not from its own observer)");
}

InUse::~InUse() {
  if (world_) worlds_in_use().erase(world_);
}

void PyObserver::on_output(const dem::World&, const dem::RunState& state) {
  if (callback_.is_none() || error_ || !stop_.empty()) return;
  py::gil_scoped_acquire gil;
  try {
    const py::object answer = callback_(world_, state);
    if (py::isinstance<py::bool_>(answer) && !answer.cast<bool>()) stop_ = "observer";
  } catch (py::error_already_set& e) {
    error_.emplace(std::move(e));
    stop_ = "observer error";
  }
}

void PyObserver::on_warning(const dem::World&, const dem::RunState&, const std::string& message) {
  py::gil_scoped_acquire gil;
  try {
    py::module_::import("warnings").attr("warn")("gjkdem: " + message, py::handle(PyExc_RuntimeWarning));
  } catch (py::error_already_set& e) {  // warnings turned into errors
    if (!error_) error_.emplace(std::move(e));
    stop_ = "warning";
  }
}

std::string PyObserver::stop_reason() {
  if (stop_.empty() && ++polls_ % 256 == 0) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      error_.emplace();  // takes the KeyboardInterrupt
      stop_ = "KeyboardInterrupt";
    }
  }
  return stop_;
}

namespace {

bool stderr_is_a_terminal() {
  const py::object err = py::module_::import("sys").attr("stderr");
  return py::hasattr(err, "isatty") && err.attr("isatty")().cast<bool>();
}

}  // namespace

PyProgress::PyProgress(std::uint64_t first_step, Real duration)
    : clock_(stderr_is_a_terminal(), first_step), duration_(duration) {}

void PyProgress::on_step(const dem::World& world, const dem::RunState& state) { show(world, state, false); }

void PyProgress::on_stop(const dem::World& world, const dem::RunState& state, const dem::RunOutcome&) {
  show(world, state, true);
}

void PyProgress::show(const dem::World& world, const dem::RunState& state, bool final) {
  const std::string line = clock_.due(world.time, duration_, state.step, state.steps_total, final);
  if (line.empty()) return;  // the GIL only when a line is due
  py::gil_scoped_acquire gil;
  try {
    const py::object err = py::module_::import("sys").attr("stderr");
    err.attr("write")(clock_.terminal() ? "\rgjkdem: " + line + (final ? "\n" : "") : "gjkdem: " + line + "\n");
    err.attr("flush")();
  } catch (py::error_already_set&) {  // a closed or odd stderr: progress is not worth failing the run
  }
}

void PyObserver::raise_if_failed() {
  if (error_) {
    error_->restore();
    error_.reset();
    throw py::error_already_set();
  }
}

PyListener::PyListener(py::object world, py::object callback, std::uint64_t every)
    : world_(std::move(world)), callback_(std::move(callback)), every_(every) {}

void PyListener::before_forces(dem::OwnedBodies, const dem::RunState& state) {
  py::gil_scoped_acquire gil;
  try {
    callback_(world_, state);
  } catch (py::error_already_set& e) {
    const std::string message = std::string("the listener raised ") + e.what();
    error_.emplace(std::move(e));
    throw std::runtime_error(message);
  }
}

void PyListener::raise_if_failed() {
  if (error_) {
    error_->restore();
    error_.reset();
    throw py::error_already_set();
  }
}

std::optional<PyListener> make_listener(py::object world, const py::object& listener, std::int64_t every) {
  if (listener.is_none()) return std::nullopt;
  if (!PyCallable_Check(listener.ptr())) throw py::type_error("listener: expected a callable f(world, state)");
  if (every < 1) throw py::value_error("listener_every: must be >= 1 (steps)");
  return std::optional<PyListener>(std::in_place, std::move(world), listener, static_cast<std::uint64_t>(every));
}

std::string run_with(PyObserver& observer, std::span<dem::RunObserver* const> extra,
                     const std::function<dem::RunOutcome(std::span<dem::RunObserver* const>,
                                                         const std::function<std::string()>&)>& loop,
                     PyListener* listener) {
  std::vector<dem::RunObserver*> observers(extra.begin(), extra.end());
  observers.push_back(&observer);
  dem::RunOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = loop(observers, [&] { return observer.stop_reason(); });
  }
  observer.raise_if_failed();
  if (listener) listener->raise_if_failed();
  if (outcome.status == dem::RunStatus::Failed) throw RunError(outcome.error);
  return outcome.status == dem::RunStatus::Completed ? "completed" : "stopped";
}

}  // namespace gjkdem::py_bind
