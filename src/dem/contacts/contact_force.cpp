#include "gjkdem/dem/contact_force.hpp"

#include <cmath>
#include <limits>

#include "gjkdem/dem/contact_law.hpp"

namespace gjkdem::dem {
namespace {


// Velocity of the point p moving with a side of the contact.
Vec3 point_velocity(const ContactSide& s, const Vec3& p) {
  return s.moving ? s.velocity + cross(s.spin, p - s.position) : Vec3{};
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

}  // namespace

ContactForce contact_force(const ContactGeometry& g, bool a_is_plane, const MaterialPair& mp, const ContactSide& a,
                           const ContactSide& b, const PairHistory& before, const WorldSettings& s,
                           Real dt) noexcept {
  ContactForce out;
  const Real m_eff = effective_mass(a.mass, b.mass);
  const Real r_star = effective_radius(a.curvature_radius, b.curvature_radius);
  const Real e_star = mp.youngs_modulus;
  const Vec3 v_rel = point_velocity(b, g.point) - point_velocity(a, g.point);  // b relative to a
  const Real approach = -dot(v_rel, g.normal);
  // A patch of surface grains takes, under Hertz and linear too, an energy
  // of its overlap alone, so that its force is the energy's gradient: the
  // law's depth is delta = V / a_ref^2 between bodies, sqrt(2 I) / a_ref on a
  // plane wall (I the depth integral; a flat face of area a_ref^2 at depth d
  // gives delta = d both ways), a_ref^3 the smaller body's volume. The
  // approach x moves delta by `lever` = d(delta)/dx: |S_A| / a_ref^2 (dV/dx =
  // |S_A|), or V / (a_ref^2 delta) on a plane (dI/dx = V); the force is the
  // law's at delta times the lever, on the gradient's line (surface_patches.cpp).
  Real depth = g.depth, lever = 1;
  if (g.patch && s.model != ContactModel::Volume) {
    const Real a_ref = std::cbrt(std::fmin(a.volume, b.volume)), a_ref2 = a_ref * a_ref;
    depth = a_is_plane ? std::sqrt(2 * g.depth_integral) / a_ref : g.volume / a_ref2;
    lever = !(depth > 0) ? 0 : a_is_plane ? g.volume / (a_ref2 * depth) : g.area / a_ref2;
  }
  Real magnitude = 0, k_normal = 0, c_normal = 0;  // normal force on b; its stiffness and dashpot (linear and volume laws)
  if (!(lever > 0)) {
    // a patch of no volume: no force
  } else if (s.model == ContactModel::Hertz) {
    // The law on delta, whose motion has the mass m* / lever^2.
    magnitude = hertz_normal_force({m_eff / (lever * lever), r_star, e_star, mp.damping}, depth, approach * lever) * lever;
    out.elastic = 8.0 / 15 * e_star * std::sqrt(r_star) * std::pow(depth, 2.5);
  } else {
    if (s.model == ContactModel::Volume) {
      // k |S_A| on depth V / |S_A| is k V; the potential form scales it by |S_A| / A_ref.
      const Real k_volume = s.volume_stiffness > 0 ? s.volume_stiffness : e_star / r_star;
      k_normal = k_volume * g.area;
      if (a_is_plane) {
        out.elastic = k_volume * g.depth_integral;
      } else if (s.volume_form == VolumeForm::Potential) {
        const Real a_ref = std::cbrt(std::fmin(a.volume, b.volume));
        k_normal *= g.area / (a_ref * a_ref);
        out.elastic = 0.5 * k_volume * g.volume * g.volume / (a_ref * a_ref);
      } else {
        out.elastic = 0.5 * k_normal * g.depth * g.depth;  // exact for flat contacts only
      }
    } else {
      const Real k_linear = s.linear_stiffness > 0 ? s.linear_stiffness : e_star * r_star;
      out.elastic = 0.5 * k_linear * depth * depth;
      k_normal = k_linear * lever * lever;  // along the approach
    }
    // The volume law's dashpot 2 zeta sqrt(k |S_A| m*) v is exact for flat
    // contacts (V linear in the approach) and an approximation otherwise.
    c_normal = linear_damping(mp.damping, k_normal, m_eff);
    magnitude = linear_normal_force(k_normal, c_normal, depth / lever, approach);
  }
  const Vec3 spin = b.spin - a.spin;
  const Real r2 = g.area / kPi;  // volume law: the contact seen as a disc of radius r
  // Tangential spring: advance by the relative tangential motion, keep it in
  // the tangent plane, cap it at mu F_n.
  const Real mu = mp.friction;
  Vec3 ft, twisting;
  if (mu > 0 && magnitude > 0) {
    const Vec3 v_t = v_rel - g.normal * dot(v_rel, g.normal);
    Vec3 spring = into_tangent_plane(before.spring, g.normal) + v_t * dt;
    // Mindlin's stiffness for Hertz, 2/7 of the normal stiffness otherwise;
    // the dashpot uses the normal law's calibrated damping, so sticking
    // contacts do not ring.
    const Real k_t = s.model == ContactModel::Hertz ? 8 * mp.shear_modulus * std::sqrt(r_star * depth)
                                                    : 2.0 / 7 * k_normal;
    const Real c_t = 2 * mp.damping * std::sqrt(k_t * m_eff);
    ft = spring * -k_t - v_t * c_t;  // on b, opposing its motion relative to a
    cap_spring(ft, spring, k_t, mu * magnitude);  // sliding: force at the Coulomb limit
    out.history.spring = spring;
    out.elastic += 0.5 * k_t * dot(spring, spring);
    if (s.model == ContactModel::Volume) {
      // Twisting friction of the contact area, seen as a disc of radius r of
      // tangential springs and dashpots: stiffness k_t r^2 / 2, slipping at
      // Coulomb's 2/3 mu F_n r (uniform pressure). A single point of friction
      // would let the bodies spin freely about the normal, and Feng's twisting
      // couple of a tilted overlap did spin a stack of cubes apart.
      const Real k_twist = k_t * r2 / 2, c_twist = c_t * r2 / 2;
      const Real twist_rate = dot(spin, g.normal);
      Real twist = before.twist + twist_rate * dt;
      Real couple = -k_twist * twist - c_twist * twist_rate;
      const Real twist_cap = 2.0 / 3 * mu * magnitude * std::sqrt(r2);
      if (std::fabs(couple) > twist_cap) {
        couple = std::copysign(twist_cap, couple);
        twist = -couple / k_twist;
      }
      out.history.twist = twist;
      out.elastic += 0.5 * k_twist * twist * twist;
      twisting = g.normal * couple;
    }
  }
  // One rolling spring, slider and dashpot on the relative rolling angle
  // theta, made of two resistances in parallel (they share theta; their
  // limits add):
  // - the volume law's rocking of the contact area (between bodies). Any
  //   potential of V alone leaves two flat faces free to rock about the
  //   middle of their contact (a wedge has the volume of the slab it tilts
  //   from), so a stack of cubes is an inverted pendulum. Seen as a disc of
  //   radius r of normal springs and dashpots, the area resists theta with
  //   k r^2 / 4 (k, c of the normal law), up to the moment F_n r at which all
  //   the pressure sits on the rim. Plane walls need none: their force through
  //   the centroid of the part below the plane rocks back.
  // - the material's rolling resistance (Ai et al. 2011, type C): stiffness
  //   2.25 k mu_r^2 R*^2, limit mu_r R* F_n, dashpot eta_r 2 sqrt(I_r k_r)
  //   with I_r = 7/5 m* R*^2 (a sphere about its contact point). It is what
  //   stops a ball rolling on a plane, or a grain rocking on a curved top:
  //   rolling without slip loses nothing to the normal or tangential dashpots.
  const bool rocks = s.model == ContactModel::Volume && s.rocking_resistance && !a_is_plane;
  const Real mu_roll = mp.rolling_friction;
  if ((rocks || mu_roll > 0) && magnitude > 0) {
    const Real arm_area = rocks ? std::sqrt(r2) : 0;
    const Real arm_rolling = mu_roll * r_star;
    // Hertz has no constant k: its tangent stiffness dF/d(delta).
    const Real k_contact =
        s.model == ContactModel::Hertz ? 2 * e_star * std::sqrt(r_star * depth) * lever * lever : k_normal;
    const Real k_rolling = 2.25 * k_contact * arm_rolling * arm_rolling;
    const Real inertia = 1.4 * m_eff * r_star * r_star;
    const Real k_roll = (rocks ? k_contact * r2 / 4 : 0) + k_rolling;
    const Real c_roll = (rocks ? c_normal * r2 / 4 : 0) + mp.rolling_damping * 2 * std::sqrt(inertia * k_rolling);
    const Vec3 roll_rate = spin - g.normal * dot(spin, g.normal);
    Vec3 roll = into_tangent_plane(before.roll, g.normal) + roll_rate * dt;
    Vec3 couple = roll * -k_roll - roll_rate * c_roll;
    cap_spring(couple, roll, k_roll, magnitude * (arm_area + arm_rolling));
    out.history.roll = roll;
    out.elastic += 0.5 * k_roll * dot(roll, roll);
    twisting += couple;
  }
  out.force = g.normal * magnitude + ft;
  out.torque = g.moment * magnitude + cross(g.point, ft) + twisting;
  return out;
}

}  // namespace gjkdem::dem
