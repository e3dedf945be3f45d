#pragma once
// Rigid transform: x_world = rotation * x_local + translation.
#include "gjkdem/math/quat.hpp"

namespace gjkdem {

struct Transform {
  Mat3 rotation;     ///< orthonormal, det +1
  Vec3 translation;  ///< origin of the local frame, in the parent frame

  static constexpr Transform identity() noexcept { return {}; }
  static constexpr Transform from(const Vec3& position, const Quat& q) noexcept { return {to_matrix(q), position}; }
};

constexpr Vec3 apply(const Transform& t, const Vec3& p) noexcept { return t.rotation * p + t.translation; }
constexpr Vec3 apply_rotation(const Transform& t, const Vec3& d) noexcept { return t.rotation * d; }
/// Inverse transform of a point: rotation^T (p - translation).
constexpr Vec3 apply_inverse(const Transform& t, const Vec3& p) noexcept {
  return transpose_mul(t.rotation, p - t.translation);
}
constexpr Vec3 apply_inverse_rotation(const Transform& t, const Vec3& d) noexcept {
  return transpose_mul(t.rotation, d);
}
/// A frame placed in `parent`'s frame, placed in the world: parent * child.
constexpr Transform compose(const Transform& parent, const Transform& child) noexcept {
  return {parent.rotation * child.rotation, apply(parent, child.translation)};
}

/// The transform taking b's local coordinates into a's local frame: a^-1 * b.
constexpr Transform relative(const Transform& a, const Transform& b) noexcept {
  return {transpose(a.rotation) * b.rotation, apply_inverse(a, b.translation)};
}

}  // namespace gjkdem
