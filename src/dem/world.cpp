#include "gjkdem/dem/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/contact/manifold.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/dem/contact_law.hpp"
#include "gjkdem/dem/half_space.hpp"
#include "gjkdem/dem/rigid_rotation.hpp"
#include "gjkdem/tolerances.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gjkdem::dem {
namespace {

constexpr Real kPi = 3.14159265358979323846;
constexpr Real kInf = std::numeric_limits<Real>::infinity();
// Below these sizes a loop runs on one thread: waking the team costs more.
constexpr std::int64_t kMinParallelBodies = 512;
constexpr std::int64_t kMinParallelContacts = 64;

Vec3 principal_moments(const World& w, const Body& b) {
  return w.templates[b.shape].principal.moments * w.materials[b.material].density;
}

// Velocity of the point p moving with body b, spinning at `spin` (zero for fixed bodies).
Vec3 point_velocity(const Body& b, const Vec3& spin, const Vec3& p) {
  return b.fixed ? Vec3{} : b.velocity + cross(spin, p - b.position);
}

// An incremental spring carried into the tangent plane of unit normal n,
// keeping its length (the contact turned; the stretch did not change).
Vec3 into_tangent_plane(Vec3 spring, const Vec3& n) {
  const Real keep = length(spring);
  spring -= n * dot(spring, n);
  const Real now = length(spring);
  return now > 0 ? spring * (keep / now) : spring;
}

// Caps a spring's load at `cap`: past it the contact slips, and the spring
// keeps only the stretch that holds the capped load.
void cap_spring(Vec3& load, Vec3& spring, Real stiffness, Real cap) {
  if (length(load) > cap) {
    load *= cap / length(load);
    spring = load / -stiffness;
  }
}

// Calibrated damping per (law, restitution): beta for Hertz, zeta for the
// linear and volume laws (both dashpots are 2 x damping x sqrt(k m*)).
// Filled before the parallel part, read-only inside it.
Real damping_for(World& w, Real restitution) {
  const bool hertz = w.model == ContactModel::Hertz;
  const auto [it, inserted] = w.damping_cache.try_emplace({hertz, restitution}, 0);
  if (inserted)
    it->second = hertz ? hertz_damping_for_restitution(restitution) : linear_damping_ratio_for_restitution(restitution);
  return it->second;
}

Real pair_restitution(const Material& ma, const Material& mb) { return std::sqrt(ma.restitution * mb.restitution); }

int thread_count(const World& w) {
#ifdef _OPENMP
  return w.threads > 0 ? w.threads : omp_get_max_threads();
#else
  (void)w;
  return 1;
#endif
}

int thread_id() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

const Material& material_a(const World& w, const StepContact& c) {
  return w.materials[c.a_is_plane ? w.planes[c.a].material : w.bodies[c.a].material];
}

void narrow_phase(World& w, StepContact& c) {
  const Body& b = w.bodies[c.b];
  const Shape& sb = w.templates[b.shape].shape;
  const Transform pb = shape_pose(w, b);
  if (c.a_is_plane) {
    const PlaneWall& wall = w.planes[c.a];
    const HalfSpaceContact h = half_space_contact(sb, pb, wall.point, wall.normal);
    if (!h.touching) return;
    c.normal = wall.normal;
    if (w.model == ContactModel::Volume) {
      if (!h.has_volume || !(h.area > 0) || !(h.volume > 0)) return;
      c.area = h.area;
      c.volume = h.volume;
      c.depth = h.volume / h.area;
      c.depth_integral = h.depth_integral;
      // On the wall, below the centroid of the part under it (half_space.hpp).
      c.point = h.centroid + wall.normal * dot(wall.point - h.centroid, wall.normal);
    } else {
      if (!(h.depth > 0)) return;
      c.depth = h.depth;
      // A flat face on the wall pushes at its middle, not at one corner.
      c.point = h.has_volume && h.area > 0 ? h.face_centroid : h.deepest + wall.normal * (h.depth / 2);
    }
    c.moment = cross(c.point, c.normal);
    c.active = true;
    return;
  }
  const Body& a = w.bodies[c.a];
  const Shape& sa = w.templates[a.shape].shape;
  const Transform pa = shape_pose(w, a);
  GjkCache* cache = c.cache >= 0 ? &w.pair_caches[c.cache].gjk : nullptr;
  if (w.model == ContactModel::Volume) {
    if (!intersect(sa, pa, sb, pb, cache)) return;
    const OverlapResult o = overlap(sa, pa, sb, pb, w.overlap_work[thread_id()]);
    if (o.status != OverlapStatus::Overlapping || !o.has_normal) return;
    c.area = length(o.area_a);
    if (!(c.area > 0)) return;
    c.normal = o.area_a / c.area;
    c.volume = o.volume;
    // Feng's line of action, level with the centroid; the moment carries the
    // twisting couple: about the origin it is (F / |S_A|) M_A.
    c.point = o.application_point + c.normal * dot(o.centroid - o.application_point, c.normal);
    c.depth = o.volume / c.area;
    c.moment = o.moment_a / c.area;
  } else {
    const PenetrationResult r = penetration(sa, pa, sb, pb, cache);
    if (!r.intersect || !(r.depth > 0)) return;
    c.normal = r.normal;
    c.depth = r.depth;
    c.point = (r.witness_a + r.witness_b) * 0.5;
    c.moment = cross(c.point, c.normal);
  }
  c.active = true;
}

// Under the penetration laws a body touching several pieces of one wall (the
// triangles of a mesh, the slabs of a box) gets one contact per cluster of
// nearby, like-facing contacts: the deepest piece carries it.
void merge_wall_contacts(const World& w, std::vector<StepContact>& contacts) {
  struct Key {
    std::uint32_t body, group;
    std::size_t index;
  };
  std::vector<Key> keys;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const StepContact& c = contacts[k];
    if (!c.active || c.a_is_plane) continue;
    const Body& a = w.bodies[c.a];
    const Body& b = w.bodies[c.b];
    if (a.group > 0 && !b.fixed) keys.push_back({c.b, a.group, k});
    else if (b.group > 0 && !a.fixed) keys.push_back({c.a, b.group, k});
  }
  std::stable_sort(keys.begin(), keys.end(),
                   [](const Key& x, const Key& y) { return std::pair(x.body, x.group) < std::pair(y.body, y.group); });
  std::vector<ContactPoint> points;
  std::vector<int> cluster_of;
  for (std::size_t begin = 0; begin < keys.size();) {
    std::size_t end = begin + 1;
    while (end < keys.size() && keys[end].body == keys[begin].body && keys[end].group == keys[begin].group) ++end;
    if (end - begin > 1) {
      points.clear();
      for (std::size_t k = begin; k < end; ++k) {
        const StepContact& c = contacts[keys[k].index];
        const bool wall_is_a = c.b == keys[k].body;
        points.push_back({c.point, wall_is_a ? c.normal : -c.normal, c.depth});  // normals wall -> body
      }
      const Real size = w.templates[w.bodies[keys[begin].body].shape].curvature_radius;
      const std::vector<ContactPoint> merged = cluster_contacts(points, size, kWallMergeCos, &cluster_of);
      for (std::size_t m = 0; m < merged.size(); ++m) {
        std::size_t carrier = 0;  // the deepest member carries the cluster (and its history)
        Real deepest = -kInf;
        for (std::size_t k = begin; k < end; ++k)
          if (cluster_of[k - begin] == static_cast<int>(m) && contacts[keys[k].index].depth > deepest) {
            deepest = contacts[keys[k].index].depth;
            carrier = keys[k].index;
          }
        for (std::size_t k = begin; k < end; ++k)
          if (cluster_of[k - begin] == static_cast<int>(m) && keys[k].index != carrier) contacts[keys[k].index].active = false;
        StepContact& c = contacts[carrier];
        const bool wall_is_a = c.b == keys[begin].body;
        c.point = merged[m].point;
        c.depth = merged[m].depth;
        c.normal = wall_is_a ? merged[m].normal : -merged[m].normal;
        c.moment = cross(c.point, c.normal);
      }
    }
    begin = end;
  }
}

// The history of a contact lives with the body of smaller id (planes have the
// largest ids, so a plane contact lives with its body).
std::pair<std::uint32_t, std::uint64_t> history_owner(const World& w, const StepContact& c) {
  const std::uint64_t id_a = c.a_is_plane ? w.planes[c.a].id : w.bodies[c.a].id;
  const std::uint64_t id_b = w.bodies[c.b].id;
  if (!c.a_is_plane && id_a < id_b) return {c.a, id_b};
  return {c.b, id_a};
}

ContactHistory find_history(const World& w, const StepContact& c) {
  const auto [owner, other] = history_owner(w, c);
  for (const ContactHistory& h : w.bodies[owner].history)
    if (h.other == other) return h;
  return {};
}

void force_law(const World& w, StepContact& c, Real dt) {
  const Body& b = w.bodies[c.b];
  const Body* a = c.a_is_plane ? nullptr : &w.bodies[c.a];
  const Material& ma = material_a(w, c);
  const Material& mb = w.materials[b.material];
  const bool a_fixed = !a || a->fixed;
  const Real m_eff = effective_mass(a_fixed ? kInf : mass_of(w, *a), b.fixed ? kInf : mass_of(w, b));
  const Real damping = w.damping_cache.at({w.model == ContactModel::Hertz, pair_restitution(ma, mb)});
  const Real r_star = effective_radius(a_fixed ? kInf : w.templates[a->shape].curvature_radius,
                                       b.fixed ? kInf : w.templates[b.shape].curvature_radius);
  const Real e_star = effective_modulus(ma.youngs_modulus, ma.poisson_ratio, mb.youngs_modulus, mb.poisson_ratio);
  // Angular velocities once: for the relative velocity and, under the volume
  // law, the relative spin that twists and rocks the contact.
  const Vec3 spin_b = angular_velocity_of(w, b), spin_a = a ? angular_velocity_of(w, *a) : Vec3{};
  const Vec3 v_rel = point_velocity(b, spin_b, c.point) - (a ? point_velocity(*a, spin_a, c.point) : Vec3{});  // b relative to a
  const Real approach = -dot(v_rel, c.normal);
  Real magnitude, k_normal = 0, c_normal = 0;  // normal force on b; its stiffness and dashpot (linear and volume laws)
  if (w.model == ContactModel::Hertz) {
    magnitude = hertz_normal_force({m_eff, r_star, e_star, damping}, c.depth, approach);
    c.elastic = 8.0 / 15 * e_star * std::sqrt(r_star) * std::pow(c.depth, 2.5);
  } else {
    if (w.model == ContactModel::Volume) {
      // k |S_A| on depth V / |S_A| is k V; the potential form scales it by |S_A| / A_ref.
      const Real k_volume = w.volume_stiffness > 0 ? w.volume_stiffness : e_star / r_star;
      k_normal = k_volume * c.area;
      if (c.a_is_plane) {
        c.elastic = k_volume * c.depth_integral;
      } else if (w.volume_form == VolumeForm::Potential) {
        const Real a_ref = std::cbrt(std::fmin(a_fixed ? kInf : w.templates[a->shape].unit_mass.volume,
                                               b.fixed ? kInf : w.templates[b.shape].unit_mass.volume));
        k_normal *= c.area / (a_ref * a_ref);
        c.elastic = 0.5 * k_volume * c.volume * c.volume / (a_ref * a_ref);
      } else {
        c.elastic = 0.5 * k_normal * c.depth * c.depth;  // exact for flat contacts only
      }
    } else {
      k_normal = w.linear_stiffness > 0 ? w.linear_stiffness : e_star * r_star;
      c.elastic = 0.5 * k_normal * c.depth * c.depth;
    }
    // The volume law's dashpot 2 zeta sqrt(k |S_A| m*) v is exact for flat
    // contacts (V linear in the approach) and an approximation otherwise.
    c_normal = linear_damping(damping, k_normal, m_eff);
    magnitude = linear_normal_force(k_normal, c_normal, c.depth, approach);
  }
  const bool has_history = magnitude > 0 && (w.model == ContactModel::Volume || ma.friction * mb.friction > 0);
  const ContactHistory history = has_history ? find_history(w, c) : ContactHistory{};
  const Vec3 spin = spin_b - spin_a;
  const Real r2 = c.area / kPi;  // volume law: the contact seen as a disc of radius r
  // Tangential spring: advance by the relative tangential motion, keep it in
  // the tangent plane, cap it at mu F_n.
  const Real mu = std::sqrt(ma.friction * mb.friction);
  Vec3 ft, twisting;
  c.spring = {};
  c.twist = 0;
  if (mu > 0 && magnitude > 0) {
    const Vec3 v_t = v_rel - c.normal * dot(v_rel, c.normal);
    Vec3 spring = into_tangent_plane(history.spring, c.normal) + v_t * dt;
    // Mindlin's stiffness for Hertz, 2/7 of the normal stiffness otherwise;
    // the dashpot uses the normal law's calibrated damping, so sticking
    // contacts do not ring.
    const Real k_t = w.model == ContactModel::Hertz
                         ? 8 * effective_shear_modulus(ma.youngs_modulus, ma.poisson_ratio, mb.youngs_modulus,
                                                       mb.poisson_ratio) * std::sqrt(r_star * c.depth)
                         : 2.0 / 7 * k_normal;
    const Real c_t = 2 * damping * std::sqrt(k_t * m_eff);
    ft = spring * -k_t - v_t * c_t;  // on b, opposing its motion relative to a
    cap_spring(ft, spring, k_t, mu * magnitude);  // sliding: force at the Coulomb limit
    c.spring = spring;
    c.elastic += 0.5 * k_t * dot(spring, spring);
    if (w.model == ContactModel::Volume) {
      // Twisting friction of the contact area, seen as a disc of radius r of
      // tangential springs and dashpots: stiffness k_t r^2 / 2, slipping at
      // Coulomb's 2/3 mu F_n r (uniform pressure). A single point of friction
      // would let the bodies spin freely about the normal, and Feng's twisting
      // couple of a tilted overlap did spin a stack of cubes apart.
      const Real k_twist = k_t * r2 / 2, c_twist = c_t * r2 / 2;
      const Real twist_rate = dot(spin, c.normal);
      Real twist = history.twist + twist_rate * dt;
      Real couple = -k_twist * twist - c_twist * twist_rate;
      const Real twist_cap = 2.0 / 3 * mu * magnitude * std::sqrt(r2);
      if (std::fabs(couple) > twist_cap) {
        couple = std::copysign(twist_cap, couple);
        twist = -couple / k_twist;
      }
      c.twist = twist;
      c.elastic += 0.5 * k_twist * twist * twist;
      twisting = c.normal * couple;
    }
  }
  c.roll = {};
  if (w.model == ContactModel::Volume && w.rocking_resistance && !c.a_is_plane && magnitude > 0) {
    // Rocking stiffness of the contact area. Any potential of V alone leaves
    // two flat faces free to rock about the middle of their contact (a wedge
    // has the volume of the slab it tilts from), so a stack of cubes is an
    // inverted pendulum. Seen as a disc of radius r of normal springs and
    // dashpots, the area resists a relative rocking angle theta with
    // k r^2 / 4 theta (k, c of the normal law), up to the moment F_n r at
    // which all the pressure sits on the rim. (Plane walls need none: their
    // force through the centroid of the part below the plane rocks back.)
    const Vec3 roll_rate = spin - c.normal * dot(spin, c.normal);
    Vec3 roll = into_tangent_plane(history.roll, c.normal) + roll_rate * dt;
    const Real k_rock = k_normal * r2 / 4, c_rock = c_normal * r2 / 4;
    Vec3 couple = roll * -k_rock - roll_rate * c_rock;
    cap_spring(couple, roll, k_rock, magnitude * std::sqrt(r2));
    c.roll = roll;
    c.elastic += 0.5 * k_rock * dot(roll, roll);
    twisting += couple;
  }
  c.force = c.normal * magnitude + ft;
  c.torque = c.moment * magnitude + cross(c.point, ft) + twisting;
}

void store_spring(World& w, const StepContact& c) {
  const auto [owner, other] = history_owner(w, c);
  for (ContactHistory& h : w.bodies[owner].history)
    if (h.other == other) {
      h.spring = c.spring;
      h.twist = c.twist;
      h.roll = c.roll;
      h.touched = true;
      return;
    }
  w.bodies[owner].history.push_back({other, c.spring, c.twist, c.roll, true});
}

// dt: time since the last evaluation, for the tangential springs (0 at the start).
void compute_forces(World& w, Real dt) {
  const int threads = thread_count(w);
  if (static_cast<int>(w.overlap_work.size()) < threads) w.overlap_work.resize(threads);
  const std::int64_t n = static_cast<std::int64_t>(w.bodies.size());
  w.boxes.resize(w.bodies.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= kMinParallelBodies)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = w.bodies[i];
    b.force = b.fixed ? Vec3{} : w.gravity * mass_of(w, b);
    b.torque = {};
    for (ContactHistory& h : b.history) h.touched = false;
    w.boxes[i] = aabb(w.templates[b.shape].shape, shape_pose(w, b));
  }
  overlapping_pairs(w.boxes, w.sweep, w.candidates, threads);
  align_pair_caches(w.candidates, w.pair_caches);

  std::vector<StepContact>& contacts = w.contacts;
  contacts.clear();
  for (std::size_t k = 0; k < w.candidates.size(); ++k) {
    const auto [i, j] = w.candidates[k];
    if (w.bodies[i].fixed && w.bodies[j].fixed) continue;
    StepContact c;
    c.a = i;
    c.b = j;
    c.cache = static_cast<int>(k);
    contacts.push_back(c);
  }
  // Plane walls: only bodies whose box reaches the plane can touch it (the
  // box bounds the shape, so no contact is left out).
  for (std::uint32_t p = 0; p < w.planes.size(); ++p) {
    const PlaneWall& wall = w.planes[p];
    for (std::uint32_t i = 0; i < w.bodies.size(); ++i) {
      const Aabb& box = w.boxes[i];
      Real lowest = -dot(wall.normal, wall.point);  // of the box's corners above the plane
      for (int k = 0; k < 3; ++k) lowest += wall.normal[k] * (wall.normal[k] > 0 ? box.lo[k] : box.hi[k]);
      if (w.bodies[i].fixed || lowest > 0) continue;
      StepContact c;
      c.a = p;
      c.b = i;
      c.a_is_plane = true;
      contacts.push_back(c);
    }
  }
  // Damping calibrations happen here, outside the threads: once per pair of
  // materials (a handful), not per contact and step.
  for (const Material& ma : w.materials)
    for (const Material& mb : w.materials) damping_for(w, pair_restitution(ma, mb));

  const std::int64_t m = static_cast<std::int64_t>(contacts.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
  for (std::int64_t k = 0; k < m; ++k) narrow_phase(w, contacts[k]);
  if (w.model != ContactModel::Volume) merge_wall_contacts(w, contacts);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 32) if (m >= kMinParallelContacts)
  for (std::int64_t k = 0; k < m; ++k)
    if (contacts[k].active) force_law(w, contacts[k], dt);

  // Sums in the fixed order of the contact list: the same bits for any thread count.
  w.elastic_energy = 0;
  w.last_contacts = 0;
  w.last_wall_contacts = 0;
  for (const StepContact& c : contacts) {
    if (!c.active) continue;
    Body& b = w.bodies[c.b];
    b.force += c.force;
    b.torque += c.torque - cross(b.position, c.force);
    if (!c.a_is_plane) {
      Body& a = w.bodies[c.a];
      a.force -= c.force;
      a.torque -= c.torque - cross(a.position, c.force);
    }
    store_spring(w, c);
    w.elastic_energy += c.elastic;
    ++w.last_contacts;
    if (c.a_is_plane || w.bodies[c.a].fixed || w.bodies[c.b].fixed) ++w.last_wall_contacts;
  }
  for (Body& b : w.bodies)  // contacts that ended forget their spring
    std::erase_if(b.history, [](const ContactHistory& h) { return !h.touched; });
  w.forces_current = true;
}

void kick(World& w, Real h) {
  for (Body& b : w.bodies) {
    if (b.fixed) continue;
    b.velocity += b.force * (h / mass_of(w, b));
    b.angular_momentum += b.torque * h;
  }
}

}  // namespace

// In place (both lists are sorted): drop the stale entries moving left, then spread the kept ones to
// their candidates' slots from the back, where each lands at or after its
// current slot.
void align_pair_caches(std::span<const BodyPair> candidates, std::vector<PairCache>& caches) {
  std::size_t kept = 0;
  for (std::size_t k = 0, i = 0; k < caches.size(); ++k) {
    while (i < candidates.size() && candidates[i] < caches[k].pair) ++i;
    if (i < candidates.size() && candidates[i] == caches[k].pair) {
      caches[kept++] = caches[k];
      ++i;
    }
  }
  // Each candidate took at most one entry, so kept <= candidates.size() even
  // for a list that is not sorted (a damaged checkpoint): memory stays safe.
  caches.resize(candidates.size());
  for (std::size_t j = candidates.size(), from = kept; j-- > 0;)
    caches[j] = from > 0 && caches[from - 1].pair == candidates[j] ? caches[--from] : PairCache{candidates[j], {}};
}

ShapeTemplate make_template(const Shape& shape) {
  ShapeTemplate t;
  t.shape = shape;
  t.unit_mass = mass_properties(shape);
  t.principal = principal_axes(t.unit_mass.inertia);
  if (std::holds_alternative<Point>(shape.core) || std::holds_alternative<Segment>(shape.core)) t.curvature_radius = shape.margin;
  else t.curvature_radius = std::cbrt(3 * t.unit_mass.volume / (4 * kPi));
  return t;
}

ShapeTemplate make_wall_template(const Shape& shape) {
  ShapeTemplate t;
  t.shape = shape;
  t.curvature_radius = kInf;
  return t;
}

Transform shape_pose(const World& w, const Body& b) noexcept {
  const ShapeTemplate& t = w.templates[b.shape];
  const Quat world_from_local = b.orientation * conjugate(t.principal.rotation);
  return Transform::from(b.position - rotate(world_from_local, t.unit_mass.centroid), world_from_local);
}

Vec3 angular_velocity_of(const World& w, const Body& b) noexcept {
  return b.fixed ? Vec3{} : angular_velocity(b.orientation, b.angular_momentum, principal_moments(w, b));
}

Real mass_of(const World& w, const Body& b) noexcept {
  return w.materials[b.material].density * w.templates[b.shape].unit_mass.volume;
}

void step(World& w, Real dt) {
  if (!w.forces_current) compute_forces(w, 0);
  kick(w, dt / 2);
  const int threads = thread_count(w);
  const std::int64_t n = static_cast<std::int64_t>(w.bodies.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= kMinParallelBodies)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = w.bodies[i];
    if (b.fixed) continue;
    b.position += b.velocity * dt;
    rotate_free(b.orientation, b.angular_momentum, principal_moments(w, b), dt);
  }
  compute_forces(w, dt);
  kick(w, dt / 2);
  w.time += dt;
}

Real kinetic_energy(const World& w) noexcept {
  Real e = 0;
  for (const Body& b : w.bodies) {
    if (b.fixed) continue;
    e += 0.5 * mass_of(w, b) * dot(b.velocity, b.velocity);
    e += rotational_energy(b.orientation, b.angular_momentum, principal_moments(w, b));
  }
  return e;
}

Real potential_energy(const World& w) noexcept {
  Real e = 0;
  for (const Body& b : w.bodies)
    if (!b.fixed) e -= mass_of(w, b) * dot(w.gravity, b.position);
  return e;
}

Real critical_time_step(const World& w) {
  Real best = kInf;
  // Every pair of materials and moving templates in use, against each other
  // and against a rigid wall (the stiffest case): a linear contact of
  // stiffness k between masses m lasts pi sqrt(m* / k).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> kinds;
  for (const Body& b : w.bodies)
    if (!b.fixed) kinds.emplace_back(b.shape, b.material);
  std::sort(kinds.begin(), kinds.end());
  kinds.erase(std::unique(kinds.begin(), kinds.end()), kinds.end());
  for (const auto& [shape, material] : kinds) {
    const ShapeTemplate& t = w.templates[shape];
    const Material& mat = w.materials[material];
    const Real m = mat.density * t.unit_mass.volume, r = t.curvature_radius;
    Real stiffest = 0;  // E* against the stiffest material in the world
    for (const Material& other : w.materials)
      stiffest = std::fmax(stiffest, effective_modulus(mat.youngs_modulus, mat.poisson_ratio, other.youngs_modulus,
                                                       other.poisson_ratio));
    Real dt;
    if (w.model == ContactModel::Hertz) {
      // Rayleigh wave time step pi R sqrt(rho / G) / (0.1631 nu + 0.8766), a fifth of it.
      const Real shear = mat.youngs_modulus / (2 * (1 + mat.poisson_ratio));
      dt = 0.2 * kPi * r * std::sqrt(mat.density / shear) / (0.1631 * mat.poisson_ratio + 0.8766);
    } else {
      const Real k = w.model == ContactModel::Linear
                         ? (w.linear_stiffness > 0 ? w.linear_stiffness : stiffest * r)
                         : (w.volume_stiffness > 0 ? w.volume_stiffness : stiffest / r) * kPi * r * r;
      dt = kPi * std::sqrt(m / k) / 20;
    }
    best = std::fmin(best, dt);
  }
  return best;
}

}  // namespace gjkdem::dem
