// One step of the engine: the stages of world.hpp in order.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/contact_force.hpp"
#include "gjkdem/dem/integrator.hpp"
#include "gjkdem/dem/narrow_phase.hpp"
#include "gjkdem/dem/world.hpp"
#include "parallel.hpp"


namespace gjkdem::dem {
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();
using detail::kMinParallelBodies;
using detail::kMinParallelContacts;
using detail::thread_count;
using detail::thread_id;

// Candidate body pairs: moving and driven bodies against each other by the
// sweep (two driven ones never touch), moving against static from the static
// tree (built again when the boxes were all made anew).
void find_candidates(World& w, int threads) {
  StepWorkspace& work = w.work;
  const std::vector<Aabb>& boxes = w.search.boxes.boxes;
  if (!work.static_ready) {
    work.moving.clear();
    std::vector<std::uint32_t> fixed;
    std::vector<Aabb> fixed_boxes;
    for (std::uint32_t i = 0; i < w.bodies.size(); ++i) {
      if (is_static(w.bodies[i])) {
        fixed.push_back(i);
        fixed_boxes.push_back(boxes[i]);
      } else {
        work.moving.push_back(i);
      }
    }
    build_static_tree(fixed_boxes, fixed, work.fixed_tree);
    work.static_ready = true;
  }
  work.moving_boxes.resize(work.moving.size());
  for (std::size_t k = 0; k < work.moving.size(); ++k) work.moving_boxes[k] = boxes[work.moving[k]];
  if (w.cell.active()) {
    if (w.search.renew_cell) w.search.cell = w.cell, w.search.renew_cell = false;
    find_periodic_candidates(w, threads);
    work.candidates_current = true;
    return;
  }
  std::vector<BodyPair>& pairs = work.candidates;
  overlapping_pairs(work.moving_boxes, work.sweep, pairs, threads);
  for (BodyPair& p : pairs) p = {work.moving[p.first], work.moving[p.second]};  // moving is increasing
  if (!w.driven.empty())
    std::erase_if(pairs, [&](const BodyPair& p) { return w.bodies[p.first].fixed && w.bodies[p.second].fixed; });
  std::vector<std::uint32_t> found;
  for (const std::uint32_t i : work.moving) {
    if (w.bodies[i].fixed) continue;
    found.clear();
    query_static_tree(work.fixed_tree, boxes[i], found);
    for (const std::uint32_t f : found) pairs.emplace_back(std::min(i, f), std::max(i, f));
  }
  std::sort(pairs.begin(), pairs.end());
  work.candidates_current = true;
}

// Where b's image lies from b in a periodic world (zero otherwise).
Vec3 shift_of(const World& w, const StepContact& c) { return image_shift_of(w.cell, c); }

// A sphere about each part of a body, world frame (one for a convex body).
struct PartSphere {
  Vec3 centre;
  Real radius;
};

void part_spheres(const ShapeTemplate& t, const Body& b, std::vector<PartSphere>& out, const Vec3& shift = {}) {
  out.clear();
  Transform pose = shape_pose(t, b);
  pose.translation += shift;
  if (t.parts.empty()) {
    out.push_back({pose.translation, bounding_radius(t.shape)});
    return;
  }
  for (const TemplatePart& p : t.parts) out.push_back({apply(pose, p.pose.translation), p.radius});
}

// The contact list in pair-key order (bodies are in increasing id order and
// plane ids lie above every body's): for each body, its candidates with
// larger indices, then the plane walls its box reaches; for compounds, each
// pair of parts whose bounding spheres meet, in part order.
void list_contacts(World& w, const DomainRole* domain) {
  StepWorkspace& work = w.work;
  std::vector<StepContact>& contacts = work.contacts;
  contacts.clear();
  work.keys.clear();
  const std::vector<BodyPair>& pairs = work.candidates;
  std::vector<PartSphere> parts_a, parts_b;
  // Worlds without compounds never look at templates here.
  const bool any_compound =
      std::any_of(w.templates.begin(), w.templates.end(), [](const ShapeTemplate& t) { return !t.parts.empty(); });
  std::size_t k = 0;
  for (std::uint32_t i = 0; i < w.bodies.size(); ++i) {
    const Body& body = w.bodies[i];
    const ShapeTemplate& t = w.templates[body.shape];
    const bool compound = any_compound && !t.parts.empty();
    if (compound) part_spheres(t, body, parts_a);
    for (; k < pairs.size() && pairs[k].first == i; ++k) {
      if (domain && !domain->owns(i) && !domain->owns(pairs[k].second)) continue;  // another domain's pair
      StepContact c;
      c.a = i;
      c.b = pairs[k].second;
      if (!work.candidate_images.empty()) c.image = work.candidate_images[k];
      const Body& other = w.bodies[c.b];
      if (!any_compound || (!compound && w.templates[other.shape].parts.empty())) {
        contacts.push_back(c);
        work.keys.push_back(pair_key(body.id, other.id));
        continue;
      }
      if (!compound) part_spheres(t, body, parts_a);
      part_spheres(w.templates[other.shape], other, parts_b, shift_of(w, c));
      for (std::uint16_t pa = 0; pa < parts_a.size(); ++pa)
        for (std::uint16_t pb = 0; pb < parts_b.size(); ++pb) {
          if (length(parts_a[pa].centre - parts_b[pb].centre) > parts_a[pa].radius + parts_b[pb].radius) continue;
          c.part_a = pa, c.part_b = pb;
          contacts.push_back(c);
          work.keys.push_back(pair_key(body.id, other.id, pa, pb));
        }
    }
    if (body.fixed || (domain && !domain->owns(i))) continue;
    const Aabb& box = w.search.boxes.boxes[i];
    for (std::uint32_t p = 0; p < w.planes.size(); ++p) {
      const PlaneWall& wall = w.planes[p];
      Real lowest = -dot(wall.normal, wall.point);  // of the box's corners above the plane
      for (int axis = 0; axis < 3; ++axis) lowest += wall.normal[axis] * (wall.normal[axis] > 0 ? box.lo[axis] : box.hi[axis]);
      if (lowest > 0) continue;
      StepContact c;
      c.a = p;
      c.b = i;
      c.a_is_plane = true;
      if (!compound) {
        contacts.push_back(c);
        work.keys.push_back(pair_key(body.id, wall.id));
        continue;
      }
      for (std::uint16_t pb = 0; pb < parts_a.size(); ++pb) {
        if (dot(parts_a[pb].centre - wall.point, wall.normal) > parts_a[pb].radius) continue;
        c.part_b = pb;
        contacts.push_back(c);
        work.keys.push_back(pair_key(body.id, wall.id, pb, 0));
      }
    }
  }
}

// A plane wall or a fixed body: infinite mass, radius and volume, no motion.
ContactSide fixed_side() {
  ContactSide s;
  s.mass = s.curvature_radius = s.volume = kInf;
  return s;
}

// A driven wall or body: infinite too, moving with its motion's frame.
ContactSide driven_side(const MotionFrame& f, const Vec3& position, const Vec3& velocity) {
  ContactSide s = fixed_side();
  s.moving = true;
  s.position = position;
  s.velocity = velocity;
  s.spin = f.spin;
  return s;
}

ContactSide plane_side(const World& w, const PlaneWall& p) {
  if (p.motion == 0) return fixed_side();
  const MotionFrame& f = w.work.motion_frames[p.motion - 1];
  return driven_side(f, f.center, f.velocity);
}

// `part`: of a compound, whose own radius of curvature and volume the laws
// use; `shift`: of b's image, which moves with b and the deforming cell.
ContactSide side_of(const World& w, const Body& b, std::uint32_t part, const Vec3& shift = {}) {
  const Vec3 velocity = b.velocity + affine_velocity(w.cell_rate, shift);
  if (b.fixed) return b.motion ? driven_side(w.work.motion_frames[b.motion - 1], b.position + shift, velocity) : fixed_side();
  ContactSide s;
  const ShapeTemplate& t = w.templates[b.shape];
  s.moving = true;
  s.position = b.position + shift;
  s.velocity = velocity;
  s.spin = angular_velocity_of(w, b);
  s.mass = mass_of(w, b);
  s.curvature_radius = t.parts.empty() ? t.curvature_radius : t.parts[part].curvature_radius;
  s.volume = t.parts.empty() ? t.unit_mass.volume : t.parts[part].volume;
  return s;
}

// dt: time since the last evaluation, for the springs (0 at the start).
StepReport compute_forces(World& w, Real dt, const DomainRole* domain) {
  const int threads = thread_count(w.settings.threads);
  StepWorkspace& work = w.work;
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
      update_boxes(w.bodies, w.templates, w.settings.box_skin, w.search.boxes, threads, cell_drift(w));
  if (updated > 0) w.search.renew_cell = true;
  if (updated > 0 || !work.static_ready || !work.candidates_current) find_candidates(w, threads);
  list_contacts(w, domain);
  align_pair_states(work.keys, w.pairs);

  std::vector<StepContact>& contacts = work.contacts;
  const ContactModel model = w.settings.model;
  const std::int64_t m = static_cast<std::int64_t>(contacts.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
  for (std::int64_t k = 0; k < m; ++k) {
    StepContact& c = contacts[k];
    const Body& b = w.bodies[c.b];
    PartPose pb = part_pose(w.templates[b.shape], b, c.part_b);
    pb.pose.translation += shift_of(w, c);
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
  for (const StepContact& c : contacts)
    if (c.geometry.status == GeometryStatus::Unsupported)
      return {StepStatus::UnsupportedPair, c.a_is_plane ? w.planes[c.a].id : w.bodies[c.a].id, w.bodies[c.b].id};
  if (model != ContactModel::Volume) merge_wall_contacts(w.bodies, w.templates, contacts);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
  for (std::int64_t k = 0; k < m; ++k) {
    StepContact& c = contacts[k];
    if (!c.active) continue;
    const Body& b = w.bodies[c.b];
    const ContactSide side_a = c.a_is_plane ? plane_side(w, w.planes[c.a]) : side_of(w, w.bodies[c.a], c.part_a);
    const std::uint32_t material_a = c.a_is_plane ? w.planes[c.a].material : w.bodies[c.a].material;
    const ContactForce f = contact_force(c.geometry, c.a_is_plane, w.material_pairs(material_a, b.material), side_a,
                                         side_of(w, b, c.part_b, shift_of(w, c)), w.pairs[k].history, w.settings, dt);
    c.force = f.force;
    c.torque = f.torque;
    c.history = f.history;
    c.elastic = f.elastic;
  }

  // Sums in the fixed order of the contact list: the same bits for any thread count.
  StepStats& stats = w.stats;
  stats = {};
  stats.box_updates = static_cast<int>(updated);
  // The periodic cell's stress: sum of f x branch (b's centre, or image,
  // from a's centre or the wall's contact point).
  CellTensor virial{};
  const bool periodic = w.cell.active();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const StepContact& c = contacts[k];
    if (!c.active) {
      w.pairs[k].history = {};  // a contact that ended forgets its springs
      continue;
    }
    Body& b = w.bodies[c.b];
    const Vec3 shift = shift_of(w, c);
    push_b(b, c, shift);
    if (!c.a_is_plane) push_a(w.bodies[c.a], c);
    if (periodic) {
      add_virial(virial, c.force, virial_branch(w.bodies, c, shift));
      // A deforming cell works on the bodies through the images' motion.
      if (c.image != kNoImage) stats.wall_power -= dot(c.force, affine_velocity(w.cell_rate, shift));
    }
    w.pairs[k].history = c.history;
    // Power of a driven side on the other: its velocity field against the
    // force and torque it exerts (c.force and c.torque act on b).
    const std::uint32_t motion_a = c.a_is_plane ? w.planes[c.a].motion : w.bodies[c.a].motion;
    if (motion_a) stats.wall_power += driven_power(work.motion_frames[motion_a - 1], c.force, c.torque);
    if (b.motion) stats.wall_power -= driven_power(work.motion_frames[b.motion - 1], c.force, c.torque);
    stats.elastic_energy += c.elastic;
    ++stats.contacts;
    if (c.a_is_plane || w.bodies[c.a].fixed || b.fixed) ++stats.wall_contacts;
  }
  if (periodic)
    for (int k = 0; k < 6; ++k) w.cell_stress[k] = virial[k] / cell_volume(w.cell);
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
  kick(w.bodies, w.templates, w.materials, dt / 2, threads);
  const bool deforming = w.settings.cell_control.deforms();
  if (deforming) control_cell(w, ctx.domain);
  drift(w.bodies, w.templates, w.materials, dt, threads);
  if (deforming) {
    if (deform_cell(w, dt)) w.work.candidates_current = false, w.search.renew_cell = true;  // images renamed
    const Real shortest = shortest_period(w, ctx.domain);
    for (int a = 0; a < 3; ++a)
      if (w.cell.axes[a] && !(cell_width(w.cell, a) > shortest)) {
        w.forces_current = false;
        return {StepStatus::CellTooShort, static_cast<std::uint64_t>(a), 0, shortest};
      }
  }
  if (w.cell.active() && wrap_bodies(w, ctx.domain) > 0) w.work.candidates_current = false, w.search.renew_cell = true;
  ctx.power_before = w.stats.wall_power;
  w.time += dt;
  ctx.kicked_bodies = w.bodies.size();
  // A domain run inserts the inflows' bodies itself, before its exchange
  // (insert_inflow_bodies, domains.hpp).
  ctx.inserted = w.inflows.empty() || ctx.domain ? 0 : run_inflows(w);
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
  kick(std::span(w.bodies).first(kicked), w.templates, w.materials, dt / 2, thread_count(w.settings.threads));
  w.wall_work += 0.5 * dt * (ctx.power_before + w.stats.wall_power);  // trapezoid rule
  return r;
}

StepReport step(World& w, Real dt) {
  StepContext ctx{.dt = dt};
  const StepReport r = begin_step(w, ctx);
  return r.status == StepStatus::Ok ? finish_step(w, ctx) : r;
}

}  // namespace gjkdem::dem
