#pragma once
// When and where a grain breaks (issue 31): its stress from the forces on
// it, the plane it breaks along, and its strength, drawn per grain from a
// Weibull distribution whose scale falls with size (the size effect).
// Conventions and sources: docs/dem.md, "Breakage".
#include <cstdint>
#include <span>

#include "gjkdem/dem/material.hpp"
#include "gjkdem/math/mat3.hpp"
#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

/// The stress in a grain (Pa, compression positive) from the forces on it:
/// -1/V sum over its contacts of (x_c - x_p) (x) f_c, the symmetric part
/// (the Love-Weber average over one grain, as measure.hpp's over a region).
/// `points` and `forces` pair up: where each force acts and the force.
Mat3 grain_stress(const Vec3& centre, Real volume, std::span<const Vec3> points, std::span<const Vec3> forces);

/// Where a stressed grain breaks: the plane through its centre whose normal
/// is its most tensile (least compressed) principal direction, so that the
/// crack holds the direction of the largest compression (a disc squeezed
/// across a diameter splits along it: the Brazilian test). Yade's
/// PolyhedraSplitter (J. Elias, 2013) splits on the stress of the same
/// contact sum; its strength compares with `deviatoric`, the von Mises
/// measure sqrt(((s1-s2)^2 + (s1-s3)^2 + (s2-s3)^2) / 2).
struct BreakPlane {
  Vec3 normal;           ///< unit, world
  Real smallest = 0;     ///< principal stress along the normal (negative: tension), Pa
  Real largest = 0;      ///< the largest principal stress (compression), Pa
  Real deviatoric = 0;   ///< Pa
};
BreakPlane break_plane(const Mat3& stress);

/// The strength (Pa) of a grain of size d (m) whose draw is u in [0, 1):
/// mean / Gamma(1 + 1/m) * (d / d0)^(-3/m) * (-ln(1 - u))^(1/m).
Real grain_strength(const Strength& strength, Real size, Real u);

/// u for a grain, keyed by the run's seed, its id and how many times it (or
/// its parent) broke, so that it does not depend on threads or ranks.
Real strength_draw(std::uint64_t seed, std::uint64_t id, std::uint64_t generation) noexcept;

}  // namespace gjkdem::dem
