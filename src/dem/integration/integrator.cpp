#include "gjkdem/dem/integrator.hpp"

#include <cstdint>

#include "gjkdem/dem/rigid_rotation.hpp"
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

using detail::kMinParallelBodies;

}  // namespace

void kick(std::span<Body> bodies, const Makeup& makeup, Real h, int threads, bool applied) noexcept {
  const std::int64_t n = static_cast<std::int64_t>(bodies.size());
  if (!applied) {
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= kMinParallelBodies)
    for (std::int64_t i = 0; i < n; ++i) {
      Body& b = bodies[i];
      if (b.fixed) continue;
      const Real mass = makeup.mass(b);
      b.velocity += b.force * (h / mass);
      b.angular_momentum += b.torque * h;
    }
    return;
  }
  // The kick's change of kinetic energy is h f.(v0 + v1) / 2 + h t.(w0 + w1) / 2,
  // linear in the force and torque: the applied load's share is its work.
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= kMinParallelBodies)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (b.fixed) continue;
    const Real mass = makeup.mass(b);
    const Vec3 v0 = b.velocity, l0 = b.angular_momentum;
    b.velocity += b.force * (h / mass);
    b.angular_momentum += b.torque * h;
    Real work = dot(b.applied_force, v0 + b.velocity);
    if (b.applied_torque != Vec3{}) {
      const Vec3 moments = makeup.moments(b);
      work += dot(b.applied_torque, angular_velocity(b.orientation, l0, moments) +
                                        angular_velocity(b.orientation, b.angular_momentum, moments));
    }
    b.applied_work += 0.5 * h * work;
  }
}

void drift(std::span<Body> bodies, const Makeup& makeup, Real dt, int threads) noexcept {
  const std::int64_t n = static_cast<std::int64_t>(bodies.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= detail::kMinParallelRotations)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (b.fixed) continue;
    b.position += b.velocity * dt;
    rotate_free(b.orientation, b.angular_momentum, makeup.moments(b), dt);
  }
}

}  // namespace gjkdem::dem
