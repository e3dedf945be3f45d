// Queries on a whole world: masses, energies and the critical time step.
#include "gjkdem/dem/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/dem/contact_law.hpp"
#include "gjkdem/dem/rigid_rotation.hpp"

namespace gjkdem::dem {

Transform shape_pose(const World& w, const Body& b) noexcept { return shape_pose(w.templates[b.shape], b); }

Real mass_of(const World& w, const Body& b) noexcept { return Makeup{w.templates, w.materials}.mass(b); }

Vec3 principal_moments(const World& w, const Body& b) noexcept { return Makeup{w.templates, w.materials}.moments(b); }

Vec3 angular_velocity_of(const World& w, const Body& b) noexcept {
  return b.fixed ? Vec3{} : angular_velocity(b.orientation, b.angular_momentum, principal_moments(w, b));
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

Real contact_energy(const World& w) noexcept {
  Real e = 0;
  for (const StepContact& c : w.results.contacts)
    if (c.active) e += c.elastic;
  return e;
}

Real potential_energy(const World& w) noexcept {
  Real e = 0;
  for (const Body& b : w.bodies)
    if (!b.fixed) e -= mass_of(w, b) * dot(w.settings.gravity, b.position);
  return e;
}

Real critical_time_step(const World& w) {
  Real best = std::numeric_limits<Real>::infinity();
  // Every pair of materials and moving templates in use, against each other
  // and against a rigid wall (the stiffest case): a linear contact of
  // stiffness k between masses m lasts pi sqrt(m* / k).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> kinds;
  for (const Body& b : w.bodies)
    if (!b.fixed) kinds.emplace_back(b.shape, b.material);
  for (const Inflow& f : w.inflows)  // bodies to come
    for (const std::uint32_t t : f.templates) kinds.emplace_back(t, f.material);
  std::sort(kinds.begin(), kinds.end());
  kinds.erase(std::unique(kinds.begin(), kinds.end()), kinds.end());
  const WorldSettings& s = w.settings;
  for (const auto& [shape, material] : kinds) {
    const ShapeTemplate& t = w.templates[shape];
    const Material& mat = w.materials[material];
    const Real m = mat.density * t.unit_mass.volume, r = t.curvature_radius;
    Real stiffest = 0;  // E* against the stiffest material in the world
    for (const Material& other : w.materials)
      stiffest = std::fmax(stiffest, effective_modulus(mat.youngs_modulus, mat.poisson_ratio, other.youngs_modulus,
                                                       other.poisson_ratio));
    Real dt;
    if (s.model == ContactModel::Hertz) {
      // Rayleigh wave time step pi R sqrt(rho / G) / (0.1631 nu + 0.8766), a
      // fifth of it, over the Mindlin factor: a sphere's tangential contact
      // (stiffness k_t = 2 (1 - nu) / (2 - nu) k_n, effective mass 2/7 of
      // the normal one, as the sphere turns) rings sqrt(3.5 k_t / k_n), 1.5
      // (nu = 0.5) to 2.2 (nu = -1) times, faster than its normal contact. Without it frictional
      // spheres compressed to p / E = 1e-3 never came to rest.
      const Real nu = mat.poisson_ratio;
      const Real shear = mat.youngs_modulus / (2 * (1 + nu));
      const Real mindlin = std::sqrt(3.5 * 2 * (1 - nu) / (2 - nu));
      dt = 0.2 * kPi * r * std::sqrt(mat.density / shear) / (0.1631 * nu + 0.8766) / mindlin;
    } else {
      const Real k = s.model == ContactModel::Linear
                         ? (s.linear_stiffness > 0 ? s.linear_stiffness : stiffest * r)
                         : (s.volume_stiffness > 0 ? s.volume_stiffness : stiffest / r) * kPi * r * r;
      dt = kPi * std::sqrt(m / k) / 20;
    }
    // Rolling resistance (contact_force.cpp, Ai et al.'s type C) turns the
    // body on a spring k_r = 2.25 k (mu_r R*)^2 against its smallest moment
    // of inertia: against a wall (R* = R) it rings mu_r R sqrt(2.25 m / I)
    // times as fast as the normal contact, faster above mu_r of about 0.4
    // for a sphere (mu_r = 1000 created energy at the normal law's step).
    Real mu_roll = 0;
    for (const Material& other : w.materials)
      mu_roll = std::fmax(mu_roll, std::sqrt(mat.rolling_friction * other.rolling_friction));
    const Vec3 moments = t.principal.moments * mat.density;
    const Real inertia = std::fmin(moments.x, std::fmin(moments.y, moments.z));
    if (mu_roll > 0 && inertia > 0) {
      const Real faster = mu_roll * r * std::sqrt(2.25 * m / inertia);
      if (faster > 1) dt /= faster;
    }
    // Grains that break (breakage.hpp) leave fragments as small as 3/4 of
    // `unbreakable_below` across (a plane through a convex body's centroid
    // leaves at least (3/4)^3 of its volume on each side, Gruenbaum 1960):
    // the step is the one of the smallest fragment, as short as their size
    // (k grows as the size, m as its cube), or as its power 3/2 under a
    // given linear stiffness.
    if (mat.strength.mean > 0) {
      const Real shrink = std::fmin(1, 0.75 * mat.strength.smallest / grain_size(t));
      dt *= s.model == ContactModel::Linear && s.linear_stiffness > 0 ? shrink * std::sqrt(shrink) : shrink;
    }
    best = std::fmin(best, dt);
  }
  // The bonds' springs (bonds.hpp), by the same rule.
  return std::fmin(best, bond_time_step(w.bonds, w.bodies, {w.templates, w.materials}));
}

Real largest_reach(const World& w, const DomainRole* domain) noexcept {
  Real reach = domain ? domain->whole_reach : 0;  // of moving bodies, and of those inflows will insert
  for (const Body& b : w.bodies)
    if (!b.fixed) reach = std::fmax(reach, w.templates[b.shape].reach);
  for (const Inflow& f : w.inflows)
    for (const std::uint32_t t : f.templates) reach = std::fmax(reach, w.templates[t].reach);
  return reach;
}

Real shortest_period(const World& w, const DomainRole* domain) noexcept {
  return 4 * largest_reach(w, domain) * (1 + w.settings.box_skin);
}

void place_driven(World& w) {
  std::vector<MotionFrame>& frames = w.results.motion_frames;
  frames.resize(w.motions.size());
  for (std::size_t k = 0; k < w.motions.size(); ++k) frames[k] = motion_frame(w.motions[k], w.time);
  for (const DrivenBody& d : w.driven) {
    Body& b = w.bodies[d.body];
    const MotionFrame& f = frames[b.motion - 1];
    const PrescribedMotion& m = w.motions[b.motion - 1];
    b.position = moved_point(f, m, d.position);
    b.orientation = normalized(f.rotation * d.orientation);
    b.velocity = point_velocity(f, b.position);
  }
  for (PlaneWall& p : w.planes) {
    if (p.motion == 0) continue;
    const MotionFrame& f = frames[p.motion - 1];
    p.point = moved_point(f, w.motions[p.motion - 1], p.given_point);
    p.normal = normalized(rotate(f.rotation, p.given_normal));
  }
}

}  // namespace gjkdem::dem
