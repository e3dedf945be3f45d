#include "gjkdem/dem/break_criterion.hpp"

#include <cmath>
#include <stdexcept>

#include "gjkdem/dem/inflow.hpp"
#include "gjkdem/shape/mass_properties.hpp"

namespace gjkdem::dem {

Mat3 grain_stress(const Vec3& centre, Real volume, std::span<const Vec3> points, std::span<const Vec3> forces) {
  if (points.size() != forces.size()) throw std::invalid_argument("grain_stress: one force per point");
  if (!(volume > 0)) throw std::invalid_argument("grain_stress: the volume must be > 0");
  Mat3 sum{{Vec3{}, Vec3{}, Vec3{}}};
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec3 arm = points[k] - centre;
    for (int i = 0; i < 3; ++i) sum.row[i] += forces[k] * arm[i];
  }
  Mat3 stress;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) stress.row[i][j] = -0.5 * (sum.row[i][j] + sum.row[j][i]) / volume;
  return stress;
}

BreakPlane break_plane(const Mat3& stress) {
  const PrincipalAxes p = principal_axes(stress);  // ascending: x the least compressed
  const Vec3& s = p.moments;
  return {rotate(p.rotation, Vec3{1, 0, 0}), s.x, s.z,
          std::sqrt(((s.x - s.y) * (s.x - s.y) + (s.x - s.z) * (s.x - s.z) + (s.y - s.z) * (s.y - s.z)) / 2)};
}

Real grain_strength(const Strength& s, Real size, Real u) {
  const Real m = s.weibull_modulus;
  const Real scale = s.mean / std::tgamma(1 + 1 / m) * std::pow(size / s.reference_size, -3 / m);
  return scale * std::pow(-std::log1p(-u), 1 / m);
}

Real strength_draw(std::uint64_t seed, std::uint64_t id, std::uint64_t generation) noexcept {
  constexpr std::uint64_t kStrength = 0x5354524e47544831;  // keys these draws apart from the inflows'
  return keyed_uniform(seed, id, generation, kStrength);
}

}  // namespace gjkdem::dem
