// dem::run on domains (domains.hpp): the same sequence as run.cpp's loop,
// with the bodies exchanged in the middle of each step, the whole world
// gathered on rank 0 for every output, and every decision (stop, failure,
// a guard's verdict) agreed by all ranks before it is acted on.
#include <optional>
#include <stdexcept>

#include "gjkdem/dem/domains.hpp"
#include "run_guard.hpp"

namespace gjkdem::dem {
namespace {

// The first non-empty message of any rank (lowest rank first), on every rank.
std::string agree(DomainTransport& t, const std::string& mine) {
  for (std::string& m : all_gather(t, mine))
    if (!m.empty()) return std::move(m);
  return "";
}

// Runs `f` (a stage of one rank), its exception as a message.
template <class F>
std::string failure_of(World& domain, F f) {
  try {
    const StepReport r = f();
    return r.status == StepStatus::Ok ? "" : describe_failure(domain, r);
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace

RunOutcome run_domains(World& whole, RunState& state, std::span<RunObserver* const> observers, DomainTransport& t,
                       const std::function<bool()>& stop_requested, const RunGuards& guards) {
  if (const std::string why = domains_unsupported(whole); !why.empty())
    throw std::invalid_argument("a run on more than one rank cannot have " + why + " yet: run it on one rank");
  const bool root = t.rank() == 0;
  const DomainLayout layout = layout_domains(whole, t.size());
  World domain = make_domain(whole, layout, t.rank());
  RunOutcome outcome;
  detail::GuardCheck check;
  auto finish = [&](RunStatus status, std::string error = {}) {
    gather_world(domain, t, whole);
    outcome = {status, std::move(error)};
    if (root)
      for (RunObserver* o : observers) o->on_stop(whole, state, outcome);
    return outcome;
  };
  // Rank 0's verdict on the gathered world (`start`: the initial energy is
  // recorded first), agreed by all: "" to go on.
  auto output = [&](bool start) {
    gather_world(domain, t, whole);
    std::string verdict;
    if (root) {
      try {
        if (start) {
          state.initial_energy = kinetic_energy(whole) + potential_energy(whole) + whole.stats.elastic_energy;
          verdict = check(whole, state, guards, observers);
        }
        if (verdict.empty()) verdict = check_finite(whole);
        if (verdict.empty()) {
          ++state.outputs;
          for (RunObserver* o : observers) o->on_output(whole, state);
          verdict = check(whole, state, guards, observers);
        }
      } catch (const std::exception& e) {
        verdict = e.what();
      }
    }
    return agree(t, verdict);
  };

  exchange_bodies(domain, layout, t);
  if (state.step == 0 && state.outputs == 0) {
    std::string failed = agree(t, failure_of(domain, [&] { return compute_forces_now(domain); }));
    if (failed.empty()) failed = output(true);
    if (!failed.empty()) return finish(RunStatus::Failed, std::move(failed));
  } else {
    std::string verdict = root ? check(whole, state, guards, observers) : "";
    verdict = agree(t, verdict);
    if (!verdict.empty()) return finish(RunStatus::Failed, std::move(verdict));
  }
  // Rank 0's stop request, or the failure of an on_step observer, told to all.
  const std::string kStop = "\x01stop";
  std::string observer_failure;
  auto stop_or_fail = [&](bool ask) -> std::optional<RunOutcome> {
    std::string mine = observer_failure;
    if (root && mine.empty() && ask && stop_requested && stop_requested()) mine = kStop;
    std::string said = agree(t, mine);
    if (said.empty()) return std::nullopt;
    if (said == kStop) return finish(RunStatus::Stopped);
    return finish(RunStatus::Failed, std::move(said));
  };
  while (state.step < state.steps_total) {
    if (const auto done = stop_or_fail(true)) return *done;
    std::string failed = failure_of(domain, [&] { return begin_step(domain, state.dt); });
    exchange_bodies(domain, layout, t);  // every rank takes part, failed or not
    if (failed.empty()) failed = failure_of(domain, [&] { return finish_step(domain, state.dt); });
    failed = agree(t, failed);
    if (!failed.empty()) return finish(RunStatus::Failed, std::move(failed));
    ++state.step;
    if (root) try {
        for (RunObserver* o : observers) o->on_step(domain, state);
      } catch (const std::exception& e) {
        observer_failure = e.what();
      }
    if (state.step % state.steps_per_output == 0 || state.step == state.steps_total)
      if (std::string verdict = output(false); !verdict.empty()) return finish(RunStatus::Failed, std::move(verdict));
  }
  if (const auto done = stop_or_fail(false)) return *done;
  return finish(RunStatus::Completed);
}

}  // namespace gjkdem::dem
