#include "gjkdem/dem/rigid_rotation.hpp"

namespace gjkdem {

void rotate_free(Quat& q, const Vec3& l_world, const Vec3& moments, Real dt) noexcept {
  auto sub = [&](int axis, Real t) {
    const Vec3 pi = transpose_mul(to_matrix(q), l_world);  // body-frame angular momentum
    Vec3 e;
    e[axis] = 1;
    q = normalized(q * quat_from_axis_angle(e, t * pi[axis] / moments[axis]));
  };
  sub(0, dt / 2);
  sub(1, dt / 2);
  sub(2, dt);
  sub(1, dt / 2);
  sub(0, dt / 2);
}

Vec3 angular_velocity(const Quat& q, const Vec3& l_world, const Vec3& moments) noexcept {
  const Mat3 r = to_matrix(q);
  const Vec3 pi = transpose_mul(r, l_world);
  return r * Vec3{pi.x / moments.x, pi.y / moments.y, pi.z / moments.z};
}

Real rotational_energy(const Quat& q, const Vec3& l_world, const Vec3& moments) noexcept {
  return dot(angular_velocity(q, l_world, moments), l_world) / 2;
}

}  // namespace gjkdem
