#include "gjkdem/dem/round_region.hpp"

#include <cmath>

#include "gjkdem/dem/build_error.hpp"

namespace gjkdem::dem {
namespace {

// Two unit vectors that make a right-handed frame with the unit axis a.
void across(const Vec3& a, Vec3& e1, Vec3& e2) {
  const Vec3 helper = std::fabs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  e1 = normalized(cross(helper, a));
  e2 = cross(a, e1);
}

}  // namespace

void check_round_region(const RoundRegion& g, const std::string& label, bool flat) {
  if (!is_finite(g.base) || !is_finite(g.axis) || !(length(g.axis) > 0))
    throw BuildError(label + ": the region's base and a non-zero axis must be finite");
  const bool height_ok = flat ? g.height >= 0 : g.height > 0;
  if (!(g.radius > 0) || !std::isfinite(g.radius) ||
      (g.kind == RoundRegion::Kind::Cylinder && (!height_ok || !std::isfinite(g.height))))
    throw BuildError(label + ": the region's radius (and a cylinder's height) must be finite and " +
                     (flat ? "> 0 (the height >= 0)" : "> 0"));
}

Aabb round_box(const RoundRegion& g) {
  if (g.kind == RoundRegion::Kind::Ball)
    return {g.base - Vec3{g.radius, g.radius, g.radius}, g.base + Vec3{g.radius, g.radius, g.radius}};
  // A disc of radius r about the unit axis a reaches r sqrt(1 - a_k^2) along axis k.
  const Vec3 a = normalized(g.axis);
  const Vec3 reach{g.radius * std::sqrt(std::fmax(0, 1 - a.x * a.x)), g.radius * std::sqrt(std::fmax(0, 1 - a.y * a.y)),
                   g.radius * std::sqrt(std::fmax(0, 1 - a.z * a.z))};
  const Vec3 top = g.base + a * g.height;
  return {min(g.base, top) - reach, max(g.base, top) + reach};
}

bool ball_inside(const RoundRegion& g, const Vec3& c, Real r) {
  const Vec3 rel = c - g.base;
  if (g.kind == RoundRegion::Kind::Ball) return length(rel) + r <= g.radius;
  const Vec3 a = normalized(g.axis);
  const Real along = dot(rel, a);
  return along >= r && along <= g.height - r && length(rel - a * along) + r <= g.radius;
}

Real distance_to(const RoundRegion& g, const Vec3& p) {
  const Vec3 rel = p - g.base;
  if (g.kind == RoundRegion::Kind::Ball) return std::fmax(length(rel) - g.radius, 0.0);
  const Vec3 a = normalized(g.axis);
  const Real along = dot(rel, a);
  const Real out_radially = std::fmax(length(rel - a * along) - g.radius, 0.0);
  const Real out_along = std::fmax(std::fmax(-along, along - g.height), 0.0);
  return std::hypot(out_radially, out_along);
}

Real depth_in(const RoundRegion& g, const Vec3& p) {
  const Vec3 rel = p - g.base;
  if (g.kind == RoundRegion::Kind::Ball) return g.radius - length(rel);
  const Vec3 a = normalized(g.axis);
  const Real along = dot(rel, a);
  return std::fmin(g.radius - length(rel - a * along), std::fmin(along, g.height - along));
}

Real round_volume(const RoundRegion& g) {
  return g.kind == RoundRegion::Kind::Ball ? 4 * kPi / 3 * g.radius * g.radius * g.radius
                                           : kPi * g.radius * g.radius * g.height;
}

Shape round_shape(const RoundRegion& g) {
  if (g.kind == RoundRegion::Kind::Ball) return make_sphere(g.radius);
  return Shape{Cylinder{g.radius, g.height / 2}};
}

Transform round_pose(const RoundRegion& g) {
  if (g.kind == RoundRegion::Kind::Ball) return Transform::from(g.base, Quat{});
  const Vec3 a = normalized(g.axis);
  Vec3 e1, e2;
  across(a, e1, e2);
  Transform t;
  for (int i = 0; i < 3; ++i) t.rotation.row[i] = {e1[i], e2[i], a[i]};
  t.translation = g.base + a * (g.height / 2);
  return t;
}

Vec3 round_point(const RoundRegion& g, Real u1, Real u2, Real u3) {
  Vec3 a = normalized(g.axis), e1, e2;
  if (g.kind == RoundRegion::Kind::Ball) {
    a = {0, 0, 1};
    const Real z = 1 - 2 * u2, ring = std::sqrt(std::fmax(0, 1 - z * z)), turn = 2 * kPi * u3;
    const Vec3 direction{ring * std::cos(turn), ring * std::sin(turn), z};
    return g.base + direction * (g.radius * std::cbrt(u1));
  }
  across(a, e1, e2);
  const Real r = g.radius * std::sqrt(u1), turn = 2 * kPi * u2;
  return g.base + e1 * (r * std::cos(turn)) + e2 * (r * std::sin(turn)) + a * (g.height * u3);
}

}  // namespace gjkdem::dem
