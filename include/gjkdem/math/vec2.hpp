#pragma once
// Small 2-vector for the planar queries.
#include <cmath>

#include "gjkdem/math/real.hpp"

namespace gjkdem {

struct Vec2 {
  Real x = 0, y = 0;
};

constexpr Vec2 operator+(const Vec2& a, const Vec2& b) noexcept { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(const Vec2& a, const Vec2& b) noexcept { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator-(const Vec2& a) noexcept { return {-a.x, -a.y}; }
constexpr Vec2 operator*(const Vec2& a, Real s) noexcept { return {a.x * s, a.y * s}; }
constexpr Vec2 operator*(Real s, const Vec2& a) noexcept { return {a.x * s, a.y * s}; }
constexpr bool operator==(const Vec2& a, const Vec2& b) noexcept { return a.x == b.x && a.y == b.y; }
constexpr Real dot(const Vec2& a, const Vec2& b) noexcept { return a.x * b.x + a.y * b.y; }
/// z-component of the 3D cross product of (a, 0) and (b, 0).
constexpr Real cross(const Vec2& a, const Vec2& b) noexcept { return a.x * b.y - a.y * b.x; }
/// (a x b) x c for planar vectors: the seed's perpendicular construction.
constexpr Vec2 triple_product(const Vec2& a, const Vec2& b, const Vec2& c) noexcept {
  const Real z = cross(a, b);
  return {-z * c.y, z * c.x};
}
inline Real length(const Vec2& a) noexcept { return std::sqrt(dot(a, a)); }

}  // namespace gjkdem
