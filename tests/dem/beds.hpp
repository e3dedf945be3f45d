#pragma once
// Beds of random polyhedra for tests: `count` grains sharing `variants`
// shapes of `vertices` corners and `size` across, placed without overlap in
// [lo, hi] (WorldBuilder::fill_region), drawn from `rng`.
#include <random>

#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::dem::test {

struct PolyhedraBed {
  std::size_t count = 0;
  int variants = 5, vertices = 10;
  Real size = 0.01;
  Vec3 lo, hi;
  std::uint32_t material = 0;
};

inline void fill_polyhedra(WorldBuilder& b, const PolyhedraBed& bed, std::mt19937_64& rng) {
  RegionFill fill;
  for (int k = 0; k < bed.variants; ++k) fill.variants.push_back({random_polyhedron(bed.vertices, bed.size, rng), {}});
  fill.count = bed.count;
  fill.lo = bed.lo;
  fill.hi = bed.hi;
  fill.material = bed.material;
  b.fill_region(fill, rng);
}

}  // namespace gjkdem::dem::test
