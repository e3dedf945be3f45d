// The run loop, once for every run: a whole world is a domain run on one
// rank. Start-up, outputs, guards, the stop request and the end exist
// here only. On more ranks each rank steps its domain (domains.hpp): the
// bodies are exchanged in the middle of each step, the whole world is
// gathered on rank 0 for every output, and every decision (stop, failure, a
// guard's verdict) is agreed by all ranks before it is acted on. On one
// rank the world steps itself: nothing is cut, exchanged or gathered.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "domains/domain_records.hpp"
#include "gjkdem/dem/domain_couplings.hpp"
#include "run/run_guard.hpp"

namespace gjkdem::dem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The first non-empty message of any rank (lowest rank first), on every rank.
std::string agree(DomainTransport& t, const std::string& mine) {
  if (t.size() == 1) return mine;
  for (std::string& m : all_gather(t, mine))
    if (!m.empty()) return std::move(m);
  return "";
}

// Runs `f` (a stage of one rank), its exception as a message.
template <class F>
std::string failure_of(const World& stepped, F f) {
  try {
    const StepReport r = f();
    return r.status == StepStatus::Ok ? "" : describe_failure(stepped, r);
  } catch (const std::exception& e) {
    return e.what();
  }
}

// One rank: the world it steps (the whole world when it is the only rank,
// else its domain) and what it measured, summed over the steps.
class Rank {
 public:
  Rank(World& whole, DomainTransport& t) : t_(t), whole_(whole), split_(t.size() > 1) {
    if (!split_) return;
    layout_ = layout_domains(whole, t.size());
    domain_ = make_domain(whole, layout_, t.rank(), role_);
  }
  bool split() const { return split_; }
  World& stepped() { return split_ ? domain_ : whole_; }
  DomainRole* role() { return split_ ? &role_ : nullptr; }
  DomainLayout& layout() { return layout_; }

  // Boxes, bodies that change domain, ghosts (every rank, failed or not).
  void exchange() {
    if (!split_) return;
    const auto t0 = Clock::now();
    const ExchangeCounts c = exchange_bodies(domain_, role_, layout_, t_);
    measured.exchange_seconds += seconds_since(t0);
    measured.owned += static_cast<double>(c.owned), measured.ghosts += static_cast<double>(c.ghosts);
    measured.moved_out += static_cast<double>(c.moved_out), measured.bytes_sent += static_cast<double>(c.bytes_sent);
  }
  // The whole world on rank 0, for outputs (at most once per step).
  void gather(std::uint64_t step) {
    if (gathered_at_ == step) return;
    if (split_) gather_world(domain_, role_, t_, whole_);
    gathered_at_ = step;
  }
  void moved_on() { gathered_at_ = ~std::uint64_t{0}; }

  DomainReport::Rank measured;
  std::uint64_t steps = 0;
  int rebalances = 0;

 private:
  DomainTransport& t_;
  World& whole_;
  bool split_;
  DomainLayout layout_;
  DomainRole role_;
  World domain_;
  std::uint64_t gathered_at_ = ~std::uint64_t{0};
};

}  // namespace

RunOutcome run_domains(World& whole, RunState& state, std::span<RunObserver* const> observers, DomainTransport& t,
                       const std::function<bool()>& stop_requested, const RunGuards& guards,
                       const DomainOptions& options, DomainReport* report,
                       std::span<StepListener* const> listeners) {
  const bool root = t.rank() == 0;
  if (!listeners.empty()) whole.applied_loads = true;
  Rank rank(whole, t);
  World& stepped = rank.stepped();
  StepContext ctx{.dt = state.dt, .domain = rank.role()};
  RunOutcome outcome;
  detail::GuardCheck check;
  DomainReport::Rank& mine = rank.measured;
  auto finish = [&](RunStatus status, std::string error = {}) {
    rank.gather(state.step);
    outcome = {status, std::move(error)};
    // An observer failing here fails the run with its message, after the
    // collectives below, which every rank must reach.
    if (root) try {
        for (RunObserver* o : observers) o->on_stop(whole, state, outcome);
      } catch (const std::exception& e) {
        outcome = {RunStatus::Failed, e.what()};
      }
    // Every rank takes part (the others pass no report).
    const std::string bytes(reinterpret_cast<const char*>(&mine), sizeof mine);
    const std::vector<std::string> all = t.size() == 1 ? std::vector{bytes} : all_gather(t, bytes);
    if (report && root) {
      report->ranks.assign(all.size(), {});
      const double n = static_cast<double>(std::max<std::uint64_t>(rank.steps, 1));
      for (std::size_t r = 0; r < all.size(); ++r) {
        if (all[r].size() != sizeof mine) continue;
        std::memcpy(&report->ranks[r], all[r].data(), sizeof mine);
        DomainReport::Rank& k = report->ranks[r];
        k.owned /= n, k.ghosts /= n, k.moved_out /= n, k.bytes_sent /= n, k.step_seconds /= n, k.exchange_seconds /= n, k.loop_seconds /= n;
      }
      report->steps = rank.steps;
      report->rebalances = rank.rebalances;
      report->layout = rank.layout();
    }
    return outcome;
  };
  // At an output on domains: when the slowest domain's stages took more
  // than the mean by options.imbalance since the last output (a hopper
  // empties into one corner), rank 0 draws the regions again, each body
  // weighted by its cost (1 + its pairs) at the speed its domain measured;
  // every rank takes them.
  double seconds_at_output = 0;
  auto rebalance = [&] {
    if (!rank.split()) return;
    const double took = mine.step_seconds - seconds_at_output;
    seconds_at_output = mine.step_seconds;
    const std::vector<std::string> times = all_gather(t, std::string(reinterpret_cast<const char*>(&took), sizeof took));
    DomainLayout& layout = rank.layout();
    std::string regions;  // none: the regions stay (also when drawing them failed: every rank must go on)
    if (root) try {
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
    } catch (const std::exception&) {
      regions.clear();
    }
    const std::string said = all_gather(t, regions)[0];
    if (said.size() != layout.regions.size() * sizeof(DomainBox)) return;
    std::memcpy(layout.regions.data(), said.data(), said.size());
    ++rank.rebalances;
  };
  // Rank 0's verdict on the whole world (`start`: the initial energy is
  // recorded first), agreed by all: "" to go on.
  auto output = [&](bool start) {
    rank.gather(state.step);
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

  // The domain couplings this world needs (domain_couplings.hpp), walked
  // at their points by every rank together, failed or not; none on one
  // rank. Returns the first id the inflows inserted (all ones: none).
  constexpr std::uint64_t kNoneInserted = ~std::uint64_t{0};
  std::vector<const DomainCoupling*> couplings;
  if (rank.split())
    for (const DomainCoupling& c : domain_couplings())
      if (c.needed(whole)) couplings.push_back(&c);
  std::function<std::uint64_t(CouplingPoint, std::string&, bool, Real)> couple;
  const std::function<void(std::string&)> evaluate_again = [&](std::string& failed) {
    rank.exchange();
    if (failed.empty()) failed = failure_of(stepped, [&] { return compute_forces_now(stepped, ctx.domain); });
    couple(CouplingPoint::AfterEvaluation, failed, false, stepped.wall_work);
  };
  couple = [&](CouplingPoint point, std::string& failed, bool ends_step, Real work_before) {
    if (couplings.empty()) return kNoneInserted;
    CouplingContext c{.world = stepped, .role = *ctx.domain, .layout = rank.layout(), .transport = t,
                      .step = ctx, .failed = failed, .ends_step = ends_step, .work_before = work_before,
                      .first_inserted = kNoneInserted, .evaluate_again = &evaluate_again};
    for (const DomainCoupling* k : couplings)
      if (k->point == point) k->run(c);
    return c.first_inserted;
  };
  // The step listeners due before the forces at the end of step `step`
  // (0: the start), on each rank's own bodies before the exchange hands
  // them to the others as ghosts; a listener's exception as a message.
  auto listen = [&](std::uint64_t step) -> std::string {
    try {
      for (StepListener* l : listeners) {
        const std::uint64_t every = std::max<std::uint64_t>(l->every(), 1);
        if (step % every == 0) l->before_forces({stepped, ctx.domain}, state);
      }
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  const bool fresh = state.step == 0 && state.outputs == 0;
  std::string listened = fresh ? listen(0) : "";
  // The loads set now act in the start's evaluation, also on a world whose
  // forces were current (a world run again from Python).
  if (fresh && !listeners.empty()) stepped.forces_current = false;
  rank.exchange();  // the first ghosts
  if (fresh) {
    std::string failed = listened;
    if (failed.empty()) failed = failure_of(stepped, [&] { return compute_forces_now(stepped, ctx.domain); });
    couple(CouplingPoint::AfterEvaluation, failed, false, 0);
    failed = agree(t, failed);
    if (failed.empty()) failed = output(true);
    if (!failed.empty()) return finish(RunStatus::Failed, std::move(failed));
  } else {
    std::string verdict;
    if (root) try {
        verdict = check(whole, state, guards, observers);
      } catch (const std::exception& e) {
        verdict = e.what();
      }
    verdict = agree(t, verdict);
    if (!verdict.empty()) return finish(RunStatus::Failed, std::move(verdict));
  }
  // Any rank's stop request (a signal may reach one rank only), or the
  // failure of an on_step observer, told to all.
  const std::string kStop = "\x01stop";
  std::string observer_failure;
  auto stop_or_fail = [&](bool ask) -> std::optional<RunOutcome> {
    std::string here = observer_failure;
    if (here.empty() && ask && stop_requested) try {
        if (stop_requested()) here = kStop;
      } catch (const std::exception& e) {
        here = e.what();
      }
    std::string said = agree(t, here);
    if (said.empty()) return std::nullopt;
    if (said == kStop) return finish(RunStatus::Stopped);
    return finish(RunStatus::Failed, std::move(said));
  };
  while (state.step < state.steps_total) {
    const auto start = Clock::now();
    if (const auto done = stop_or_fail(true)) return *done;
    rank.moved_on();
    auto t0 = Clock::now();
    std::string failed = failure_of(stepped, [&] { return begin_step(stepped, ctx); });
    const std::uint64_t first_new = couple(CouplingPoint::AfterBeginStep, failed, false, 0);
    // Every rank's listeners are called, failed or not: a coupling may hold
    // collectives of its own.
    if (!listeners.empty()) {
      std::string heard = listen(state.step + 1);
      if (failed.empty()) failed = std::move(heard);
    }
    mine.step_seconds += seconds_since(t0);
    if (rank.split()) {
      rank.exchange();  // every rank takes part, failed or not
      // Every body took its first half kick where it was owned, but those
      // inserted now, which start with their velocity.
      ctx.kicked_bodies =
          first_new != kNoneInserted ? detail::count_ids_below(stepped.bodies, first_new) : stepped.bodies.size();
    }
    t0 = Clock::now();
    const Real work_before = stepped.wall_work;
    if (failed.empty()) failed = failure_of(stepped, [&] { return finish_step(stepped, ctx); });
    couple(CouplingPoint::AfterEvaluation, failed, true, work_before);
    couple(CouplingPoint::AfterStep, failed, false, 0);
    mine.step_seconds += seconds_since(t0);
    ++rank.steps;
    failed = agree(t, failed);
    if (!failed.empty()) return finish(RunStatus::Failed, std::move(failed));
    ++state.step;
    if (root) try {
        for (RunObserver* o : observers) o->on_step(stepped, state);
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

RunOutcome run(World& world, RunState& state, std::span<RunObserver* const> observers,
               const std::function<bool()>& stop_requested, const RunGuards& guards,
               std::span<StepListener* const> listeners) {
  OneRank alone;
  return run_domains(world, state, observers, alone, stop_requested, guards, {}, nullptr, listeners);
}

}  // namespace gjkdem::dem
