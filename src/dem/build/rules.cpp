// The rules of a world's values, written once (world_builder.hpp): materials,
// contact settings, the periodic cell, the settings, a fill's count. The scene
// reader and Python call them too, so each refusal names the same key.
#include "gjkdem/dem/world_builder.hpp"

#include <cmath>
#include <string>

namespace gjkdem::dem {

namespace {

// A field's rule: throws BuildError(subject, key, rule) unless `ok`.
void need(bool ok, const std::string& subject, const std::string& key, const std::string& rule) {
  if (!ok) throw BuildError(subject, key, rule);
}

}  // namespace

void check_material(const Material& m) {
  const std::string who = "material '" + m.name + "'";
  for (const auto& [key, v] : {std::pair{"density", m.density}, {"youngs_modulus", m.youngs_modulus},
                               {"poisson_ratio", m.poisson_ratio}, {"restitution", m.restitution},
                               {"friction", m.friction}, {"rolling_friction", m.rolling_friction},
                               {"rolling_damping", m.rolling_damping}})
    need(std::isfinite(v), who, key, "must be finite");
  need(m.density > 0, who, "density", "must be > 0");
  need(m.youngs_modulus > 0, who, "youngs_modulus", "must be > 0");
  need(m.poisson_ratio > -1 && m.poisson_ratio < 0.5, who, "poisson_ratio", "must lie in (-1, 0.5)");
  need(m.restitution > 0 && m.restitution <= 1, who, "restitution", "must lie in (0, 1]");
  need(m.friction >= 0, who, "friction", "must be >= 0");
  need(m.rolling_friction >= 0, who, "rolling_friction", "must be >= 0");
  need(m.rolling_damping >= 0 && m.rolling_damping <= 1, who, "rolling_damping", "must lie in [0, 1]");
  // Breakage (docs/breakage.md), by the scene's keys.
  const Strength& s = m.strength;
  need(std::isfinite(s.mean) && s.mean >= 0, who, "strength", "must be finite and >= 0 (Pa; 0: never breaks)");
  need(std::isfinite(s.weibull_modulus) && s.weibull_modulus > 0, who, "weibull_modulus", "must be finite and > 0");
  need(std::isfinite(s.reference_size) && s.reference_size >= 0, who, "strength_size", "must be finite and > 0 (m)");
  need(std::isfinite(s.smallest) && s.smallest >= 0, who, "unbreakable_below", "must be finite and > 0 (m)");
  if (s.mean > 0) {
    need(s.reference_size > 0, who, "strength_size",
         "must be given, > 0 (m): the size whose grains' mean strength is `strength`");
    need(s.smallest > 0, who, "unbreakable_below",
         "must be given, > 0 (m): grains smaller than this no longer break, which ends the cascade");
  }
  const Glue& g = m.glue;
  for (const auto& [key, v] : {std::pair{"bond_tensile_strength", g.tensile_strength},
                               {"bond_shear_strength", g.shear_strength},
                               {"bond_moment_strength", g.moment_strength},
                               {"bond_normal_stiffness", g.normal_stiffness},
                               {"bond_shear_stiffness", g.shear_stiffness}})
    need(std::isfinite(v) && v >= 0, who, key, "must be finite and >= 0");
  need(std::isfinite(g.damping) && g.damping >= 0 && g.damping <= 1, who, "bond_damping", "must lie in [0, 1]");
  if (g.tensile_strength > 0)
    need(g.shear_strength > 0, who, "bond_shear_strength",
         "must be given, > 0 (Pa), with a bond_tensile_strength");
}

void check_contact_settings(const WorldSettings& s) {
  const std::string who = "settings";
  need(std::isfinite(s.linear_stiffness) && s.linear_stiffness >= 0, who, "linear_stiffness",
       "must be finite and >= 0 (N/m; 0: from the materials)");
  need(std::isfinite(s.volume_stiffness) && s.volume_stiffness >= 0, who, "volume_stiffness",
       "must be finite and >= 0 (N/m^3; 0: from the materials)");
  need(s.tessellation >= kMinTessellation && s.tessellation <= kMaxTessellation, who, "tessellation",
       "must be between " + std::to_string(kMinTessellation) + " and " + std::to_string(kMaxTessellation) +
           " directions");
  need(std::isfinite(s.box_skin) && s.box_skin >= 0, who, "box_skin", "must be finite and >= 0");
}

void check_cell(const PeriodicCell& cell, const CellControl& control) {
  const std::string who = "periodic cell";
  const char* names[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (!cell.axes[a]) continue;
    need(std::isfinite(cell.lo[a]) && std::isfinite(cell.hi[a]) && cell.hi[a] > cell.lo[a], who, names[a],
         "must be [min, max] with max > min (finite)");
    need(std::fabs(cell.lo[a]) <= kMaxCoordinate && std::fabs(cell.hi[a]) <= kMaxCoordinate, who, names[a],
         "must lie within [-1e100, 1e100] m");
  }
  need(cell.tilt == Vec3{}, who, "tilt", "must be zero: a periodic cell starts unsheared");
  for (int k = 0; k < 6; ++k) {
    if (control.mode[k] == CellMode::Fixed) continue;
    const std::string key =
        std::string(control.mode[k] == CellMode::Stress ? "stress." : "strain_rate.") + kCellComponents[k];
    // A component deforms the cell along its first axis with the position on its second.
    const int along = k < 3 ? k : k == kYZ ? 1 : 0, across = k < 3 ? k : k == kXY ? 1 : 2;
    if (!cell.axes[along] || !cell.axes[across])
      throw BuildError(who, key, std::string("the cell is not periodic on ") + names[cell.axes[along] ? across : along]);
    need(std::isfinite(control.value[k]), who, key, "must be finite");
    if (control.mode[k] == CellMode::Stress && k < 3)
      need(control.value[k] > 0, who, key, "must be > 0 (Pa, compression positive)");
  }
  if (!control.servo()) {
    need(control.max_strain_rate == 0, who, "max_strain_rate",
         "bounds the servo of a cell driven to a stress: give stress too");
    return;
  }
  need(cell.axes[0] && cell.axes[1] && cell.axes[2], who, "stress",
       "needs a cell periodic on x, y and z (the stress is the contacts' over the cell's volume)");
  need(control.max_strain_rate != 0, who, "stress", "needs max_strain_rate too (1/s): the servo's largest strain rate");
  need(control.max_strain_rate > 0 && std::isfinite(control.max_strain_rate), who, "max_strain_rate",
       "must be finite and > 0 (1/s)");
  bool normal = false;
  for (int a = 0; a < 3; ++a) normal = normal || control.mode[a] == CellMode::Stress;
  need(normal, who, "stress", "needs a normal stress (x, y or z) besides shear ones: its size scales the servo");
}

void check_settings(const WorldSettings& s) {
  const std::string who = "settings";
  need(is_finite(s.gravity), who, "gravity", "must be finite");
  need(s.threads >= 0 && s.threads <= kMaxThreads, who, "threads",
       "must be 0 (all cores) or a thread count up to " + std::to_string(kMaxThreads));
  check_contact_settings(s);
  try {
    check_cell(s.periodic, s.cell_control);
  } catch (const BuildError& e) {  // named as the scene nests it: [simulation.periodic]
    throw BuildError(who, "periodic." + e.key, e.rule);
  }
}

void check_fill_count(std::int64_t count) {
  need(count > 0 && static_cast<std::uint64_t>(count) <= kMaxFillCount, "region", "count",
       "must be a positive integer up to " + std::to_string(kMaxFillCount));
}

}  // namespace gjkdem::dem
