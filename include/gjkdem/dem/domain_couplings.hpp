#pragma once
// What a domain run adds to the stage plan (stage_plan.hpp), as one ordered
// table: the couplings through which the domains of one world step as the
// whole world would (domains.hpp). Each row names the point of the run loop
// it runs at, the feature that needs it, and what it reads and writes; the
// run loop (run/run_loop.cpp) walks the rows at each point, on every rank
// together (each is a collective). A whole world runs none: its stages do
// the same on it alone. A feature whose state spans domains (a bond's, a
// heat flux's) adds its row. docs/architecture.md shows the table as
// domain_couplings_markdown prints it.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>

#include "gjkdem/dem/domains.hpp"

namespace gjkdem::dem {

/// Where in the run loop a coupling runs.
enum class CouplingPoint {
  AfterBeginStep,   ///< after begin_step's kicks, drift and moves, before the listeners and the exchange
  AfterEvaluation,  ///< after each force evaluation (the step's, the start's, one after splits)
  AfterStep,        ///< after the step's evaluation and its couplings, before the ranks agree on it
};

/// What the couplings of one rank share at one point. All ranks walk the
/// same rows in the same order, failed or not (`failed` holds this rank's
/// first failure, which a coupling may set).
struct CouplingContext {
  World& world;             ///< the rank's domain
  DomainRole& role;
  const DomainLayout& layout;
  DomainTransport& transport;
  StepContext& step;
  std::string& failed;
  /// AfterEvaluation: whether the evaluation ended a step (the driven work
  /// is integrated over it from `work_before`) or stands alone.
  bool ends_step = false;
  Real work_before = 0;
  /// AfterBeginStep: the first id the inflows inserted (all ones: none).
  std::uint64_t first_inserted = ~std::uint64_t{0};
  /// AfterStep: the bodies changed (splits): exchange them, evaluate the
  /// forces again and walk the AfterEvaluation rows, a failure into the
  /// string given; the run loop's, made once per run.
  const std::function<void(std::string& failed)>* evaluate_again = nullptr;
};

struct DomainCoupling {
  std::string_view name;
  CouplingPoint point;
  std::string_view needed_by;  ///< the feature that needs it
  std::string_view file;    ///< where its collective is written (src/dem/), as "path (function)"
  std::string_view reads;
  std::string_view writes;
  bool (*needed)(const World& whole);  ///< whether a run of this world takes it (decided once, at the start)
  void (*run)(CouplingContext&);
};

/// Every coupling, in the order the run loop walks each point's.
std::span<const DomainCoupling> domain_couplings() noexcept;

/// The table as docs/architecture.md shows it (coupling, point, needed by,
/// file, reads, writes).
std::string domain_couplings_markdown();

std::string_view point_name(CouplingPoint point) noexcept;

}  // namespace gjkdem::dem
