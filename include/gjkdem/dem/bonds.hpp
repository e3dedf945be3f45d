#pragma once
// Bonds of bonded assemblies (issue 31; docs/breakage.md): two bodies glued
// at a face they share, as the pieces of a rock cut into Voronoi cells
// (shape/voronoi.hpp). A bond is a parallel bond of the face (Potyondy and
// Cundall 2004): springs per unit area resist the opening, sliding, bending
// and twisting of the face from where it was glued, and the face breaks for
// good when the tensile or shear stress at its rim reaches the glue's
// strength. While a bond holds, its bodies' contact is not computed (the
// bond carries their load, in compression too); once broken, they touch as
// any two grains do, their contact starting without springs.
//
// Elastic forces come from the total displacement since gluing (no history
// but the bodies' poses), so a bond's energy is a function of the state and
// counts in the energy balance with the contacts' (World::stats); a bond
// that breaks gives its energy up, which the balance counts as dissipated.
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "gjkdem/dem/body.hpp"

namespace gjkdem::dem {

struct Bond {
  std::uint64_t a = 0, b = 0;  ///< the bodies' ids, a < b
  Vec3 point_a, point_b;       ///< the face's centroid in a's and b's principal frames (m)
  Vec3 normal_a, normal_b;     ///< the face's unit normal, from a towards b, in a's and b's principal frames
  Quat rest;                   ///< b's orientation seen from a's when glued: conj(q_a) q_b
  Real area = 0;               ///< of the face (m^2)
  Real polar_moment = 0;       ///< of the face about its centroid (m^4)
  Real normal_stiffness = 0;   ///< per unit area (Pa/m)
  Real shear_stiffness = 0;    ///< per unit area (Pa/m)
  Real tensile_strength = 0;   ///< Pa
  Real shear_strength = 0;     ///< Pa
  Real moment_strength = 0;    ///< Pa, of the moments alone (Glue::moment_strength); 0: none
  Real damping = 0;            ///< ratio of the critical damping of each spring
  std::uint8_t intact = 1;     ///< 0: broken, for good
  Real broken_time = 0;        ///< when it broke (s)
};
static_assert(std::is_trivially_copyable_v<Bond>);

/// The bond gluing bodies a and b (a.id < b.id, both moving, of materials
/// with a glue) at a face of their current poses: its centroid and unit
/// normal from a towards b (world), area (m^2) and polar moment (m^4). The
/// stiffnesses and strengths come from the glue of a's material (Glue's
/// defaults from its Young's modulus and Poisson ratio).
Bond glue_bodies(const Body& a, const Body& b, const Material& material, const Vec3& centroid, const Vec3& normal,
                 Real area, Real polar_moment);

/// What a bond does now: its force on b at the face's centre (a takes the
/// opposite) and its torque on b about the world origin, the energy its
/// springs hold, and the stresses at its rim that break it.
struct BondLoad {
  Vec3 force, torque;
  Real elastic = 0;  ///< J
  Real tension = 0;  ///< normal stress at the rim (Pa), tension positive
  Real shear = 0;    ///< shear stress at the rim (Pa)
  Real moment = 0;   ///< the larger of the moments' own stresses at the rim, bending and twisting (Pa)
};

/// The face's equivalent radius: the disc's of the same area and polar
/// moment, sqrt(2 J / A) (m), where the rim stresses are taken.
Real bond_radius(const Bond& bond) noexcept;

/// The load of a bond between bodies a and b (by the bond's ids) of the
/// world's makeup.
BondLoad bond_load(const Bond& bond, const Body& a, const Body& b, const Makeup& makeup) noexcept;

/// Whether the bond breaks under `load`: its tension or shear at the rim
/// reaches its strength, or its moments' stress the moment strength.
bool bond_breaks(const Bond& bond, const BondLoad& load) noexcept;

/// Whether bodies of ids lo < hi are held by an intact bond (`bonds` sorted
/// by ids).
bool bonded(std::span<const Bond> bonds, std::uint64_t lo, std::uint64_t hi) noexcept;

/// The ids of the bodies that an intact bond holds, sorted (with repeats).
std::vector<std::uint64_t> held_bodies(std::span<const Bond> bonds);

/// Whether any of `bonds` still holds.
bool any_intact(std::span<const Bond> bonds) noexcept;

/// How many of `bonds` have broken.
std::size_t broken_bonds(std::span<const Bond> bonds) noexcept;

/// What the bonds did in a force evaluation.
struct BondSums {
  Real elastic = 0;  ///< J, in the intact bonds
  int broke = 0;     ///< bonds that broke in it
};

/// Adds every intact bond's load to its bodies, in the order of `bonds`
/// (sorted by ids: the same bits for any thread count); a bond whose
/// stress reached its strength breaks at `time` and adds nothing. A bond
/// whose bodies are not both in `bodies` (a domain's) is skipped. Each
/// bond's energy goes to `energies` (one per bond; 0 for those broken or
/// skipped), from which a domain run sums the whole world's in bond order.
BondSums add_bond_forces(std::span<Bond> bonds, std::span<Body> bodies, const Makeup& makeup, Real time,
                         std::span<Real> energies);

/// The shortest time step the bonds allow (s): the period of the stiffest
/// spring of each bond against its bodies' reduced mass or moment of
/// inertia, over 20 (the contacts' rule, world.hpp); infinite without
/// bonds.
Real bond_time_step(std::span<const Bond> bonds, std::span<const Body> bodies, const Makeup& makeup) noexcept;

}  // namespace gjkdem::dem
