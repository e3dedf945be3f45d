#include "gjkdem/dem/material.hpp"

#include <cmath>
#include <map>

#include "gjkdem/dem/contact_law.hpp"

namespace gjkdem::dem {

MaterialTable make_material_table(const std::vector<Material>& materials, ContactModel model) {
  MaterialTable t;
  t.count = static_cast<std::uint32_t>(materials.size());
  t.pairs.resize(materials.size() * materials.size());
  std::map<Real, Real> damping;  // per distinct restitution: each calibration integrates impacts
  for (std::uint32_t i = 0; i < t.count; ++i)
    for (std::uint32_t j = 0; j < t.count; ++j) {
      const Material& a = materials[i];
      const Material& b = materials[j];
      MaterialPair& p = t.pairs[i * t.count + j];
      p.youngs_modulus = effective_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus, b.poisson_ratio);
      p.shear_modulus = effective_shear_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus, b.poisson_ratio);
      p.friction = std::sqrt(a.friction * b.friction);
      p.rolling_friction = std::sqrt(a.rolling_friction * b.rolling_friction);
      p.rolling_damping = (a.rolling_damping + b.rolling_damping) / 2;
      // The product of square roots: e = 1e-162 on both sides must not underflow to 0.
      p.restitution = std::sqrt(a.restitution) * std::sqrt(b.restitution);
      const auto [it, inserted] = damping.try_emplace(p.restitution, 0);
      if (inserted)
        it->second = model == ContactModel::Hertz ? hertz_damping_for_restitution(p.restitution)
                                                  : linear_damping_ratio_for_restitution(p.restitution);
      p.damping = it->second;
    }
  return t;
}

}  // namespace gjkdem::dem
