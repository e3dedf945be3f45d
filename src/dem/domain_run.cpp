// dem::run on domains (domains.hpp): the same sequence as run.cpp's loop,
// with the bodies exchanged in the middle of each step, the whole world
// gathered on rank 0 for every output, and every decision (stop, failure,
// a guard's verdict) agreed by all ranks before it is acted on.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "domain_records.hpp"
#include "gjkdem/dem/domains.hpp"
#include "run_guard.hpp"

namespace gjkdem::dem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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
                       const std::function<bool()>& stop_requested, const RunGuards& guards,
                       const DomainOptions& options, DomainReport* report) {
  const bool root = t.rank() == 0;
  DomainLayout layout = layout_domains(whole, t.size());
  DomainRole role;
  World domain = make_domain(whole, layout, t.rank(), role);
  StepContext ctx{.dt = state.dt, .domain = &role};
  RunOutcome outcome;
  detail::GuardCheck check;
  // This rank's counts, summed over the steps.
  DomainReport::Rank mine;
  std::uint64_t steps = 0;
  int rebalances = 0;
  auto exchange = [&] {
    const auto t0 = Clock::now();
    const ExchangeCounts c = exchange_bodies(domain, role, layout, t);
    mine.exchange_seconds += seconds_since(t0);
    mine.owned += static_cast<double>(c.owned), mine.ghosts += static_cast<double>(c.ghosts);
    mine.moved_out += static_cast<double>(c.moved_out), mine.bytes_sent += static_cast<double>(c.bytes_sent);
  };
  // Driven walls and bodies, a deforming cell: rank 0 makes the whole
  // world's power and work of a step again from every domain's contacts
  // (each domain's own sums are partial), and every rank takes the whole
  // stress a servo reads. `step`: after a step from `work_before` (else the
  // first force evaluation).
  const bool deforming = whole.settings.cell_control.deforms();
  const bool driven = !whole.motions.empty() || deforming;
  const bool servo = whole.settings.cell_control.servo();
  auto settle_wall_power = [&](Real work_before, bool step) {
    if (servo) domain.cell_stress = whole_cell_stress(domain, t);
    if (!driven) return;
    const Real power = whole_wall_power(domain, t);
    if (!root) return;
    domain.stats.wall_power = power;
    if (step) domain.wall_work = work_before + 0.5 * state.dt * (ctx.power_before + power);
  };
  // The work of a deforming cell's field on the bodies in begin_step (its
  // change, the wraps), summed again on rank 0.
  auto settle_field_work = [&] {
    if (deforming) add_field_work(domain, role, t);
  };
  std::uint64_t gathered_at = ~std::uint64_t{0};  // the step the whole world was last gathered at
  auto finish = [&](RunStatus status, std::string error = {}) {
    if (gathered_at != state.step) gather_world(domain, role, t, whole);
    outcome = {status, std::move(error)};
    if (root)
      for (RunObserver* o : observers) o->on_stop(whole, state, outcome);
    const std::string bytes(reinterpret_cast<const char*>(&mine), sizeof mine);
    const std::vector<std::string> all = all_gather(t, bytes);
    if (report && root) {
      report->ranks.assign(all.size(), {});
      const double n = static_cast<double>(std::max<std::uint64_t>(steps, 1));
      for (std::size_t r = 0; r < all.size(); ++r) {
        if (all[r].size() != sizeof mine) continue;
        std::memcpy(&report->ranks[r], all[r].data(), sizeof mine);
        DomainReport::Rank& k = report->ranks[r];
        k.owned /= n, k.ghosts /= n, k.moved_out /= n, k.bytes_sent /= n, k.step_seconds /= n, k.exchange_seconds /= n, k.loop_seconds /= n;
      }
      report->steps = steps;
      report->rebalances = rebalances;
      report->layout = layout;
    }
    return outcome;
  };
  // At an output: when the slowest domain's stages took more than the mean
  // by options.imbalance since the last output (a hopper empties into one
  // corner), rank 0 draws the regions again, each body weighted by its cost
  // (1 + its pairs) at the speed its domain measured; every rank takes them.
  double seconds_at_output = 0;
  auto rebalance = [&] {
    const double took = mine.step_seconds - seconds_at_output;
    seconds_at_output = mine.step_seconds;
    const std::vector<std::string> times = all_gather(t, std::string(reinterpret_cast<const char*>(&took), sizeof took));
    std::string regions;
    if (root) {
      const std::size_t ranks = times.size();
      std::vector<double> seconds(ranks, 0);
      for (std::size_t r = 0; r < ranks; ++r)
        if (times[r].size() == sizeof(double)) std::memcpy(&seconds[r], times[r].data(), sizeof(double));
      const double mean = std::accumulate(seconds.begin(), seconds.end(), 0.0) / static_cast<double>(ranks);
      const double slowest = *std::max_element(seconds.begin(), seconds.end());
      if (mean > 0 && slowest > (1 + options.imbalance) * mean) {
        const std::vector<Real> cost = body_costs(whole);
        std::vector<Real> load(ranks, 0), weight(whole.bodies.size(), 0);
        for (std::size_t i = 0; i < whole.bodies.size(); ++i)
          if (!whole.bodies[i].fixed) load[layout.owner_of(whole.bodies[i].position)] += cost[i];
        for (std::size_t i = 0; i < whole.bodies.size(); ++i) {
          if (whole.bodies[i].fixed) continue;
          const int r = layout.owner_of(whole.bodies[i].position);
          weight[i] = cost[i] * seconds[r] / load[r];
        }
        const DomainLayout next = layout_domains(whole, t.size(), weight);
        std::vector<Real> predicted(ranks, 0);
        for (std::size_t i = 0; i < whole.bodies.size(); ++i)
          if (!whole.bodies[i].fixed) predicted[next.owner_of(whole.bodies[i].position)] += weight[i];
        if (*std::max_element(predicted.begin(), predicted.end()) < slowest)
          regions.assign(reinterpret_cast<const char*>(next.regions.data()), next.regions.size() * sizeof(DomainBox));
      }
    }
    const std::string said = all_gather(t, regions)[0];
    if (said.size() != layout.regions.size() * sizeof(DomainBox)) return;
    std::memcpy(layout.regions.data(), said.data(), said.size());
    ++rebalances;
  };
  // Rank 0's verdict on the gathered world (`start`: the initial energy is
  // recorded first), agreed by all: "" to go on.
  auto output = [&](bool start) {
    gather_world(domain, role, t, whole);
    gathered_at = state.step;
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
    verdict = agree(t, verdict);
    if (verdict.empty()) rebalance();
    return verdict;
  };

  exchange_bodies(domain, role, layout, t);  // the first ghosts
  if (state.step == 0 && state.outputs == 0) {
    std::string failed = agree(t, failure_of(domain, [&] { return compute_forces_now(domain, &role); }));
    settle_wall_power(Real(0), false);
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
    std::string here = observer_failure;
    if (root && here.empty() && ask && stop_requested && stop_requested()) here = kStop;
    std::string said = agree(t, here);
    if (said.empty()) return std::nullopt;
    if (said == kStop) return finish(RunStatus::Stopped);
    return finish(RunStatus::Failed, std::move(said));
  };
  while (state.step < state.steps_total) {
    const auto start = Clock::now();
    if (const auto done = stop_or_fail(true)) return *done;
    gathered_at = ~std::uint64_t{0};  // the domains move on
    auto t0 = Clock::now();
    std::string failed = failure_of(domain, [&] { return begin_step(domain, ctx); });
    settle_field_work();
    const std::uint64_t first_new = insert_inflow_bodies(domain, ctx, layout, t);
    mine.step_seconds += seconds_since(t0);
    exchange();  // every rank takes part, failed or not
    // Every body took its first half kick where it was owned, but those
    // inserted now, which start with their velocity.
    ctx.kicked_bodies =
        first_new != ~std::uint64_t{0} ? detail::index_of_id(domain.bodies, first_new) : domain.bodies.size();
    t0 = Clock::now();
    const Real work_before = domain.wall_work;
    if (failed.empty()) failed = failure_of(domain, [&] { return finish_step(domain, ctx); });
    mine.step_seconds += seconds_since(t0);
    settle_wall_power(work_before, true);
    ++steps;
    failed = agree(t, failed);
    if (!failed.empty()) return finish(RunStatus::Failed, std::move(failed));
    ++state.step;
    if (root) try {
        for (RunObserver* o : observers) o->on_step(domain, state);
      } catch (const std::exception& e) {
        observer_failure = e.what();
      }
    mine.loop_seconds += seconds_since(start);
    if (state.step % state.steps_per_output == 0 || state.step == state.steps_total)
      if (std::string verdict = output(false); !verdict.empty()) return finish(RunStatus::Failed, std::move(verdict));
  }
  if (const auto done = stop_or_fail(false)) return *done;
  return finish(RunStatus::Completed);
}

}  // namespace gjkdem::dem
