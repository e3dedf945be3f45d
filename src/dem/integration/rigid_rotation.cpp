#include "gjkdem/dem/rigid_rotation.hpp"

#include <cmath>

namespace gjkdem::dem {

namespace {

// sin and cos of x: Taylor series to full double precision for |x| < 0.25
// (the half angles of a time step are far smaller, typically 1e-4), libm
// beyond. Below 1e-3 the terms past x^5 are under 1e-22 relative.
void sin_cos(Real x, Real& s, Real& c) noexcept {
  const Real x2 = x * x;
  constexpr Real f3 = 1.0 / 6, f5 = f3 / 20, f7 = f5 / 42, f9 = f7 / 72, f11 = f9 / 110, f13 = f11 / 156,
                 f15 = f13 / 210;
  constexpr Real f2 = 1.0 / 2, f4 = f2 / 12, f6 = f4 / 30, f8 = f6 / 56, f10 = f8 / 90, f12 = f10 / 132,
                 f14 = f12 / 182, f16 = f14 / 240;
  if (x2 < 1e-6) {
    s = x * (1 - x2 * (f3 - x2 * f5));
    c = 1 - x2 * (f2 - x2 * (f4 - x2 * f6));
  } else if (x2 < 0.0625) {  // the next terms are below 0.25^17 / 17! ~ 5e-25
    s = x * (1 - x2 * (f3 - x2 * (f5 - x2 * (f7 - x2 * (f9 - x2 * (f11 - x2 * (f13 - x2 * f15)))))));
    c = 1 - x2 * (f2 - x2 * (f4 - x2 * (f6 - x2 * (f8 - x2 * (f10 - x2 * (f12 - x2 * (f14 - x2 * f16)))))));
  } else {
    s = std::sin(x);
    c = std::cos(x);
  }
}

}  // namespace

// The body-frame angular momentum pi is carried along: a turn of the body by
// theta about its axis i turns pi by -theta about that axis (two components
// change), so the matrix of q is made once, not once per sub-rotation.
void rotate_free(Quat& q, const Vec3& l_world, const Vec3& moments, Real dt) noexcept {
  Vec3 pi = transpose_mul(to_matrix(q), l_world);
  const Vec3 rate{dt / moments.x, dt / moments.y, dt / moments.z};  // angle per unit of pi over dt
  auto sub = [&](int i, Real fraction) {
    const Real angle = fraction * rate[i] * pi[i];
    if (angle == 0) return;
    Real s, c;
    sin_cos(angle / 2, s, c);
    // q * (c + s e_i), written out: the product with a turn about one axis.
    const Quat a = q;
    if (i == 0) q = {a.w * c - a.x * s, a.x * c + a.w * s, a.y * c + a.z * s, a.z * c - a.y * s};
    else if (i == 1) q = {a.w * c - a.y * s, a.x * c - a.z * s, a.y * c + a.w * s, a.z * c + a.x * s};
    else q = {a.w * c - a.z * s, a.x * c + a.y * s, a.y * c - a.x * s, a.z * c + a.w * s};
    const Real cos_full = c * c - s * s, sin_full = 2 * s * c;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const Real pj = pi[j], pk = pi[k];
    pi[j] = cos_full * pj + sin_full * pk;
    pi[k] = cos_full * pk - sin_full * pj;
  };
  sub(0, 0.5);
  sub(1, 0.5);
  sub(2, 1);
  sub(1, 0.5);
  sub(0, 0.5);
  const Real inverse_norm = 1 / std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  q = {q.w * inverse_norm, q.x * inverse_norm, q.y * inverse_norm, q.z * inverse_norm};
}

Vec3 angular_velocity(const Quat& q, const Vec3& l_world, const Vec3& moments) noexcept {
  const Mat3 r = to_matrix(q);
  const Vec3 pi = transpose_mul(r, l_world);
  return r * Vec3{pi.x / moments.x, pi.y / moments.y, pi.z / moments.z};
}

Real rotational_energy(const Quat& q, const Vec3& l_world, const Vec3& moments) noexcept {
  return dot(angular_velocity(q, l_world, moments), l_world) / 2;
}

}  // namespace gjkdem::dem
