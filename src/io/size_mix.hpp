#pragma once
// The bodies a generator or an inflow draws from when the scene gives a
// size distribution: each part (a shape and its fraction) drawn in every
// size class of a sieve table, with the number weight of each variant such
// that the classes get their mass fractions and the parts their number (or
// mass) fractions. No TOML here: the scene reader (scene_reader/) reads
// the tables, this samples. Internal to src/io.
#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::io::detail {

/// A random polyhedron's vertex count and size range (bounding diameter, m).
struct PolyhedronSpec {
  std::int64_t vertices = 12;
  Real size_lo = 0, size_hi = 0;
};

/// One shape of a mix: a random polyhedron, or a shape scaled into the size
/// classes (of bounding size `base_size`).
struct MixPart {
  std::string where;  ///< the scene's table, for messages
  Real fraction = 1;
  std::optional<PolyhedronSpec> polyhedron;
  dem::BodyShape base;
  Real base_size = 0;
};

/// A class of a sieve table: sizes in [lo, hi] (m), its mass fraction.
struct SizeClass {
  Real lo = 0, hi = 0, mass_fraction = 1;
};

struct SampledMix {
  std::vector<dem::BodyShape> variants;
  std::vector<Real> weights;  ///< number probabilities of the variants
};

/// `per_group` variants of each part in each class (`classes` empty: the
/// parts' own sizes, one class), drawn from `rng` part by part, class by
/// class; fractions by mass (`by_mass`) or by number. Throws SceneError for
/// a part whose shape has no volume.
SampledMix sample_mix(std::span<const MixPart> parts, std::span<const SizeClass> classes, std::int64_t per_group,
                      bool by_mass, std::mt19937_64& rng);

}  // namespace gjkdem::io::detail
