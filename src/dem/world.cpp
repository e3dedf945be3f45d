#include "gjkdem/dem/world.hpp"

#include <cmath>
#include <limits>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/dem/contact_law.hpp"
#include "gjkdem/dem/rigid_rotation.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kPi = 3.14159265358979323846;
constexpr Real kInf = std::numeric_limits<Real>::infinity();

Vec3 principal_moments(const World& w, const Body& b) {
  return w.templates[b.shape].principal.moments * w.materials[b.material].density;
}

Vec3 angular_velocity_of(const World& w, const Body& b) {
  return b.fixed ? Vec3{} : angular_velocity(b.orientation, b.angular_momentum, principal_moments(w, b));
}

Vec3 point_velocity(const World& w, const Body& b, const Vec3& p) {
  return b.fixed ? Vec3{} : b.velocity + cross(angular_velocity_of(w, b), p - b.position);
}

// Calibrated damping per (law, restitution), computed once.
Real damping_for(World& w, Real restitution) {
  const Real key = w.model == ContactModel::Hertz ? restitution : -restitution;
  const auto it = w.damping_cache.find(key);
  if (it != w.damping_cache.end()) return it->second;
  return w.damping_cache[key] = w.model == ContactModel::Hertz ? hertz_damping_for_restitution(restitution)
                                                               : linear_damping_ratio_for_restitution(restitution);
}

void apply(Body& b, const Vec3& force, const Vec3& point) {
  b.force += force;
  b.torque += cross(point - b.position, force);
}

ContactHistory& history_of(Body& owner, std::uint64_t other) {
  for (ContactHistory& h : owner.history)
    if (h.other == other) return h;
  owner.history.push_back({other, {}, false});
  return owner.history.back();
}

// dt: time since the last evaluation, for the tangential springs (0 at the start).
void compute_forces(World& w, Real dt) {
  for (Body& b : w.bodies)
    for (ContactHistory& h : b.history) h.touched = false;
  for (Body& b : w.bodies) {
    b.force = b.fixed ? Vec3{} : w.gravity * mass_of(w, b);
    b.torque = {};
  }
  w.boxes.resize(w.bodies.size());
  for (std::size_t i = 0; i < w.bodies.size(); ++i)
    w.boxes[i] = aabb(w.templates[w.bodies[i].shape].shape, shape_pose(w, w.bodies[i]));
  overlapping_pairs(w.boxes, w.sweep_order, w.candidates);
  for (const auto& [i, j] : w.candidates) {
    Body& a = w.bodies[i];
    Body& b = w.bodies[j];
    if (a.fixed && b.fixed) continue;
    const Shape& sa = w.templates[a.shape].shape;
    const Shape& sb = w.templates[b.shape].shape;
    const Transform pa = shape_pose(w, a), pb = shape_pose(w, b);
    const Material& ma = w.materials[a.material];
    const Material& mb = w.materials[b.material];
    const Real m_eff = effective_mass(a.fixed ? kInf : mass_of(w, a), b.fixed ? kInf : mass_of(w, b));
    const Real restitution = std::sqrt(ma.restitution * mb.restitution);
    Vec3 normal, p;       // unit A -> B; where friction and damping act
    Real magnitude = 0;   // normal force on B along the normal (N)
    Real depth = 0;       // penetration depth, or for the volume law V / |S_A|
    Real k_normal = 0;    // dF/d(depth): the normal stiffness the dashpots scale with
    if (w.model == ContactModel::Volume) {
      // F = k V along S_A, acting on the line through Feng's point with the
      // twisting couple: the moment about the origin is (F / |S_A|) M_A. The
      // dashpot 2 zeta sqrt(k |S_A| m*) v is exact for flat contacts (V linear
      // in the approach) and an approximation otherwise.
      const OverlapResult o = overlap(sa, pa, sb, pb, w.overlap_work);
      if (o.status != OverlapStatus::Overlapping || !o.has_normal) continue;
      const Real area = length(o.area_a);
      normal = o.area_a / area;
      p = o.application_point + normal * dot(o.centroid - o.application_point, normal);  // on the line, level with the centroid
      k_normal = w.volume_stiffness * area;
      depth = o.volume / area;
      const Real approach = -dot(point_velocity(w, b, p) - point_velocity(w, a, p), normal);
      magnitude = linear_normal_force(k_normal, linear_damping(damping_for(w, restitution), k_normal, m_eff), depth, approach);
      const Vec3 f = normal * magnitude, moment = o.moment_a * (magnitude / area);  // on B, about the world origin
      b.force += f;
      b.torque += moment - cross(b.position, f);
      a.force -= f;
      a.torque -= moment - cross(a.position, f);
    } else {
      const PenetrationResult r = penetration(sa, pa, sb, pb);
      if (!r.intersect || !(r.depth > 0)) continue;
      normal = r.normal;
      depth = r.depth;
      p = (r.witness_a + r.witness_b) * 0.5;
      const Real approach = -dot(point_velocity(w, b, p) - point_velocity(w, a, p), normal);
      if (w.model == ContactModel::Hertz) {
        const HertzParameters hp{m_eff,
                                 effective_radius(a.fixed ? kInf : w.templates[a.shape].curvature_radius,
                                                  b.fixed ? kInf : w.templates[b.shape].curvature_radius),
                                 effective_modulus(ma.youngs_modulus, ma.poisson_ratio, mb.youngs_modulus, mb.poisson_ratio),
                                 damping_for(w, restitution)};
        magnitude = hertz_normal_force(hp, depth, approach);
      } else {
        k_normal = w.linear_stiffness;
        magnitude = linear_normal_force(k_normal, linear_damping(damping_for(w, restitution), k_normal, m_eff), depth, approach);
      }
      apply(b, normal * magnitude, p);
      apply(a, normal * -magnitude, p);
    }
    // Tangential spring: advance by the relative tangential motion, keep it in
    // the tangent plane, cap it at mu F_n.
    Body& owner = a.id < b.id ? a : b;
    ContactHistory& hist = history_of(owner, a.id < b.id ? b.id : a.id);
    hist.touched = true;
    const Real mu = std::sqrt(ma.friction * mb.friction);
    Vec3 ft;
    if (mu > 0 && magnitude > 0) {
      const Vec3 v_rel = point_velocity(w, b, p) - point_velocity(w, a, p);  // B relative to A
      const Vec3 v_t = v_rel - normal * dot(v_rel, normal);
      const Real keep = length(hist.spring);
      hist.spring -= normal * dot(hist.spring, normal);  // into the current tangent plane
      if (length(hist.spring) > 0) hist.spring *= keep / length(hist.spring);
      hist.spring += v_t * dt;
      // Stiffness and dashpot of the tangential spring; the dashpot uses the
      // normal law's calibrated damping, so sticking contacts do not ring.
      Real k_t, c_t;
      const Real damping = damping_for(w, restitution);
      if (w.model == ContactModel::Hertz) {
        const Real g_star = 1 / (2 * (2 - ma.poisson_ratio) * (1 + ma.poisson_ratio) / ma.youngs_modulus +
                                 2 * (2 - mb.poisson_ratio) * (1 + mb.poisson_ratio) / mb.youngs_modulus);
        const Real r_star = effective_radius(a.fixed ? kInf : w.templates[a.shape].curvature_radius,
                                             b.fixed ? kInf : w.templates[b.shape].curvature_radius);
        k_t = 8 * g_star * std::sqrt(r_star * depth);
        c_t = 2 * damping * std::sqrt(k_t * m_eff);
      } else {  // linear and volume laws: 2/7 of the normal stiffness
        k_t = 2.0 / 7 * k_normal;
        c_t = linear_damping(damping, k_t, m_eff);
      }
      ft = hist.spring * -k_t - v_t * c_t;  // on B, opposing its motion relative to A
      const Real cap = mu * magnitude;
      if (length(ft) > cap) {  // sliding: force at the Coulomb limit, the spring holds it
        ft *= cap / length(ft);
        hist.spring = ft / -k_t;
      }
    } else {
      hist.spring = {};
    }
    apply(b, ft, p);
    apply(a, -ft, p);
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

ShapeTemplate make_template(const Shape& shape) {
  ShapeTemplate t;
  t.shape = shape;
  t.unit_mass = mass_properties(shape);
  t.principal = principal_axes(t.unit_mass.inertia);
  if (std::holds_alternative<Point>(shape.core) || std::holds_alternative<Segment>(shape.core)) t.curvature_radius = shape.margin;
  else t.curvature_radius = std::cbrt(3 * t.unit_mass.volume / (4 * kPi));
  return t;
}

Transform shape_pose(const World& w, const Body& b) noexcept {
  const ShapeTemplate& t = w.templates[b.shape];
  const Quat world_from_local = b.orientation * conjugate(t.principal.rotation);
  return Transform::from(b.position - rotate(world_from_local, t.unit_mass.centroid), world_from_local);
}

Real mass_of(const World& w, const Body& b) noexcept {
  return w.materials[b.material].density * w.templates[b.shape].unit_mass.volume;
}

void step(World& w, Real dt) {
  if (!w.forces_current) compute_forces(w, 0);
  kick(w, dt / 2);
  for (Body& b : w.bodies) {
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

}  // namespace gjkdem::dem
