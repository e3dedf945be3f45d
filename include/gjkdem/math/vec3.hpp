#pragma once
// Small 3-vector with value semantics. Kept hand-written (not Eigen) because it
// sits in the innermost loop of every support call and must inline trivially.
#include <cmath>

#include "gjkdem/math/real.hpp"

namespace gjkdem {

struct Vec3 {
  Real x = 0, y = 0, z = 0;

  constexpr Real operator[](int i) const noexcept { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Real& operator[](int i) noexcept { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3& operator+=(const Vec3& o) noexcept { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& o) noexcept { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr Vec3& operator*=(Real s) noexcept { x *= s; y *= s; z *= s; return *this; }
  constexpr Vec3& operator/=(Real s) noexcept { x /= s; y /= s; z /= s; return *this; }
};

constexpr Vec3 operator+(const Vec3& a, const Vec3& b) noexcept { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(const Vec3& a, const Vec3& b) noexcept { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(const Vec3& a) noexcept { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(const Vec3& a, Real s) noexcept { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(Real s, const Vec3& a) noexcept { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator/(const Vec3& a, Real s) noexcept { return {a.x / s, a.y / s, a.z / s}; }
constexpr bool operator==(const Vec3& a, const Vec3& b) noexcept { return a.x == b.x && a.y == b.y && a.z == b.z; }

constexpr Real dot(const Vec3& a, const Vec3& b) noexcept { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// Component-wise product.
inline Vec3 min(const Vec3& a, const Vec3& b) noexcept { return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)}; }
inline Vec3 max(const Vec3& a, const Vec3& b) noexcept { return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)}; }
constexpr Vec3 hadamard(const Vec3& a, const Vec3& b) noexcept { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr Real length_sq(const Vec3& a) noexcept { return dot(a, a); }
inline Real length(const Vec3& a) noexcept { return std::sqrt(dot(a, a)); }
/// Largest absolute component (the infinity norm).
inline Real max_abs(const Vec3& a) noexcept { return std::fmax(std::fabs(a.x), std::fmax(std::fabs(a.y), std::fabs(a.z))); }
/// Unit vector along a; the zero vector stays zero.
inline Vec3 normalized(const Vec3& a) noexcept {
  const Real len = length(a);
  return len > 0 ? a / len : Vec3{};
}
inline bool is_finite(const Vec3& a) noexcept { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

/// Two unit vectors that complete n (unit) to a right-handed orthonormal basis.
inline void orthonormal_basis(const Vec3& n, Vec3& t1, Vec3& t2) noexcept {
  // Pixar's branchless construction (Duff et al. 2017): no cancellation near the poles.
  const Real sign = std::copysign(Real(1), n.z);
  const Real a = Real(-1) / (sign + n.z);
  const Real b = n.x * n.y * a;
  t1 = {1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
  t2 = {b, sign + n.y * n.y * a, -n.y};
}

}  // namespace gjkdem
