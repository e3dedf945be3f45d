#include "gjkdem/dem/integrator.hpp"

#include <cstdint>

#include "gjkdem/dem/rigid_rotation.hpp"
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

using detail::kMinParallelBodies;

}  // namespace

void kick(std::span<Body> bodies, const Makeup& makeup, Real h, int threads) noexcept {
  const std::int64_t n = static_cast<std::int64_t>(bodies.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= kMinParallelBodies)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (b.fixed) continue;
    const Real mass = makeup.mass(b);
    b.velocity += b.force * (h / mass);
    b.angular_momentum += b.torque * h;
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
