#pragma once
// Materials, and the table of what every pair of them gives a contact:
// effective moduli, friction, restitution and the calibrated damping of the
// world's contact law. The table is filled once when a world is built, so a
// contact reads its pair's values with one index, never a map lookup.
#include <cstdint>
#include <string>
#include <vector>

#include "gjkdem/math/real.hpp"

namespace gjkdem::dem {

/// A material's strength (docs/breakage.md): a grain of it breaks when the
/// stress of its contacts reaches its own strength, drawn from a Weibull
/// distribution of modulus m whose mean is `mean` for grains of
/// `reference_size` (m, the diameter of the sphere of equal volume); for a
/// grain of size d the scale is multiplied by (d / reference_size)^(-3/m),
/// the weakest-link size effect (a grain of twice the volume holds twice the
/// flaws). Grains smaller than `smallest` never break, which ends the
/// cascade.
struct Strength {
  Real mean = 0;                ///< Pa at the reference size; 0: the grains never break
  Real weibull_modulus = 3;     ///< m > 0
  Real reference_size = 0;      ///< m, > 0 where mean > 0
  Real smallest = 0;            ///< m, > 0 where mean > 0: grains smaller do not break
  std::uint64_t seed = 1;       ///< keys the draws (with each grain's id and generation)
};

/// The glue of bonded assemblies made of a material (bonds.hpp,
/// docs/breakage.md): a bond between two pieces is a face of area A that
/// resists their relative motion with springs per unit area, and breaks for
/// good when the tensile or shear stress at the face's rim reaches its
/// strength. A material without a tensile strength makes no bonds.
struct Glue {
  Real tensile_strength = 0;  ///< Pa, >= 0; 0: no bonds
  Real shear_strength = 0;    ///< Pa, > 0 where tensile_strength > 0
  /// Pa, >= 0: the strength against the moments alone, a glue weaker in
  /// bending or twisting than the beam stresses say (the bending stress
  /// |M_b| R / I or the twisting stress |M_t| R / J at the rim reaches it).
  /// 0: none; the moments still count in the tension and shear at the rim.
  Real moment_strength = 0;
  /// Normal stiffness per unit area (Pa/m), >= 0; 0: E / l, with l the
  /// distance between the two pieces' centres (a bar of the material
  /// spanning them).
  Real normal_stiffness = 0;
  /// Shear stiffness per unit area (Pa/m), >= 0; 0: the normal one over
  /// 2 (1 + nu) (the ratio of the shear to Young's modulus).
  Real shear_stiffness = 0;
  /// Damping ratio of the bond's springs against the pair's reduced mass
  /// and moment of inertia, in [0, 1].
  Real damping = 0.1;
};

struct Material {
  std::string name;
  Real density = 2500;          ///< kg/m^3, > 0
  Real youngs_modulus = 1e7;    ///< Pa, > 0
  Real poisson_ratio = 0.25;    ///< in (-1, 0.5)
  Real restitution = 0.5;       ///< normal coefficient of restitution, (0, 1]
  Real friction = 0.5;          ///< Coulomb coefficient, >= 0
  /// Rolling resistance (Ai et al. 2011's elastic-plastic model, type C):
  /// the contact resists relative rolling with a moment of at most
  /// mu_r R* F_n. Dimensionless, >= 0; 0 lets round grains roll forever.
  Real rolling_friction = 0;
  /// Damping ratio of the rolling spring below its limit, in [0, 1]
  /// (Ai et al.'s eta_r; 0.3 is their suggestion).
  Real rolling_damping = 0.3;
  /// Breakage (docs/breakage.md); by default the grains never break.
  Strength strength{};
  /// Bonded assemblies (docs/breakage.md); by default no bonds.
  Glue glue{};
};

/// The contact law between bodies (docs/dem.md).
/// - Hertz: damped Hertz on the penetration depth (GJK/EPA), Mindlin's
///   tangential stiffness;
/// - Linear: a linear spring-dashpot on the penetration depth;
/// - Volume: k V from the overlap region (the seed's contact model).
enum class ContactModel { Hertz, Linear, Volume };

/// What a pair of materials gives a contact (symmetric in the two).
struct MaterialPair {
  Real youngs_modulus = 0;  ///< E* (Pa)
  Real shear_modulus = 0;   ///< Mindlin's G* (Pa)
  Real friction = 0;        ///< sqrt(mu_a mu_b)
  Real restitution = 0;     ///< sqrt(e_a e_b)
  Real rolling_friction = 0;  ///< sqrt(mu_r,a mu_r,b)
  Real rolling_damping = 0;   ///< (eta_a + eta_b) / 2
  /// The law's calibrated damping for that restitution: beta for Hertz,
  /// the damping ratio zeta for the linear and volume laws.
  Real damping = 0;
};

/// Every pair of a world's materials, row-major: pair (i, j) at i * count + j.
struct MaterialTable {
  std::uint32_t count = 0;
  std::vector<MaterialPair> pairs;

  const MaterialPair& operator()(std::uint32_t a, std::uint32_t b) const noexcept { return pairs[a * count + b]; }
};

/// The table for `materials` under `model` (calibrates the damping of each
/// distinct restitution once).
MaterialTable make_material_table(const std::vector<Material>& materials, ContactModel model);

}  // namespace gjkdem::dem
