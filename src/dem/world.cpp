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

// Calibrated damping per (law, restitution), computed once: beta for Hertz,
// zeta for the linear and volume laws (both dashpots are 2 x damping x sqrt(k m*)).
Real damping_for(World& w, Real restitution) {
  const bool hertz = w.model == ContactModel::Hertz;
  const auto [it, inserted] = w.damping_cache.try_emplace({hertz, restitution}, 0);
  if (inserted)
    it->second = hertz ? hertz_damping_for_restitution(restitution) : linear_damping_ratio_for_restitution(restitution);
  return it->second;
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
    // Per pair: restitution and friction from both materials, the damping
    // calibrated for the law once per restitution value.
    const Real damping = damping_for(w, std::sqrt(ma.restitution * mb.restitution));
    const Real r_star = effective_radius(a.fixed ? kInf : w.templates[a.shape].curvature_radius,
                                         b.fixed ? kInf : w.templates[b.shape].curvature_radius);
    Vec3 normal, p;      // unit A -> B; where friction and damping act
    Real depth = 0;      // penetration depth, or for the volume law V / |S_A|
    Real k_normal = 0;   // linear and volume laws: dF/d(depth), which the dashpots scale with
    OverlapResult o;  // volume law only
    if (w.model == ContactModel::Volume) {
      o = overlap(sa, pa, sb, pb, w.overlap_work);
      if (o.status != OverlapStatus::Overlapping || !o.has_normal) continue;
      const Real area = length(o.area_a);
      normal = o.area_a / area;
      p = o.application_point + normal * dot(o.centroid - o.application_point, normal);  // on the line, level with the centroid
      k_normal = w.volume_stiffness * area;
      depth = o.volume / area;
    } else {
      const PenetrationResult r = penetration(sa, pa, sb, pb);
      if (!r.intersect || !(r.depth > 0)) continue;
      normal = r.normal;
      depth = r.depth;
      p = (r.witness_a + r.witness_b) * 0.5;
      k_normal = w.linear_stiffness;
    }
    const Vec3 v_rel = point_velocity(w, b, p) - point_velocity(w, a, p);  // B relative to A at the contact
    const Real approach = -dot(v_rel, normal);
    Real magnitude;  // normal force on B along the normal (N)
    if (w.model == ContactModel::Hertz) {
      const HertzParameters hp{m_eff, r_star,
                               effective_modulus(ma.youngs_modulus, ma.poisson_ratio, mb.youngs_modulus, mb.poisson_ratio),
                               damping};
      magnitude = hertz_normal_force(hp, depth, approach);
    } else {
      magnitude = linear_normal_force(k_normal, linear_damping(damping, k_normal, m_eff), depth, approach);
    }
    if (w.model == ContactModel::Volume) {
      // F = k V along S_A, acting on the line through Feng's point with the
      // twisting couple: the moment about the origin is (F / |S_A|) M_A. The
      // dashpot 2 zeta sqrt(k |S_A| m*) v is exact for flat contacts (V linear
      // in the approach) and an approximation otherwise.
      const Vec3 f = normal * magnitude, moment = o.moment_a * (magnitude / length(o.area_a));
      b.force += f;
      b.torque += moment - cross(b.position, f);
      a.force -= f;
      a.torque -= moment - cross(a.position, f);
    } else {
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
      const Vec3 v_t = v_rel - normal * dot(v_rel, normal);
      const Real keep = length(hist.spring);
      hist.spring -= normal * dot(hist.spring, normal);  // into the current tangent plane
      if (length(hist.spring) > 0) hist.spring *= keep / length(hist.spring);
      hist.spring += v_t * dt;
      // Mindlin's stiffness for Hertz, 2/7 of the normal stiffness otherwise;
      // the dashpot uses the normal law's calibrated damping, so sticking
      // contacts do not ring.
      const Real k_t = w.model == ContactModel::Hertz
                           ? 8 * effective_shear_modulus(ma.youngs_modulus, ma.poisson_ratio, mb.youngs_modulus,
                                                         mb.poisson_ratio) * std::sqrt(r_star * depth)
                           : 2.0 / 7 * k_normal;
      const Real c_t = 2 * damping * std::sqrt(k_t * m_eff);
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
