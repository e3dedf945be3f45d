#include "gjkdem/dem/run.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "gjkdem/tolerances.hpp"
#include "number_text.hpp"
#include "run/run_guard.hpp"

namespace gjkdem::dem {
namespace {

std::string number_text(Real v) { return detail::number_text(v, 9); }

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

// Where the energy guard found the energy it cannot explain: the body
// moving with the most kinetic energy and the contact storing the most
// elastic energy, where a step too long for the stiffness blows up first.
std::string energy_growth_cause(const World& w) {
  const Body* fastest = nullptr;
  Real most = 0;
  for (const Body& b : w.bodies) {
    const Real e = b.fixed ? 0 : 0.5 * mass_of(w, b) * dot(b.velocity, b.velocity);
    if (e > most) most = e, fastest = &b;
  }
  const StepContact* stiffest = nullptr;
  for (const StepContact& c : w.results.contacts)
    if (c.active && (!stiffest || c.elastic > stiffest->elastic)) stiffest = &c;
  std::string where;
  if (fastest)
    where += "body " + std::to_string(fastest->id) + " moves fastest, at " + number_text(length(fastest->velocity)) + " m/s; ";
  if (stiffest && stiffest->elastic > 0)
    where += "the contact of " + name_of(w, stiffest->a_is_plane ? w.planes[stiffest->a].id : w.bodies[stiffest->a].id) +
             " and body " + std::to_string(w.bodies[stiffest->b].id) + " stores the most, " +
             number_text(stiffest->elastic) + " J; ";
  return where + "a blow-up: lower dt, or check the stiffness";
}

}  // namespace

Real stable_time_step(const World& w) {
  // critical_time_step is pi sqrt(m / k) / 20 (contact duration / 20) for
  // the linear and volume laws, and a fifth of the Rayleigh step over the
  // Mindlin factor for Hertz.
  const Real safe = critical_time_step(w);
  return w.settings.model == ContactModel::Hertz ? 5 * safe : safe * 20 * 2 / kPi;
}

std::string check_guards(const World& w, const RunState& state, const RunGuards& g) {
  if (g.action == GuardAction::Off) return "";
  const Real limit = stable_time_step(w);
  if (state.dt > limit)
    return "the time step " + number_text(state.dt) + " s is above the stability limit " + number_text(limit) +
           " s of the stiffest contact: contacts would blow up (use dt = \"auto\" or a smaller dt)";
  // A driven wall or body moving more than max_travel of the smallest
  // moving body's reach in one step can pass through bodies unseen too.
  Real smallest = std::numeric_limits<Real>::infinity();
  for (const Body& b : w.bodies)
    if (!b.fixed) smallest = std::fmin(smallest, w.templates[b.shape].reach);
  if (std::isfinite(smallest) && w.results.motion_frames.size() == w.motions.size()) {
    const auto too_fast = [&](Real speed, const std::string& who) -> std::string {
      const Real travel = speed * state.dt;
      if (!(travel > g.max_travel * smallest)) return "";
      return who + " moves " + number_text(travel / smallest) + " of the smallest body's size in one step (speed " +
             number_text(speed) + " m/s, dt " + number_text(state.dt) + " s) at t = " + number_text(w.time) +
             " s: it can pass through bodies unseen (lower dt or its speed)";
    };
    for (const Body& b : w.bodies) {
      if (!b.motion) continue;
      const MotionFrame& f = w.results.motion_frames[b.motion - 1];
      const std::string m = too_fast(length(b.velocity) + length(f.spin) * w.templates[b.shape].reach,
                                     "driven body " + std::to_string(b.id));
      if (!m.empty()) return m;
    }
    for (std::size_t p = 0; p < w.planes.size(); ++p) {
      const PlaneWall& plane = w.planes[p];
      if (!plane.motion) continue;
      const MotionFrame& f = w.results.motion_frames[plane.motion - 1];
      const std::string m = too_fast(std::fabs(dot(point_velocity(f, plane.point), plane.normal)),
                                     "driven plane wall " + std::to_string(p));
      if (!m.empty()) return m;
    }
  }
  // A deforming cell moves a body's images by rate x period per second: more
  // than max_travel of the smallest body's reach in a step and contacts
  // through the cell's faces are missed (a strain rate of 1e12 /s inverted
  // the cell in one step, reported as a width of -nan).
  const CellControl& control = w.settings.cell_control;
  if (std::isfinite(smallest) && control.deforms() && w.cell.now.active()) {
    Real rate = 0, period = 0;
    for (int k = 0; k < 6; ++k) {
      if (control.mode[k] == CellMode::StrainRate) rate = std::fmax(rate, std::fabs(control.value[k]));
      if (control.mode[k] == CellMode::Stress) rate = std::fmax(rate, control.max_strain_rate);
    }
    for (int a = 0; a < 3; ++a)
      if (w.cell.now.axes[a]) period = std::fmax(period, cell_width(w.cell.now, a));
    const Real travel = rate * period * state.dt;
    if (travel > g.max_travel * smallest)
      return "the periodic cell's strain rate " + number_text(rate) + " 1/s moves the images " +
             number_text(travel / smallest) + " of the smallest body's size in one step (dt " + number_text(state.dt) +
             " s): contacts through the cell's faces would be missed (lower dt or the rate)";
  }
  for (const Body& b : w.bodies) {
    if (b.fixed) continue;
    const Real reach = w.templates[b.shape].reach;
    const Real travel = length(b.velocity) * state.dt + length(angular_velocity_of(w, b)) * state.dt * reach;
    if (travel > g.max_travel * reach)
      return "body " + std::to_string(b.id) + " moves " + number_text(travel / reach) +
             " of its size in one step (speed " + number_text(length(b.velocity)) + " m/s, dt " +
             number_text(state.dt) + " s) at t = " + number_text(w.time) +
             " s: it can pass through other bodies unseen (lower dt or the speeds)";
  }
  if (state.outputs > 0) {
    // Kinetic + elastic energy can come only from the start and from falling:
    // at most `available`. Round-off and the integrator's O(dt^2) wobble stay
    // far below max_energy_gain of that, and below `floor`, the energy of
    // lifting every body by kEnergyGuardFloorRel of its size.
    const EnergyBalance e = energy_balance(w, state.initial_energy);
    const Real moving = e.kinetic + e.elastic, available = moving + e.dissipated, excess = -e.dissipated;
    Real floor = 0;
    for (const Body& b : w.bodies)
      if (!b.fixed) floor += kEnergyGuardFloorRel * mass_of(w, b) * length(w.settings.gravity) * w.templates[b.shape].reach;
    if (excess > g.max_energy_gain * std::fmax(available, Real(0)) + floor)
      return "the energy grew from nowhere: kinetic + elastic " + number_text(moving) + " J where the start, "
             "gravity, driven walls, inflows, applied loads and splits supply " + number_text(available) + " J, at t = " + number_text(w.time) +
             " s (" + energy_growth_cause(w) + ")";
  }
  return "";
}

std::string check_finite(const World& w) {
  if (const Body* b = non_finite_body(w))
    return "body " + std::to_string(b->id) + " has a non-finite state at t = " + number_text(w.time) +
           " s (time step too large for the stiffness?)";
  if (!std::isfinite(kinetic_energy(w) + potential_energy(w) + w.stats.elastic_energy))
    return "the energy is not finite at t = " + number_text(w.time) +
           " s: speeds or positions beyond what double precision squares (a non-finite state ahead)";
  return "";
}

RunState plan_run(Real duration, Real dt, Real output_every) {
  if (!(std::isfinite(duration) && duration > 0)) throw std::invalid_argument("the duration must be > 0 and finite");
  if (!(std::isfinite(dt) && dt > 0)) throw std::invalid_argument("the time step must be > 0 and finite");
  if (dt > duration)
    throw std::invalid_argument("the time step (" + number_text(dt) + " s) is longer than the duration (" +
                                number_text(duration) + " s)");
  if (!(std::isfinite(output_every) && output_every > 0))
    throw std::invalid_argument("the output interval must be > 0 and finite");
  const Real steps = std::ceil(duration / dt - kStepCountRelTol);
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
  e.wall_work = w.wall_work;
  for (const InflowState& f : w.inflow_states) e.inflow += f.energy;
  Real supplied = initial + e.wall_work + e.inflow;
  if (w.applied_loads) {  // in id order: the same sum for any rank count
    for (const Body& b : w.bodies) e.applied_work += b.applied_work;
    supplied += e.applied_work;
  }
  e.split = w.split_energy;
  supplied += e.split;
  e.dissipated = supplied - e.kinetic - e.potential - e.elastic;
  return e;
}

std::string describe_failure(const World& w, const StepReport& r) {
  switch (r.status) {
    case StepStatus::Ok:
      return "";
    case StepStatus::UnsupportedPair:
      return "the contact model has no computation for the pair " + name_of(w, r.id_a) + " and " +
             name_of(w, r.id_b) + " at t = " + number_text(w.time) + " s";
    case StepStatus::ThroughWall:
      if (name_of(w, r.id_a).starts_with("plane"))
        return name_of(w, r.id_b) + " passed wholly through " + name_of(w, r.id_a) + " at t = " +
               number_text(w.time) +
               " s: nothing holds a body wholly beyond a plane wall (lower dt, or its speed, or stiffen the contact)";
      return name_of(w, r.id_b) + " went through the mesh wall piece " + name_of(w, r.id_a) + " at t = " +
             number_text(w.time) +
             " s: its centre crossed the wall's triangle, and past it the contact pushes on through (lower dt, or "
             "its speed, or stiffen the contact; a thicker wall holds faster bodies)";
    case StepStatus::Engulfed:
      return "one of " + name_of(w, r.id_a) + " and " + name_of(w, r.id_b) + " lies wholly inside the other at t = " +
             number_text(w.time) +
             " s: their overlap has no contact area to push them apart (lower dt, or their speed, or stiffen the "
             "contact)";
    case StepStatus::ThroughBody: {
      std::string depth;  // the pair's contact, as the failed step left it
      for (const StepContact& c : w.results.contacts)
        if (!c.a_is_plane && w.bodies[c.a].id == r.id_a && w.bodies[c.b].id == r.id_b && c.active) {
          const Real radius = std::fmin(w.templates[w.bodies[c.a].shape].curvature_radius,
                                        w.templates[w.bodies[c.b].shape].curvature_radius);
          depth = " (overlapping by " + number_text(c.geometry.depth) + " m, the smaller radius " +
                  number_text(radius) + " m)";
        }
      return name_of(w, r.id_a) + " and " + name_of(w, r.id_b) + " are passing through each other at t = " +
             number_text(w.time) + " s" + depth +
             ": the centre of one is inside the other, so their contact pushes them on through, not apart "
             "(lower dt, or their speeds, or stiffen the contact; a heavier or faster body needs a stiffer one)";
    }
    case StepStatus::Pierced:
      return "one of " + name_of(w, r.id_a) + " and " + name_of(w, r.id_b) + " passed through the other at t = " +
             number_text(w.time) +
             " s: the faces of each inside the other add up to no contact area, so nothing pushes them apart (lower "
             "dt, or their speed, or stiffen the contact; a thicker body holds faster ones)";
    case StepStatus::CellTooShort: {
      const int a = static_cast<int>(r.id_a);
      return std::string("the periodic cell's width across ") + "xyz"[a] + " shrank to " +
             number_text(cell_width(w.cell.now, a)) + " m at t = " + number_text(w.time) +
             " s, no longer above four times the largest body's reach (" + number_text(r.shortest) +
             " m): start from a larger cell, or compress it less";
    }
  }
  return "step failed";
}

namespace {

// The deepest contact relative to the smaller radius of curvature of its
// bodies, when beyond kLawRangeRel: a warning naming the pair, or "".
std::string deep_overlap(const World& w) {
  Real worst = kLawRangeRel;
  const StepContact* deepest = nullptr;
  Real size_of_deepest = 0;
  for (const StepContact& c : w.results.contacts) {
    if (!c.active) continue;
    Real size = w.templates[w.bodies[c.b].shape].curvature_radius;
    if (!c.a_is_plane) size = std::fmin(size, w.templates[w.bodies[c.a].shape].curvature_radius);
    if (!(size > 0) || !(c.geometry.depth > worst * size)) continue;
    worst = c.geometry.depth / size, deepest = &c, size_of_deepest = size;
  }
  if (!deepest) return "";
  const StepContact& c = *deepest;
  const std::string a = name_of(w, c.a_is_plane ? w.planes[c.a].id : w.bodies[c.a].id);
  return "contacts overlap deeply: " + a + " and " + name_of(w, w.bodies[c.b].id) + " by " +
         number_text(c.geometry.depth) + " m, " + number_text(100 * c.geometry.depth / size_of_deepest) +
         "% of the radius " + number_text(size_of_deepest) + " m, at t = " + number_text(w.time) +
         " s: the contact laws hold for small overlaps (below " + number_text(100 * kLawRangeRel) +
         "%); stiffen the material (youngs_modulus) or ease the load (said once a run)";
}

}  // namespace

std::string detail::GuardCheck::operator()(const World& w, const RunState& state, const RunGuards& guards,
                                            std::span<RunObserver* const> observers) {
  std::string trouble = check_guards(w, state, guards);
  if (!trouble.empty() && guards.action == GuardAction::Stop) return trouble;
  if (!trouble.empty()) {
    const std::string kind = trouble.substr(0, trouble.find(' ', 4));
    if (kind != last_warning_)
      for (RunObserver* o : observers) o->on_warning(w, state, trouble);
    last_warning_ = kind;
  }
  if (guards.action != GuardAction::Off && !told_deep_)
    if (const std::string deep = deep_overlap(w); !deep.empty()) {
      told_deep_ = true;
      for (RunObserver* o : observers) o->on_warning(w, state, deep);
    }
  return "";
}

}  // namespace gjkdem::dem
