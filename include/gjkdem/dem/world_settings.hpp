#pragma once
// The settings of a world: fixed when it is built (WorldBuilder, whose
// check_settings holds their rules), read by every step. Plain data with the
// defaults of a scene file, but threads: a scene's default is 0 (every
// core), a world's 1.
#include <optional>
#include <string_view>

#include "gjkdem/dem/material.hpp"
#include "gjkdem/dem/periodic.hpp"
#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

/// The volume law between two bodies (plane walls always use k V, which is
/// conservative there, see half_space.hpp):
/// - Normalized: F = k V along the unit normal S_A / |S_A| (issue 4's F = k V;
///   a potential force only while |S_A| stays constant, as in flat contacts);
/// - Potential: F = (k / A_ref) V S_A, the gradient of U = k V^2 / (2 A_ref),
///   so collisions keep their energy exactly up to the integrator. A_ref is
///   the smaller moving body's volume to the power 2/3 (a cube's face: a cube
///   lying flat on a larger body feels k V under both forms).
enum class VolumeForm { Normalized, Potential };

/// The names scenes and Python give the laws and the volume forms.
inline constexpr const char* name_of(ContactModel m) noexcept {
  return m == ContactModel::Hertz ? "hertz" : m == ContactModel::Linear ? "linear" : "volume";
}
inline constexpr const char* name_of(VolumeForm f) noexcept {
  return f == VolumeForm::Potential ? "potential" : "normalized";
}
/// The law or form of that name; none for another name.
inline std::optional<ContactModel> contact_model_named(std::string_view name) noexcept {
  for (const ContactModel m : {ContactModel::Volume, ContactModel::Hertz, ContactModel::Linear})
    if (name == name_of(m)) return m;
  return std::nullopt;
}
inline std::optional<VolumeForm> volume_form_named(std::string_view name) noexcept {
  for (const VolumeForm f : {VolumeForm::Normalized, VolumeForm::Potential})
    if (name == name_of(f)) return f;
  return std::nullopt;
}
/// What a message says the names are.
inline constexpr const char* kContactModelNames = "\"volume\", \"hertz\" or \"linear\"";
inline constexpr const char* kVolumeFormNames = "\"normalized\" or \"potential\"";

struct WorldSettings {
  ContactModel model = ContactModel::Volume;
  Vec3 gravity{0, 0, -9.81};     ///< m/s^2
  /// Stiffness of the linear law (N/m) and of the volume law (N/m^3); 0 takes
  /// them from the materials per pair: E* R* and E* / R* (docs/dem.md).
  Real linear_stiffness = 0;
  Real volume_stiffness = 0;
  VolumeForm volume_form = VolumeForm::Normalized;
  /// Volume law between bodies: the contact area resists relative rocking
  /// (contact_force.cpp); without it two flat faces rock freely about the
  /// middle of their contact and stacks topple. Off, collisions under the
  /// potential form keep their energy exactly.
  bool rocking_resistance = true;
  /// Volume law: curved shapes (spheres, ellipsoids, cylinders, cones,
  /// superellipsoids, rounded shapes) are clipped as inscribed polytopes of
  /// this many support directions; their mass properties stay exact.
  int tessellation = 96;
  /// Boxes of moving bodies are enlarged by this fraction of the body's reach
  /// and recomputed only when the body may have left its box (boxes.hpp).
  Real box_skin = 0.05;
  int threads = 1;               ///< OpenMP threads for a step (0: all cores)
  PeriodicCell periodic;         ///< periodic boundaries (periodic.hpp), the cell at the start; none by default
  CellControl cell_control;      ///< how the periodic cell deforms (periodic.hpp); it does not by default
};

}  // namespace gjkdem::dem
