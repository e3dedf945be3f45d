// What the contact laws see of each side of a contact (stages.hpp).
#include <limits>

#include "gjkdem/dem/rigid_rotation.hpp"
#include "step/stages.hpp"

namespace gjkdem::dem::detail {
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

// A plane wall or a fixed body: infinite mass, radius and volume, no motion.
ContactSide fixed_side() {
  ContactSide s;
  s.mass = s.curvature_radius = s.volume = kInf;
  return s;
}

// A driven wall or body: infinite too, moving with its motion's frame.
ContactSide driven_side(const MotionFrame& f, const Vec3& position, const Vec3& velocity) {
  ContactSide s = fixed_side();
  s.moving = true;
  s.position = position;
  s.velocity = velocity;
  s.spin = f.spin;
  return s;
}

}  // namespace

ContactSide plane_side(const SideSources& sources, const PlaneWall& p) {
  if (p.motion == 0) return fixed_side();
  const MotionFrame& f = sources.motion_frames[p.motion - 1];
  return driven_side(f, f.center, f.velocity);
}

ContactSide side_of(const SideSources& sources, const Body& b, std::uint32_t part, const Vec3& shift) {
  const Vec3 velocity = b.velocity + affine_velocity(sources.cell_rate, shift);
  if (b.fixed) return b.motion ? driven_side(sources.motion_frames[b.motion - 1], b.position + shift, velocity) : fixed_side();
  ContactSide s;
  const Makeup& makeup = sources.makeup;
  const ShapeTemplate& t = makeup.templates[b.shape];
  s.moving = true;
  s.position = b.position + shift;
  s.velocity = velocity;
  s.spin = angular_velocity(b.orientation, b.angular_momentum, makeup.moments(b));
  s.mass = makeup.mass(b);
  s.curvature_radius = t.parts.empty() ? t.curvature_radius : t.parts[part].curvature_radius;
  s.volume = t.parts.empty() ? t.unit_mass.volume : t.parts[part].volume;
  return s;
}

}  // namespace gjkdem::dem::detail
