#include "gjkdem/dem/integrator.hpp"

#include <cstdint>

#include "gjkdem/dem/rigid_rotation.hpp"
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

using detail::kMinParallelBodies;

}  // namespace

void kick(std::span<Body> bodies, std::span<const ShapeTemplate> templates, std::span<const Material> materials,
          Real h, int threads) noexcept {
  const std::int64_t n = static_cast<std::int64_t>(bodies.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= kMinParallelBodies)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (b.fixed) continue;
    const Real mass = materials[b.material].density * templates[b.shape].unit_mass.volume;
    b.velocity += b.force * (h / mass);
    b.angular_momentum += b.torque * h;
  }
}

void drift(std::span<Body> bodies, std::span<const ShapeTemplate> templates, std::span<const Material> materials,
           Real dt, int threads) noexcept {
  const std::int64_t n = static_cast<std::int64_t>(bodies.size());
#pragma omp parallel for num_threads(threads) schedule(static) if (n >= detail::kMinParallelRotations)
  for (std::int64_t i = 0; i < n; ++i) {
    Body& b = bodies[i];
    if (b.fixed) continue;
    b.position += b.velocity * dt;
    rotate_free(b.orientation, b.angular_momentum,
                templates[b.shape].principal.moments * materials[b.material].density, dt);
  }
}

}  // namespace gjkdem::dem
