// Bonds of bonded assemblies (bonds.hpp, docs/breakage.md).
#include "gjkdem/dem/bonds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gjkdem/dem/rigid_rotation.hpp"

namespace gjkdem::dem {
namespace {

// The rotation vector (rad) of a unit quaternion: axis times angle, the
// angle in [0, pi].
Vec3 rotation_vector(Quat q) noexcept {
  if (q.w < 0) q = {-q.w, -q.x, -q.y, -q.z};
  const Vec3 v{q.x, q.y, q.z};
  const Real s = length(v);
  if (!(s > 0)) return {};
  return v * (2 * std::atan2(s, q.w) / s);
}

Real smallest(const Vec3& v) noexcept { return std::fmin(v.x, std::fmin(v.y, v.z)); }

// Reduced mass or moment of inertia of two bodies.
Real reduced(Real x, Real y) noexcept { return x * y / (x + y); }

// The body of an id (bodies are in id order), or null.
template <class B>
B* find(std::span<B> bodies, std::uint64_t id) noexcept {
  const std::size_t i = index_of_body(bodies, id);
  return i < bodies.size() ? &bodies[i] : nullptr;
}

}  // namespace

Bond glue_bodies(const Body& a, const Body& b, const Material& material, const Vec3& centroid, const Vec3& normal,
                 Real area, Real polar_moment) {
  const Glue& g = material.glue;
  Bond bond;
  bond.a = a.id, bond.b = b.id;
  const Quat ia = conjugate(a.orientation), ib = conjugate(b.orientation);
  bond.point_a = rotate(ia, centroid - a.position);
  bond.point_b = rotate(ib, centroid - b.position);
  bond.normal_a = rotate(ia, normal);
  bond.normal_b = rotate(ib, normal);
  bond.rest = ia * b.orientation;
  bond.area = area;
  bond.polar_moment = polar_moment;
  bond.normal_stiffness =
      g.normal_stiffness > 0 ? g.normal_stiffness : material.youngs_modulus / length(b.position - a.position);
  bond.shear_stiffness =
      g.shear_stiffness > 0 ? g.shear_stiffness : bond.normal_stiffness / (2 * (1 + material.poisson_ratio));
  bond.tensile_strength = g.tensile_strength;
  bond.shear_strength = g.shear_strength;
  bond.moment_strength = g.moment_strength;
  bond.damping = g.damping;
  return bond;
}

Real bond_radius(const Bond& bond) noexcept { return std::sqrt(2 * bond.polar_moment / bond.area); }

BondLoad bond_load(const Bond& bond, const Body& a, const Body& b, const Makeup& makeup) noexcept {
  // The face's centre as each body carries it, and its normal (the mean of
  // the two bodies' copies: neither side is favoured).
  const Vec3 pa = a.position + rotate(a.orientation, bond.point_a);
  const Vec3 pb = b.position + rotate(b.orientation, bond.point_b);
  const Vec3 n = normalized(rotate(a.orientation, bond.normal_a) + rotate(b.orientation, bond.normal_b));
  const Vec3 centre = (pa + pb) * Real(0.5);
  // Opening and sliding of the face, and how fast.
  const Vec3 gap = pb - pa;
  const Real opening = dot(gap, n);
  const Vec3 sliding = gap - n * opening;
  const Vec3 wa = angular_velocity(a.orientation, a.angular_momentum, makeup.moments(a));
  const Vec3 wb = angular_velocity(b.orientation, b.angular_momentum, makeup.moments(b));
  const Vec3 rate = b.velocity + cross(wb, centre - b.position) - a.velocity - cross(wa, centre - a.position);
  const Real opening_rate = dot(rate, n);
  const Vec3 sliding_rate = rate - n * opening_rate;
  // Turn of b against a since gluing (world frame): bending about axes in
  // the face, twisting about its normal.
  const Vec3 turn = rotation_vector(b.orientation * conjugate(a.orientation * bond.rest));
  const Real twist = dot(turn, n);
  const Vec3 bend = turn - n * twist;
  const Vec3 spin = wb - wa;
  const Real twist_rate = dot(spin, n);
  const Vec3 bend_rate = spin - n * twist_rate;

  const Real A = bond.area, J = bond.polar_moment, I = J / 2;  // I: about an axis in the face (the mean of its two)
  const Real kn = bond.normal_stiffness * A, ks = bond.shear_stiffness * A;
  const Real kb = bond.normal_stiffness * I, kt = bond.shear_stiffness * J;
  const Real mass = reduced(makeup.mass(a), makeup.mass(b));
  const Real inertia = reduced(smallest(makeup.moments(a)), smallest(makeup.moments(b)));
  const Real z = 2 * bond.damping;
  BondLoad load;
  load.force = n * -(kn * opening + z * std::sqrt(kn * mass) * opening_rate) -
               (sliding * ks + sliding_rate * (z * std::sqrt(ks * mass)));
  const Vec3 moment = -(bend * kb + bend_rate * (z * std::sqrt(kb * inertia))) -
                      n * (kt * twist + z * std::sqrt(kt * inertia) * twist_rate);
  load.torque = moment + cross(centre, load.force);
  load.elastic = Real(0.5) * (kn * opening * opening + ks * dot(sliding, sliding) + kb * dot(bend, bend) +
                              kt * twist * twist);
  // Beam stresses at the rim, at the equivalent radius R: sigma = k_n
  // (opening + R |bend|) (the force over A plus M R / I), tau = k_s
  // (|sliding| + R |twist|).
  const Real R = bond_radius(bond);
  const Real bending = bond.normal_stiffness * R * length(bend), twisting = bond.shear_stiffness * R * std::fabs(twist);
  load.tension = bond.normal_stiffness * opening + bending;
  load.shear = bond.shear_stiffness * length(sliding) + twisting;
  load.moment = std::fmax(bending, twisting);
  return load;
}

bool bond_breaks(const Bond& bond, const BondLoad& load) noexcept {
  return load.tension >= bond.tensile_strength || load.shear >= bond.shear_strength ||
         (bond.moment_strength > 0 && load.moment >= bond.moment_strength);
}

bool bonded(std::span<const Bond> bonds, std::uint64_t lo, std::uint64_t hi) noexcept {
  const auto at = std::lower_bound(bonds.begin(), bonds.end(), std::pair{lo, hi}, [](const Bond& x, const std::pair<std::uint64_t, std::uint64_t>& key) {
    return x.a != key.first ? x.a < key.first : x.b < key.second;
  });
  return at != bonds.end() && at->a == lo && at->b == hi && at->intact;
}

std::vector<std::uint64_t> held_bodies(std::span<const Bond> bonds) {
  std::vector<std::uint64_t> held;
  for (const Bond& bond : bonds)
    if (bond.intact) held.push_back(bond.a), held.push_back(bond.b);
  std::sort(held.begin(), held.end());
  return held;
}

bool any_intact(std::span<const Bond> bonds) noexcept {
  return std::any_of(bonds.begin(), bonds.end(), [](const Bond& b) { return b.intact; });
}

std::size_t broken_bonds(std::span<const Bond> bonds) noexcept {
  return static_cast<std::size_t>(std::count_if(bonds.begin(), bonds.end(), [](const Bond& b) { return !b.intact; }));
}

BondSums add_bond_forces(std::span<Bond> bonds, std::span<Body> bodies, const Makeup& makeup, Real time,
                         std::span<Real> energies) {
  BondSums sums;
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    Bond& bond = bonds[k];
    energies[k] = 0;
    if (!bond.intact) continue;
    Body* a = find(bodies, bond.a);
    Body* b = find(bodies, bond.b);
    if (!a || !b) continue;
    const BondLoad load = bond_load(bond, *a, *b, makeup);
    if (bond_breaks(bond, load)) {
      bond.intact = 0;
      bond.broken_time = time;
      ++sums.broke;
      continue;
    }
    b->force += load.force;
    b->torque += load.torque - cross(b->position, load.force);
    a->force -= load.force;
    a->torque -= load.torque - cross(a->position, load.force);
    sums.elastic += load.elastic;
    energies[k] = load.elastic;
  }
  return sums;
}

Real bond_time_step(std::span<const Bond> bonds, std::span<const Body> bodies, const Makeup& makeup) noexcept {
  Real best = std::numeric_limits<Real>::infinity();
  for (const Bond& bond : bonds) {
    const Body* a = find(bodies, bond.a);
    const Body* b = find(bodies, bond.b);
    if (!a || !b) continue;
    const Real A = bond.area, J = bond.polar_moment;
    const Real stiff = std::fmax(bond.normal_stiffness, bond.shear_stiffness);
    const Real mass = reduced(makeup.mass(*a), makeup.mass(*b));
    const Real inertia = reduced(smallest(makeup.moments(*a)), smallest(makeup.moments(*b)));
    // A spring k between masses m* rings with period 2 pi sqrt(m* / k);
    // pi sqrt(m* / k) / 20 is the contacts' rule (world.hpp).
    best = std::fmin(best, kPi * std::sqrt(mass / (stiff * A)) / 20);
    best = std::fmin(best, kPi * std::sqrt(inertia / (stiff * J)) / 20);
  }
  return best;
}

}  // namespace gjkdem::dem
