#pragma once
// Unit quaternion [w, x, y, z] for rotations (the order of the query and scene formats).
#include "gjkdem/math/mat3.hpp"

namespace gjkdem {

struct Quat {
  Real w = 1, x = 0, y = 0, z = 0;
};

constexpr Quat operator*(const Quat& a, const Quat& b) noexcept {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
constexpr Quat conjugate(const Quat& q) noexcept { return {q.w, -q.x, -q.y, -q.z}; }
inline Real norm(const Quat& q) noexcept { return std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z); }
inline Quat normalized(const Quat& q) noexcept {
  const Real n = norm(q);
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}
/// Rotation of angle (rad) about a unit axis.
inline Quat quat_from_axis_angle(const Vec3& axis, Real angle) noexcept {
  const Real s = std::sin(angle / 2);
  return {std::cos(angle / 2), axis.x * s, axis.y * s, axis.z * s};
}
/// Rotation matrix of a unit quaternion.
constexpr Mat3 to_matrix(const Quat& q) noexcept {
  const Real xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  const Real xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  const Real wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  return {{{1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy)},
           {2 * (xy + wz), 1 - 2 * (xx + zz), 2 * (yz - wx)},
           {2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy)}}};
}
inline Vec3 rotate(const Quat& q, const Vec3& v) noexcept { return to_matrix(q) * v; }
/// Unit quaternion of a rotation matrix (Shepperd: from the largest of the
/// four diagonal combinations, so no division by a small number).
inline Quat quat_from_matrix(const Mat3& m) noexcept {
  const Real t = m.row[0].x + m.row[1].y + m.row[2].z;
  Quat q;
  if (t >= m.row[0].x && t >= m.row[1].y && t >= m.row[2].z) {
    const Real s = std::sqrt(1 + t) * 2;
    q = {s / 4, (m.row[2].y - m.row[1].z) / s, (m.row[0].z - m.row[2].x) / s, (m.row[1].x - m.row[0].y) / s};
  } else if (m.row[0].x >= m.row[1].y && m.row[0].x >= m.row[2].z) {
    const Real s = std::sqrt(1 + m.row[0].x - m.row[1].y - m.row[2].z) * 2;
    q = {(m.row[2].y - m.row[1].z) / s, s / 4, (m.row[0].y + m.row[1].x) / s, (m.row[0].z + m.row[2].x) / s};
  } else if (m.row[1].y >= m.row[2].z) {
    const Real s = std::sqrt(1 + m.row[1].y - m.row[0].x - m.row[2].z) * 2;
    q = {(m.row[0].z - m.row[2].x) / s, (m.row[0].y + m.row[1].x) / s, s / 4, (m.row[1].z + m.row[2].y) / s};
  } else {
    const Real s = std::sqrt(1 + m.row[2].z - m.row[0].x - m.row[1].y) * 2;
    q = {(m.row[1].x - m.row[0].y) / s, (m.row[0].z + m.row[2].x) / s, (m.row[1].z + m.row[2].y) / s, s / 4};
  }
  return normalized(q);
}

}  // namespace gjkdem
