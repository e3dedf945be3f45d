#pragma once
// Shapes and placements for scene generators: random convex polyhedra, the
// five Platonic solids, and the filling of a region with bodies that do not
// overlap each other, the existing bodies or the plane walls.
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

/// A random convex polyhedron: `vertices` points drawn uniformly on a sphere
/// of the given diameter, each axis then scaled by a factor drawn in
/// [0.7, 1] so that the grains are not round. Every point is a hull vertex
/// (for vertices >= 4), so the hull has exactly `vertices` corners.
Shape random_polyhedron(int vertices, Real diameter, std::mt19937_64& rng);

/// A Platonic solid ("tetrahedron", "cube", "octahedron", "dodecahedron",
/// "icosahedron") inscribed in a sphere of the given diameter, centred at the
/// origin. Throws std::invalid_argument for another name.
Shape platonic(const std::string& name, Real diameter);

struct Placement {
  Vec3 position;
  Quat rotation;
};

/// Up to `count` non-overlapping placements for bodies no larger than a
/// sphere of `diameter`, in the box [lo, hi]: cells of that size filled layer
/// by layer from the bottom (lowest z), each with a random orientation and a
/// random offset within the cell's slack, skipping cells whose sphere touches
/// a body already in `world` or lies outside a plane wall. Returns fewer than
/// `count` when the region is too small.
std::vector<Placement> place_in_region(const World& world, const Vec3& lo, const Vec3& hi, Real diameter,
                                       std::size_t count, std::mt19937_64& rng);

}  // namespace gjkdem::dem
