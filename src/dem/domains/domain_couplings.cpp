// The domain couplings (domain_couplings.hpp): the table, and each row's
// function, which hands its collective (domains.hpp) what it takes.
#include "gjkdem/dem/domain_couplings.hpp"

#include <array>

#include "gjkdem/dem/breakage.hpp"

namespace gjkdem::dem {
namespace {

bool deforming(const World& w) { return w.settings.cell_control.deforms(); }
bool inflowing(const World& w) { return !w.inflows.empty(); }
bool bonded(const World& w) { return !w.bonds.empty(); }
bool servoed(const World& w) { return w.settings.cell_control.servo(); }
bool driven(const World& w) { return !w.motions.empty() || deforming(w); }
bool breaking(const World& w) { return world_breaks(w); }

void field_work(CouplingContext& c) { add_field_work(c.world, c.role, c.transport); }

void inflows(CouplingContext& c) { c.first_inserted = insert_inflow_bodies(c.world, c.step, c.layout, c.transport); }

void bonds(CouplingContext& c) { sync_bonds(c.world, c.role, c.transport); }

void cell_stress(CouplingContext& c) { c.world.cell.stress = whole_cell_stress(c.world, c.transport); }

// Rank 0 takes the whole world's power, and after a step the work of the
// step by the trapezoid rule (as finish_step integrates a whole world's).
void wall_power(CouplingContext& c) {
  const Real power = whole_wall_power(c.world, c.transport);
  if (c.transport.rank() != 0) return;
  c.world.stats.wall_power = power;
  if (c.ends_step) c.world.wall_work = c.work_before + 0.5 * c.step.dt * (c.step.power_before + power);
}

// The grains broken on the step's contacts (a whole world breaks them at
// the end of finish_step); after splits the ranks exchange, so that each
// holds the fragments near it (a fragment's box can reach where its
// grain's did not), and find the fragments' forces at once.
void breakage(CouplingContext& c) {
  const DomainBreakage broke = break_domain_grains(c.world, c.role, c.transport, c.failed.empty());
  if (broke.broken > 0) {
    (*c.evaluate_again)(c.failed);
    const Real after = whole_contact_energy(c.world, c.transport);
    if (c.transport.rank() == 0) c.world.split_energy += after - broke.energy_before;
  }
  c.world.stats.broken = broke.broken;
}

using enum CouplingPoint;

constexpr std::array kCouplings{
    DomainCoupling{"field_work", AfterBeginStep, "a deforming cell", "domains/domains.cpp (add_field_work)",
                   "each domain's field and wrap work", "rank 0's wall_work", deforming, field_work},
    DomainCoupling{"inflows", AfterBeginStep, "inflows", "domains/domain_exchange.cpp (insert_inflow_bodies)",
                   "bodies near the inflows' regions on every domain", "the new bodies on every rank", inflowing,
                   inflows},
    DomainCoupling{"bonds", AfterEvaluation, "bonds", "domains/domain_exchange.cpp (sync_bonds)",
                   "the bonds each domain broke", "every rank's bonds", bonded, bonds},
    DomainCoupling{"cell_stress", AfterEvaluation, "a servo cell", "domains/domains.cpp (whole_cell_stress)",
                   "every domain's contact terms", "cell.stress on every rank", servoed, cell_stress},
    DomainCoupling{"wall_power", AfterEvaluation, "driven walls, a deforming cell",
                   "domains/domains.cpp (whole_wall_power)", "every domain's powered contact terms",
                   "rank 0's stats.wall_power, wall_work", driven, wall_power},
    DomainCoupling{"breakage", AfterStep, "breakable grains", "domains/domain_exchange.cpp (break_domain_grains)",
                   "each domain's splits", "fragments, templates, stats.broken on every rank; an evaluation; rank 0's split_energy",
                   breaking, breakage},
};

}  // namespace

std::span<const DomainCoupling> domain_couplings() noexcept { return kCouplings; }

std::string_view point_name(CouplingPoint point) noexcept {
  switch (point) {
    case AfterBeginStep: return "after begin_step";
    case AfterEvaluation: return "after each evaluation";
    case AfterStep: return "after the step";
  }
  return "?";
}

std::string domain_couplings_markdown() {
  std::string s = "| coupling | point | needed by | file | reads | writes |\n|---|---|---|---|---|---|\n";
  for (const DomainCoupling& c : kCouplings) {
    std::string file = "`";  // "path (function)": both in backticks
    const std::size_t paren = c.file.find(" (");
    if (paren == std::string_view::npos) {
      file.append(c.file).append("`");
    } else {
      file.append(c.file.substr(0, paren)).append("` (`");
      file.append(c.file.substr(paren + 2, c.file.size() - paren - 3)).append("`)");
    }
    s += "| " + std::string(c.name) + " | " + std::string(point_name(c.point)) + " | " + std::string(c.needed_by) +
         " | " + file + " | " + std::string(c.reads) + " | " + std::string(c.writes) + " |\n";
  }
  return s;
}

}  // namespace gjkdem::dem
