// The computed channels of body_channels.hpp: values worked out from the
// world rather than held, and the presence tests of features' channels.
#include "gjkdem/dem/body_channels.hpp"

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

void frame_orientation_channel(const World& w, const Body& b, Real* out) noexcept {
  const Quat q = shape_orientation(w.templates[b.shape], b);
  out[0] = q.w, out[1] = q.x, out[2] = q.y, out[3] = q.z;
}

void angular_velocity_channel(const World& w, const Body& b, Real* out) noexcept {
  const Vec3 s = angular_velocity_of(w, b);
  out[0] = s.x, out[1] = s.y, out[2] = s.z;
}

bool applied_loads_on(const World& w) noexcept { return w.applied_loads; }

}  // namespace gjkdem::dem
