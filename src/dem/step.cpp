// One step of the engine: the stages of world.hpp in order.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/contact_force.hpp"
#include "gjkdem/dem/integrator.hpp"
#include "gjkdem/dem/narrow_phase.hpp"
#include "gjkdem/dem/world.hpp"
#include "parallel.hpp"
#include "stages.hpp"


namespace gjkdem::dem {
namespace {

using detail::kMinParallelBodies;
using detail::kMinParallelContacts;
using detail::thread_count;
using detail::thread_id;
using detail::side_of;
using detail::plane_side;

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
StepReport compute_forces(World& w, Real dt, const DomainRole* domain) {
  const int threads = thread_count(w.settings.threads);
  StepWorkspace& work = w.work;
  note_template_kinds(w.templates, work.kinds);
  if (static_cast<int>(work.overlap.size()) < threads) work.overlap.resize(threads);
  const std::int64_t n = static_cast<std::int64_t>(w.bodies.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= kMinParallelBodies)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = w.bodies[i];
    b.force = b.fixed ? Vec3{} : w.settings.gravity * mass_of(w, b);
    b.torque = {};
  }
  const std::size_t boxed = w.search.boxes.boxes.size();
  if (boxed == 0 || boxed > w.bodies.size()) {
    work.static_ready = false;  // every box is made anew
  } else {
    for (std::size_t i = boxed; i < w.bodies.size(); ++i) {  // bodies added since (inflows, a continued world)
      if (is_static(w.bodies[i])) work.static_ready = false;
      else if (work.static_ready) work.moving.push_back(static_cast<std::uint32_t>(i));
    }
  }
  const std::size_t updated =
      update_boxes(w.bodies, w.templates, w.settings.box_skin, w.search.boxes, threads, cell_drift(w.cell, w.search.cell));
  if (updated > 0) w.search.renew_cell = true;
  const std::span<const Aabb> boxes = w.search.boxes.boxes;
  if (updated > 0 || !work.static_ready || !work.candidates_current) {
    if (w.cell.active() && w.search.renew_cell) w.search.cell = w.cell, w.search.renew_cell = false;
    detail::find_candidates(w.bodies, boxes, w.cell.active() ? &w.search.cell : nullptr, !w.driven.empty(), threads,
                            work);
  }
  detail::list_contacts(w.bodies, w.templates, w.planes, boxes, w.cell, domain, work);
  const ContactModel model = w.settings.model;
  if (work.kinds.surface_grains)
    detail::expand_surface_contacts(w.bodies, w.templates, w.planes, w.cell, model, w.pairs, threads, work);
  align_pair_states(work.keys, w.pairs);

  std::vector<StepContact>& contacts = work.contacts;
  const std::int64_t m = static_cast<std::int64_t>(contacts.size());
  const bool held = any_intact(w.bonds);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
  for (std::int64_t k = 0; k < m; ++k) {
    StepContact& c = contacts[k];
    if (!c.a_is_plane && held && bonded(w.bonds, std::min(w.bodies[c.a].id, w.bodies[c.b].id),
                                        std::max(w.bodies[c.a].id, w.bodies[c.b].id))) {
      c.geometry = {};  // an intact bond carries the pair's load (bonds.hpp)
      continue;
    }
    if (c.surface) {  // found by expand_surface_contacts
      w.pairs[k].anchor = c.anchor;
      continue;
    }
    const Body& b = w.bodies[c.b];
    PartPose pb = part_pose(w.templates[b.shape], b, c.part_b);
    pb.pose.translation += image_shift_of(w.cell, c);
    if (c.a_is_plane) {
      c.geometry = plane_contact(w.planes[c.a], *pb.shape, pb.pose, model);
    } else {
      const Body& a = w.bodies[c.a];
      const PartPose pa = part_pose(w.templates[a.shape], a, c.part_a);
      c.geometry = body_contact(*pa.shape, pa.pose, *pb.shape, pb.pose, model, &w.pairs[k].gjk,
                                work.overlap[thread_id()]);
    }
    c.active = c.geometry.status == GeometryStatus::Touching;
  }
  for (const StepContact& c : contacts) {
    if (c.geometry.status == GeometryStatus::Unsupported)
      return {StepStatus::UnsupportedPair, c.a_is_plane ? w.planes[c.a].id : w.bodies[c.a].id, w.bodies[c.b].id};
    if (c.geometry.status == GeometryStatus::Through)
      return {StepStatus::ThroughWall, w.planes[c.a].id, w.bodies[c.b].id};
    if (c.geometry.status == GeometryStatus::Engulfed)
      return {StepStatus::Engulfed, w.bodies[c.a].id, w.bodies[c.b].id};
  }
  if (work.kinds.wall_faces) {
    const StepReport crossed = detail::find_wall_crossing(w.bodies, w.templates, work.motion_frames, w.cell, contacts, dt);
    if (crossed.status != StepStatus::Ok) return crossed;
  }
  if (model != ContactModel::Volume) merge_wall_contacts(w.bodies, w.templates, contacts);
  const detail::SideSources sources{{w.templates, w.materials}, work.motion_frames, w.cell_rate};
#pragma omp parallel for num_threads(threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
  for (std::int64_t k = 0; k < m; ++k) {
    StepContact& c = contacts[k];
    if (!c.active) continue;
    const Body& b = w.bodies[c.b];
    const ContactSide side_a =
        c.a_is_plane ? plane_side(sources, w.planes[c.a]) : side_of(sources, w.bodies[c.a], c.part_a);
    const std::uint32_t material_a = c.a_is_plane ? w.planes[c.a].material : w.bodies[c.a].material;
    const ContactForce f = contact_force(c.geometry, c.a_is_plane, w.material_pairs(material_a, b.material), side_a,
                                         side_of(sources, b, c.part_b, image_shift_of(w.cell, c)), w.pairs[k].history, w.settings, dt);
    c.force = f.force;
    c.torque = f.torque;
    c.history = f.history;
    c.elastic = f.elastic;
  }

  w.stats = detail::sum_forces(contacts, w.bodies, w.pairs, w.planes, work.motion_frames, w.cell, w.cell_rate,
                               w.cell_stress);
  w.stats.box_updates = static_cast<int>(updated);
  work.bond_energies.assign(w.bonds.size(), 0);  // a broken bond holds none
  if (held) {
    const BondSums bonds = add_bond_forces(w.bonds, w.bodies, {w.templates, w.materials}, w.time, work.bond_energies);
    w.stats.elastic_energy += bonds.elastic;
    w.stats.bonds_broken = bonds.broke;
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
  kick(w.bodies, makeup, dt / 2, threads);
  const bool deforming = w.settings.cell_control.deforms();
  if (deforming) control_cell(w.settings.cell_control, w.cell_stress, w.cell, w.cell_rate, moved);
  drift(w.bodies, makeup, dt, threads);
  if (deforming) {
    if (deform_cell(w.cell, w.cell_rate, dt)) w.work.candidates_current = false, w.search.renew_cell = true;  // images renamed
    const Real shortest = shortest_period(w, ctx.domain);
    for (int a = 0; a < 3; ++a)
      if (w.cell.axes[a] && !(cell_width(w.cell, a) > shortest)) {
        w.forces_current = false;
        return {StepStatus::CellTooShort, static_cast<std::uint64_t>(a), 0, shortest};
      }
  }
  if (w.cell.active() && wrap_bodies(w.cell, w.cell_rate, w.search.boxes, moved) > 0) w.work.candidates_current = false, w.search.renew_cell = true;
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
  kick(std::span(w.bodies).first(kicked), {w.templates, w.materials}, dt / 2, thread_count(w.settings.threads));
  w.wall_work += 0.5 * dt * (ctx.power_before + w.stats.wall_power);  // trapezoid rule
  // Grains break at the step's end, on its forces; the fragments' forces
  // are found at once (a domain run breaks its domains' grains in
  // run_loop.cpp, together).
  if (!ctx.domain && world_breaks(w)) {
    const int broken = break_grains(w);
    if (broken > 0) {
      const StepReport again = compute_forces_now(w);
      if (again.status != StepStatus::Ok) return again;
    }
    w.stats.broken = broken;
  }
  return r;
}

StepReport step(World& w, Real dt) {
  StepContext ctx{.dt = dt};
  const StepReport r = begin_step(w, ctx);
  return r.status == StepStatus::Ok ? finish_step(w, ctx) : r;
}

}  // namespace gjkdem::dem
