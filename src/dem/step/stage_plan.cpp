// The stage plan (stage_plan.hpp): the table, and each walked stage's
// function, which hands its stage (in its own file) the parts of the world
// it takes.
#include "gjkdem/dem/stage_plan.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/contact_force.hpp"
#include "gjkdem/dem/narrow_phase.hpp"
#include "parallel.hpp"
#include "step/stages.hpp"

namespace gjkdem::dem {
namespace {

using detail::kMinParallelBodies;
using detail::kMinParallelContacts;
using detail::thread_id;

StepReport reset_loads(ForceEvaluation& e) {
  World& w = e.world;
  const std::int64_t n = static_cast<std::int64_t>(w.bodies.size());
  if (w.applied_loads) {
#pragma omp parallel for num_threads(e.threads) schedule(static) if (n >= kMinParallelBodies)
    for (std::int64_t i = 0; i < n; ++i) {
      Body& b = w.bodies[i];
      b.force = b.fixed ? Vec3{} : w.settings.gravity * mass_of(w, b) + b.applied_force;
      b.torque = b.fixed ? Vec3{} : b.applied_torque;
    }
  } else {
#pragma omp parallel for num_threads(e.threads) schedule(static) if (n >= kMinParallelBodies)
    for (std::int64_t i = 0; i < n; ++i) {
      Body& b = w.bodies[i];
      b.force = b.fixed ? Vec3{} : w.settings.gravity * mass_of(w, b);
      b.torque = {};
    }
  }
  return {};
}

StepReport make_boxes(ForceEvaluation& e) {
  World& w = e.world;
  StepWorkspace& work = w.work;
  const std::size_t boxed = w.search.boxes.boxes.size();
  if (boxed == 0 || boxed > w.bodies.size()) {
    work.static_ready = false;  // every box is made anew
  } else {
    for (std::size_t i = boxed; i < w.bodies.size(); ++i) {  // bodies added since (inflows, a continued world)
      if (is_static(w.bodies[i])) work.static_ready = false;
      else if (work.static_ready) work.moving.push_back(static_cast<std::uint32_t>(i));
    }
  }
  e.box_updates = update_boxes(w.bodies, w.templates, w.settings.box_skin, w.search.boxes, e.threads,
                               cell_drift(w.cell.now, w.search.cell));
  if (e.box_updates > 0) w.search.renew_cell = true;
  return {};
}

StepReport find_candidates(ForceEvaluation& e) {
  World& w = e.world;
  if (e.box_updates > 0 || !w.work.static_ready || !w.work.candidates_current) {
    if (w.cell.now.active() && w.search.renew_cell) w.search.cell = w.cell.now, w.search.renew_cell = false;
    detail::find_candidates(w.bodies, w.search.boxes.boxes, w.cell.now.active() ? &w.search.cell : nullptr,
                            !w.driven.empty(), e.threads, w.work);
  }
  return {};
}

StepReport list_contacts(ForceEvaluation& e) {
  World& w = e.world;
  detail::list_contacts(w.bodies, w.templates, w.planes, w.search.boxes.boxes, w.cell.now, e.domain, w.work, w.results);
  return {};
}

StepReport surface_patches(ForceEvaluation& e) {
  World& w = e.world;
  if (w.work.kinds.surface_grains)
    detail::expand_surface_contacts(w.bodies, w.templates, w.planes, w.cell.now, w.pairs, e.threads,
                                    w.results, w.work);
  return {};
}

StepReport align_pairs(ForceEvaluation& e) {
  align_pair_states(e.world.results.keys, e.world.pairs);
  return {};
}

StepReport narrow_phase(ForceEvaluation& e) {
  World& w = e.world;
  std::vector<StepContact>& contacts = w.results.contacts;
  const std::int64_t m = static_cast<std::int64_t>(contacts.size());
  const ContactModel model = w.settings.model;
  e.bonds_held = any_intact(w.bonds);
  const bool held = e.bonds_held;
#pragma omp parallel for num_threads(e.threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
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
    pb.pose.translation += image_shift_of(w.cell.now, c);
    if (c.a_is_plane) {
      c.geometry = plane_contact(w.planes[c.a], *pb.shape, pb.pose, model);
    } else {
      const Body& a = w.bodies[c.a];
      const PartPose pa = part_pose(w.templates[a.shape], a, c.part_a);
      c.geometry = body_contact(*pa.shape, pa.pose, *pb.shape, pb.pose, model, &w.pairs[k].gjk,
                                w.work.overlap[thread_id()]);
    }
    c.active = c.geometry.status == GeometryStatus::Touching;
  }
  return {};
}

// The first contact (in list order) the model could not take or found past holding.
StepReport geometry_checks(ForceEvaluation& e) {
  const World& w = e.world;
  for (const StepContact& c : w.results.contacts) {
    if (c.geometry.status == GeometryStatus::Unsupported)
      return {StepStatus::UnsupportedPair, c.a_is_plane ? w.planes[c.a].id : w.bodies[c.a].id, w.bodies[c.b].id};
    if (c.geometry.status == GeometryStatus::Through)
      return {StepStatus::ThroughWall, w.planes[c.a].id, w.bodies[c.b].id};
    if (c.geometry.status == GeometryStatus::Engulfed)
      return {StepStatus::Engulfed, w.bodies[c.a].id, w.bodies[c.b].id};
    if (c.geometry.status == GeometryStatus::Pierced)
      return {StepStatus::Pierced, w.bodies[c.a].id, w.bodies[c.b].id};
  }
  return {};
}

StepReport wall_crossing(ForceEvaluation& e) {
  const World& w = e.world;
  if (!w.work.kinds.wall_faces) return {};
  return detail::find_wall_crossing(w.bodies, w.templates, w.results.motion_frames, w.cell.now, w.results.contacts, e.dt);
}

StepReport body_crossing(ForceEvaluation& e) {
  const World& w = e.world;
  return detail::find_body_crossing(w.bodies, w.templates, w.cell.now, w.results.contacts);
}

StepReport merge_walls(ForceEvaluation& e) {
  World& w = e.world;
  if (w.settings.model != ContactModel::Volume) merge_wall_contacts(w.bodies, w.templates, w.results.contacts);
  return {};
}

StepReport contact_laws(ForceEvaluation& e) {
  World& w = e.world;
  std::vector<StepContact>& contacts = w.results.contacts;
  const std::int64_t m = static_cast<std::int64_t>(contacts.size());
  const detail::SideSources sources{{w.templates, w.materials}, w.results.motion_frames, w.cell.rate};
#pragma omp parallel for num_threads(e.threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
  for (std::int64_t k = 0; k < m; ++k) {
    StepContact& c = contacts[k];
    if (!c.active) continue;
    const Body& b = w.bodies[c.b];
    const ContactSide side_a = c.a_is_plane ? detail::plane_side(sources, w.planes[c.a])
                                            : detail::side_of(sources, w.bodies[c.a], c.part_a);
    const std::uint32_t material_a = c.a_is_plane ? w.planes[c.a].material : w.bodies[c.a].material;
    const ContactForce f =
        contact_force(c.geometry, c.a_is_plane, w.material_pairs(material_a, b.material), side_a,
                      detail::side_of(sources, b, c.part_b, image_shift_of(w.cell.now, c)), w.pairs[k].history,
                      w.settings, e.dt);
    c.force = f.force;
    c.torque = f.torque;
    c.history = f.history;
    c.elastic = f.elastic;
  }
  return {};
}

StepReport sum_forces(ForceEvaluation& e) {
  World& w = e.world;
  w.stats = detail::sum_forces(w.results.contacts, w.bodies, w.pairs, w.planes, w.results.motion_frames, w.cell.now,
                               w.cell.rate, w.cell.stress);
  w.stats.box_updates = static_cast<int>(e.box_updates);
  return {};
}

StepReport bond_forces(ForceEvaluation& e) {
  World& w = e.world;
  w.results.bond_energies.assign(w.bonds.size(), 0);  // a broken bond holds none
  if (e.bonds_held) {
    const BondSums bonds = add_bond_forces(w.bonds, w.bodies, {w.templates, w.materials}, w.time, w.results.bond_energies);
    w.stats.elastic_energy += bonds.elastic;
    w.stats.bonds_broken = bonds.broke;
  }
  return {};
}

// Grains break at the step's end, on its forces; the fragments' forces
// are found at once (a domain run breaks its domains' grains in
// run_loop.cpp, together).
StepReport break_grains(ForceEvaluation& e) {
  World& w = e.world;
  if (e.domain || !world_breaks(w)) return {};
  const int broken = dem::break_grains(w);
  if (broken > 0) {
    // The splits left the contact list as the grains had it (apply_splits
    // drops only their pairs): what it held, then what the fragments hold
    // at the same positions.
    const Real before = contact_energy(w);
    const StepReport again = compute_forces_now(w);
    if (again.status != StepStatus::Ok) return again;
    w.split_energy += contact_energy(w) - before;
  }
  w.stats.broken = broken;
  return {};
}

using P = StagePhase;

constexpr std::array kPlan{
    Stage{"first kick", P::Integrate, "integration/integrator.cpp", "forces, torques", "velocities, angular momenta (half a step)"},
    Stage{"cell control", P::Integrate, "model/periodic.cpp", "the cell's stress, its control",
          "a deforming cell's velocity gradient; the field's change on the velocities"},
    Stage{"drift", P::Integrate, "integration/integrator.cpp, integration/rigid_rotation.cpp", "velocities, angular momenta",
          "positions; orientations by the symplectic free rotation"},
    Stage{"cell", P::Integrate, "model/periodic.cpp", "the velocity gradient", "the cell's edges; bodies wrapped back in"},
    Stage{"inflows", P::Integrate, "build/inflow.cpp", "the clock, the inflows' regions", "bodies inserted"},
    Stage{"motions", P::Integrate, "model/motion.cpp", "the clock", "driven walls and bodies at the step's end time"},
    Stage{"listeners", P::Integrate, "run/run_loop.cpp", "a rank's own bodies",
          "applied loads, by a run's step listeners (run.hpp)"},
    Stage{"exchange", P::Integrate, "domains/domain_exchange.cpp", "the domains' bodies",
          "a domain run only: new bodies, boxes, migrations, ghosts"},
    Stage{"loads", P::BeforeForces, "step/stage_plan.cpp", "gravity, masses, applied loads", "forces, torques",
          reset_loads},
    Stage{"boxes", P::BeforeForces, "broad_phase/boxes.cpp", "positions, orientations, the box skin",
          "boxes, remade only when a body may have left its own", make_boxes},
    Stage{"candidates", P::BeforeForces, "broad_phase/candidates.cpp, broad_phase/broad_phase.cpp", "boxes, the periodic cell",
          "candidate pairs: moving boxes by sweep and prune in strips, fixed ones from a static tree, images",
          find_candidates},
    Stage{"contact list", P::BeforeForces, "contacts/contact_list.cpp", "candidates, plane walls, compound parts",
          "contacts in pair-key order, one per pair of parts whose spheres meet", list_contacts},
    Stage{"wall crossing", P::BeforeForces, "contacts/wall_crossing.cpp", "the contact list's pairs with mesh wall pieces, velocities",
          "a body whose centre crossed a piece: the step stops (every law and contact kind: before patches are found)",
          wall_crossing},
    Stage{"surface patches", P::BeforeForces, "contacts/surface_patch_stage.cpp", "contacts of surface grains, last patches",
          "one contact per patch with its geometry, its slot matched by its anchor", surface_patches},
    Stage{"pair store", P::BeforeForces, "model/pair_state.cpp", "the contact list's keys",
          "springs and warm starts aligned with the contacts", align_pairs},
    Stage{"narrow phase", P::PerContact, "contacts/narrow_phase.cpp", "poses, shapes, warm starts, bonds",
          "each contact's geometry: GJK/EPA, the overlap region, half-spaces", narrow_phase},
    Stage{"geometry checks", P::PerContact, "step/stage_plan.cpp", "each contact's geometry",
          "the first pair the model cannot take, or past holding: the step stops", geometry_checks},
    Stage{"body crossing", P::PerContact, "contacts/body_crossing.cpp",
          "deep contacts of two convex bodies, their centres; deep patches of surface grains, their deep points",
          "two bodies passing through each other (a centre or deep point inside the other): the step stops", body_crossing},
    Stage{"wall merge", P::PerContact, "contacts/narrow_phase.cpp", "a body's contacts with one wall's pieces",
          "one contact per body and wall (Hertz and linear laws)", merge_walls},
    Stage{"laws", P::PerContact, "contacts/contact_force.cpp, contacts/contact_sides.cpp", "geometry, material pair, sides, springs",
          "each contact's force, torque, springs and elastic energy", contact_laws},
    Stage{"sums", P::Reduce, "contacts/force_sums.cpp", "the contacts' forces, in list order",
          "forces on bodies, springs kept, stats, the driven walls' power, the cell's stress", sum_forces},
    Stage{"bonds", P::Reduce, "breakage/bonds.cpp", "bonds, their bodies' poses",
          "the bonds' forces and energies; bonds that break", bond_forces},
    Stage{"second kick", P::AfterForces, "integration/integrator.cpp", "forces, torques",
          "velocities, angular momenta (half a step); the driven walls' work"},
    Stage{"breakage", P::AfterStep, "breakage/breakage.cpp", "the step's contacts, strengths",
          "grains split in two, their fragments' forces", break_grains},
};

}  // namespace

std::span<const Stage> stage_plan() noexcept { return kPlan; }

std::string_view phase_name(StagePhase phase) noexcept {
  switch (phase) {
    case StagePhase::Integrate: return "integrate";
    case StagePhase::BeforeForces: return "before forces";
    case StagePhase::PerContact: return "per contact";
    case StagePhase::Reduce: return "reduce";
    case StagePhase::AfterForces: return "after forces";
    case StagePhase::AfterStep: return "after the step";
  }
  return "?";
}

std::string stage_plan_markdown() {
  std::string s = "| stage | phase | file | reads | writes |\n|---|---|---|---|---|\n";
  for (const Stage& stage : kPlan) {
    std::string files;  // each in backticks
    for (std::string_view rest = stage.file; !rest.empty();) {
      const std::size_t comma = rest.find(", ");
      files += (files.empty() ? "`" : ", `") + std::string(rest.substr(0, comma)) + "`";
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 2);
    }
    s += "| " + std::string(stage.name) + " | " + std::string(phase_name(stage.phase)) + " | " + files + " | " +
         std::string(stage.reads) + " | " + std::string(stage.writes) + " |\n";
  }
  return s;
}

}  // namespace gjkdem::dem
