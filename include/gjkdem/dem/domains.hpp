#pragma once
// Domain runs (issue 15): one world split among ranks by space. Each rank's
// domain is a World holding the bodies it owns (those whose centre lies in
// its region), the other domains' bodies whose boxes reach its own (ghosts,
// refreshed every step, their state only: templates, materials and walls
// are replicated) and every fixed body. A domain lists only pairs with a
// body it owns and sums each owned body's forces in the order of its pairs'
// keys, as a whole world does, so a run on any number of domains gives the
// same bits as the run of the whole world. A body that crosses into another
// region moves to its owner with the state of its pairs (GJK warm starts,
// springs): friction history survives the move. Outputs see the whole world,
// gathered on rank 0.
//
// The transport is abstract: MPI in the gjkdem program (gjkdem/mpi/), ranks
// as threads of one process in the tests.
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "gjkdem/dem/decomposition.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

/// How domains talk. Every rank calls exchange() together, in the same order.
class DomainTransport {
 public:
  virtual ~DomainTransport() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Sends outgoing[r] to rank r (size() entries, empty ones included) and
  /// returns what each rank sent to this one, by rank.
  virtual std::vector<std::string> exchange(std::vector<std::string> outgoing) = 0;
};

/// The transport of a run on one rank: a whole world (dem::run).
class OneRank : public DomainTransport {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::vector<std::string> exchange(std::vector<std::string> outgoing) override { return outgoing; }
};

/// Every rank's `mine`, by rank, on every rank.
std::vector<std::string> all_gather(DomainTransport& transport, const std::string& mine);

/// Which rank owns which region of space. The regions tile all space (the
/// outer ones reach to infinity); a body belongs to the region holding its
/// centre of mass.
struct DomainLayout {
  std::vector<DomainBox> regions;  ///< per rank
  int owner_of(const Vec3& centre) const noexcept;
};

/// Regions for `ranks` domains by recursive coordinate bisection (bisect())
/// of the moving bodies' centres, each body weighted by `weights` (per body
/// of the world, fixed ones ignored; empty: 1 each).
DomainLayout layout_domains(const World& whole, int ranks, std::span<const Real> weights = {});

/// The domain of `rank` cut from the whole world: the moving bodies of its
/// region, every fixed body, the pairs of its bodies; `role` is set to its
/// part (step_context.hpp). Ghosts come with the first exchange_bodies().
World make_domain(const World& whole, const DomainLayout& layout, int rank, DomainRole& role);

/// What one exchange moved, on one rank.
struct ExchangeCounts {
  std::size_t owned = 0;       ///< moving bodies this domain owns afterwards
  std::size_t ghosts = 0;      ///< other domains' bodies it sees
  std::size_t moved_out = 0;   ///< bodies it handed to another domain
  std::size_t bytes_sent = 0;  ///< to other ranks
};

/// Brings the boxes up to date, moves the bodies that left this domain's
/// region to their owners (with the state of their pairs) and refreshes the
/// ghosts. All ranks call it together, between begin_step and finish_step
/// (world.hpp) and before a first force evaluation.
ExchangeCounts exchange_bodies(World& domain, DomainRole& role, const DomainLayout& layout,
                               DomainTransport& transport);

/// The whole world on rank 0, written into `whole` (which keeps what never
/// changes: settings, templates, materials, walls): bodies, box anchors,
/// the pair store, the touching contacts and the stats, with the same bits
/// as a run of the whole world. All ranks call it together; the others
/// leave `whole` as it is.
void gather_world(const World& domain, const DomainRole& role, DomainTransport& transport, World& whole);

/// Inserts the bodies the inflows owe, as a whole world would: every rank
/// places them among the bodies near the inflows' regions, gathered from
/// every domain, and keeps them all (its own, the others' as ghosts until
/// the exchange). All ranks call it together, after begin_step, with its
/// context (whose domain role it extends and whose count of inserted
/// bodies it sets). Returns the first new id, or all ones when none was
/// inserted.
std::uint64_t insert_inflow_bodies(World& domain, StepContext& context, const DomainLayout& layout,
                                   DomainTransport& transport);

/// Breaks the grains whose stress reached their strength (breakage.hpp), as
/// a whole world would: each domain finds those it owns, every rank is
/// sent every split, and each places the fragments of the grains it holds
/// and appends every fragment's template in id order (the same indices on
/// every rank), with ids from the whole world's next one. All ranks call it
/// together after finish_step (`found` false: a rank whose step failed
/// offers none). Returns how many grains broke and, where any did, the whole
/// world's contact energy before the splits (whole_contact_energy: on rank
/// 0), from which the evaluation after them gives World::split_energy.
struct DomainBreakage {
  int broken = 0;
  Real energy_before = 0;
};
DomainBreakage break_domain_grains(World& domain, DomainRole& role, DomainTransport& transport, bool found = true);

/// Tells every rank the bonds this domain broke since it last told them
/// (bonds.hpp): a bond breaks in the domains that hold both its bodies, and
/// every rank's copy of the bonds must agree before the next step. All
/// ranks call it together after each force evaluation of a world with
/// bonds.
void sync_bonds(World& domain, DomainRole& role, DomainTransport& transport);

/// The power of the driven walls and bodies, and of a deforming cell
/// through the images, on the moving bodies at the last force evaluation,
/// summed over every domain's contacts in the order a whole world sums them
/// (World::stats.wall_power): on rank 0; 0 on the others. All ranks call
/// it together.
Real whole_wall_power(const World& domain, DomainTransport& transport);

/// The cell's stress at the last force evaluation (World::cell.stress),
/// which a servo reads at every step: every domain's contacts summed on
/// rank 0 in the order of their keys, as a whole world sums them, and told
/// to every rank. All ranks call it together.
CellTensor whole_cell_stress(const World& domain, DomainTransport& transport);

/// The elastic energy of every domain's touching contacts at the last force
/// evaluation, added on rank 0 in the order of their keys as contact_energy
/// adds a whole world's list (world.hpp): on rank 0; 0 on the others. All
/// ranks call it together.
Real whole_contact_energy(const World& domain, DomainTransport& transport);

/// Adds to rank 0's World::wall_work the kinetic energy a deforming cell's
/// field gave the whole world's bodies this step: by its change, then by
/// the wraps (every domain's DomainRole::field_work and wrap_work, each
/// summed in id order as control_cell and wrap_bodies sum them). Clears
/// both lists. All ranks call it together, after begin_step.
void add_field_work(World& domain, DomainRole& role, DomainTransport& transport);

/// How a domain run balances its domains.
struct DomainOptions {
  /// At each output, the regions are drawn again when the slowest domain's
  /// stages took longer than the mean by more than this fraction since the
  /// last output, and the new regions promise better: bisect() weighted by
  /// each body's cost (body_costs) at the speed its domain measured. The
  /// bodies then move to their new owners at the next step. The bits of the
  /// run do not depend on it.
  Real imbalance = 0.2;
};

/// What a domain run did, per rank (means per step), on rank 0.
struct DomainReport {
  struct Rank {
    double owned = 0, ghosts = 0, moved_out = 0, bytes_sent = 0;
    double step_seconds = 0;      ///< in its own stages of the step
    double exchange_seconds = 0;  ///< in the exchange, waiting for the others included
    double loop_seconds = 0;      ///< a whole step, agreements included, outputs not
  };
  std::vector<Rank> ranks;
  std::uint64_t steps = 0;
  int rebalances = 0;
  DomainLayout layout;  ///< at the end
};

/// Each body's cost for the layout: 1 + the pairs of the pair store it is
/// in (the narrow phase's work), by body.
std::vector<Real> body_costs(const World& whole);

/// dem::run (run.hpp) on domains: every rank calls it together with the same
/// whole world (as built, or restored from a checkpoint) and run state. It
/// is the one run loop: dem::run is run_domains on one rank (OneRank), which
/// steps the whole world itself.
/// Observers and the guards act on rank 0, which sees the gathered whole
/// world at each output (on_step sees rank 0's domain); the other ranks
/// pass no observers. Every rank may pass a stop request: the run stops
/// when any rank's says so. A failure on any rank fails the run
/// on all, with the message of the lowest failing rank. On return, rank
/// 0's `whole` holds the world as of the last output.
RunOutcome run_domains(World& whole, RunState& state, std::span<RunObserver* const> observers,
                       DomainTransport& transport, const std::function<bool()>& stop_requested = {},
                       const RunGuards& guards = {}, const DomainOptions& options = {},
                       DomainReport* report = nullptr, std::span<StepListener* const> listeners = {});

}  // namespace gjkdem::dem
