#include "gjkdem/dem/run.hpp"

#include <cmath>
#include <stdexcept>

namespace gjkdem::dem {
namespace {

std::string number_text(Real v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string name_of(const World& w, std::uint64_t id) {
  for (std::size_t p = 0; p < w.planes.size(); ++p)
    if (w.planes[p].id == id) return "plane wall " + std::to_string(p);
  return "body " + std::to_string(id);
}

// The first body whose state is not finite, if any.
const Body* non_finite_body(const World& w) {
  for (const Body& b : w.bodies)
    if (!is_finite(b.position) || !is_finite(b.velocity) || !is_finite(b.angular_momentum)) return &b;
  return nullptr;
}

}  // namespace

RunState plan_run(Real duration, Real dt, Real output_every) {
  if (!(std::isfinite(duration) && duration > 0)) throw std::invalid_argument("the duration must be > 0 and finite");
  if (!(std::isfinite(dt) && dt > 0)) throw std::invalid_argument("the time step must be > 0 and finite");
  if (!(std::isfinite(output_every) && output_every > 0))
    throw std::invalid_argument("the output interval must be > 0 and finite");
  const Real steps = std::ceil(duration / dt - 1e-9);
  if (!(steps < 9007199254740992.0))
    throw std::invalid_argument("the run would take " + number_text(steps) + " steps (more than 2^53)");
  RunState s;
  s.dt = dt;
  s.steps_total = static_cast<std::uint64_t>(std::fmax(steps, 1));
  const Real per = std::round(output_every / dt);
  s.steps_per_output = per < 1 ? 1 : (per > 9e15 ? s.steps_total : static_cast<std::uint64_t>(per));
  return s;
}

EnergyBalance energy_balance(const World& w, Real initial) noexcept {
  EnergyBalance e;
  e.kinetic = kinetic_energy(w);
  e.potential = potential_energy(w);
  e.elastic = w.stats.elastic_energy;
  e.dissipated = initial - e.kinetic - e.potential - e.elastic;
  return e;
}

std::string describe_failure(const World& w, const StepReport& r) {
  switch (r.status) {
    case StepStatus::Ok:
      return "";
    case StepStatus::UnsupportedPair:
      return "the contact model has no computation for the pair " + name_of(w, r.id_a) + " and " +
             name_of(w, r.id_b) + " at t = " + number_text(w.time) + " s";
  }
  return "step failed";
}

RunOutcome run(World& w, RunState& state, std::span<RunObserver* const> observers,
               const std::function<bool()>& stop_requested) {
  RunOutcome outcome;
  auto finish = [&](RunStatus status, std::string error = {}) {
    outcome = {status, std::move(error)};
    for (RunObserver* o : observers) o->on_stop(w, state, outcome);
    return outcome;
  };
  auto output = [&]() -> bool {
    if (const Body* b = non_finite_body(w)) {
      finish(RunStatus::Failed, "body " + std::to_string(b->id) + " has a non-finite state at t = " +
                                    number_text(w.time) + " s (time step too large for the stiffness?)");
      return false;
    }
    ++state.outputs;
    for (RunObserver* o : observers) o->on_output(w, state);
    return true;
  };
  try {
    if (state.step == 0 && state.outputs == 0) {
      const StepReport r = compute_forces_now(w);
      if (r.status != StepStatus::Ok) return finish(RunStatus::Failed, describe_failure(w, r));
      state.initial_energy = kinetic_energy(w) + potential_energy(w) + w.stats.elastic_energy;
      if (!output()) return outcome;
    }
    while (state.step < state.steps_total) {
      if (stop_requested && stop_requested()) return finish(RunStatus::Stopped);
      const StepReport r = step(w, state.dt);
      if (r.status != StepStatus::Ok) return finish(RunStatus::Failed, describe_failure(w, r));
      ++state.step;
      for (RunObserver* o : observers) o->on_step(w, state);
      if (state.step % state.steps_per_output == 0 || state.step == state.steps_total)
        if (!output()) return outcome;
    }
  } catch (const std::exception& e) {
    return finish(RunStatus::Failed, e.what());
  }
  return finish(RunStatus::Completed);
}

}  // namespace gjkdem::dem
