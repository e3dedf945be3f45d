#pragma once
// 3x3 matrix stored by rows; used for rotations and inertia tensors.
#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct Mat3 {
  Vec3 row[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  static constexpr Mat3 identity() noexcept { return {}; }
  constexpr Vec3 column(int j) const noexcept { return {row[0][j], row[1][j], row[2][j]}; }
};

constexpr Vec3 operator*(const Mat3& m, const Vec3& v) noexcept {
  return {dot(m.row[0], v), dot(m.row[1], v), dot(m.row[2], v)};
}
/// m^T v without forming the transpose.
constexpr Vec3 transpose_mul(const Mat3& m, const Vec3& v) noexcept {
  return m.row[0] * v.x + m.row[1] * v.y + m.row[2] * v.z;
}
constexpr Mat3 transpose(const Mat3& m) noexcept {
  return {{m.column(0), m.column(1), m.column(2)}};
}
constexpr Mat3 operator*(const Mat3& a, const Mat3& b) noexcept {
  Mat3 r;
  for (int i = 0; i < 3; ++i) r.row[i] = transpose_mul(b, a.row[i]);
  return r;
}

}  // namespace gjkdem
