// One step of the engine: the fixed core (the kicks, the drift, the cell,
// inflows and motions) and the stages of the plan (stage_plan.hpp) between.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include "gjkdem/dem/integrator.hpp"
#include "gjkdem/dem/stage_plan.hpp"
#include "gjkdem/dem/world.hpp"
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

using detail::thread_count;

// The kinds of the templates added since the last look (step_workspace.hpp);
// a world with fewer templates than seen is looked at anew.
void note_template_kinds(std::span<const ShapeTemplate> templates, TemplateKinds& kinds) {
  if (kinds.seen > templates.size()) kinds = {};
  for (; kinds.seen < templates.size(); ++kinds.seen) {
    kinds.surface_grains |= holds_surface(templates[kinds.seen]);
    kinds.wall_faces |= templates[kinds.seen].wall_face.has_value();
  }
}

// dt: time since the last evaluation, for the springs (0 at the start).
// The evaluation's stages are the plan's (stage_plan.hpp), in order.
StepReport compute_forces(World& w, Real dt, const DomainRole* domain) {
  ForceEvaluation e{.world = w, .domain = domain, .dt = dt, .threads = thread_count(w.settings.threads)};
  note_template_kinds(w.templates, w.work.kinds);
  if (static_cast<int>(w.work.overlap.size()) < e.threads) w.work.overlap.resize(e.threads);
  for (const Stage& stage : stage_plan()) {
    if (!stage.run || stage.phase < StagePhase::BeforeForces || stage.phase > StagePhase::Reduce) continue;
    const StepReport r = stage.run(e);
    if (r.status != StepStatus::Ok) return r;
  }
  w.forces_current = true;
  return {};
}

}  // namespace

StepReport compute_forces_now(World& w, const DomainRole* domain) {
  if (w.forces_current) return {};
  place_driven(w);
  return compute_forces(w, 0, domain);
}

StepReport begin_step(World& w, StepContext& ctx) {
  if (!w.forces_current) {
    const StepReport r = compute_forces_now(w, ctx.domain);
    if (r.status != StepStatus::Ok) return r;
  }
  const Real dt = ctx.dt;
  const int threads = thread_count(w.settings.threads);
  const Makeup makeup{w.templates, w.materials};
  const CellBodies moved{w.bodies, &makeup, ctx.domain, &w.wall_work};
  kick(w.bodies, makeup, dt / 2, threads, w.applied_loads);
  const bool deforming = w.settings.cell_control.deforms();
  if (deforming) control_cell(w.settings.cell_control, w.cell.stress, w.cell.now, w.cell.rate, moved);
  drift(w.bodies, makeup, dt, threads);
  if (deforming) {
    if (deform_cell(w.cell.now, w.cell.rate, dt)) w.work.candidates_current = false, w.search.renew_cell = true;  // images renamed
    const Real shortest = shortest_period(w, ctx.domain);
    for (int a = 0; a < 3; ++a)
      if (w.cell.now.axes[a] && !(cell_width(w.cell.now, a) > shortest)) {
        w.forces_current = false;
        return {StepStatus::CellTooShort, static_cast<std::uint64_t>(a), 0, shortest};
      }
  }
  if (w.cell.now.active() && wrap_bodies(w.cell.now, w.cell.rate, w.search.boxes, moved) > 0) w.work.candidates_current = false, w.search.renew_cell = true;
  ctx.power_before = w.stats.wall_power;
  w.time += dt;
  ctx.kicked_bodies = w.bodies.size();
  // A domain run inserts the inflows' bodies itself, before its exchange
  // (insert_inflow_bodies, domains.hpp).
  ctx.inserted = w.inflows.empty() || ctx.domain ? 0
                 : run_inflows(w.inflows, w.inflow_states, inflow_site(w), w.bodies,
                               w.bodies.empty() ? 0 : w.bodies.back().id + 1);
  if (!w.motions.empty()) place_driven(w);
  w.forces_current = false;
  return {};
}

StepReport finish_step(World& w, StepContext& ctx) {
  const Real dt = ctx.dt;
  const StepReport r = compute_forces(w, dt, ctx.domain);
  w.stats.inserted = static_cast<int>(ctx.inserted);
  if (r.status != StepStatus::Ok) {
    w.forces_current = false;
    return r;
  }
  // Bodies inserted now start at this time with their velocity: no half kick.
  const std::size_t kicked = std::min(ctx.kicked_bodies, w.bodies.size());
  kick(std::span(w.bodies).first(kicked), {w.templates, w.materials}, dt / 2, thread_count(w.settings.threads),
       w.applied_loads);
  w.wall_work += 0.5 * dt * (ctx.power_before + w.stats.wall_power);  // trapezoid rule
  ForceEvaluation e{.world = w, .domain = ctx.domain, .dt = dt, .threads = thread_count(w.settings.threads)};
  for (const Stage& stage : stage_plan()) {
    if (!stage.run || stage.phase != StagePhase::AfterStep) continue;
    const StepReport after = stage.run(e);
    if (after.status != StepStatus::Ok) return after;
  }
  return r;
}

StepReport step(World& w, Real dt) {
  StepContext ctx{.dt = dt};
  const StepReport r = begin_step(w, ctx);
  return r.status == StepStatus::Ok ? finish_step(w, ctx) : r;
}

}  // namespace gjkdem::dem
