#pragma once
// Shapes made from a few numbers: random convex polyhedra (scene generators'
// grains) and the five Platonic solids, shapes scaled, and uniformly random
// rotations.
#include <random>
#include <string>

#include "gjkdem/math/quat.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

/// A random convex polyhedron: `vertices` points drawn uniformly on a sphere
/// of the given diameter, each axis then scaled by a factor drawn in
/// [0.7, 1] so that the grains are not round. Every point is a hull vertex
/// (for vertices >= 4), so the hull has exactly `vertices` corners.
Shape random_polyhedron(int vertices, Real diameter, std::mt19937_64& rng);

/// A Platonic solid ("tetrahedron", "cube", "octahedron", "dodecahedron",
/// "icosahedron") inscribed in a sphere of the given diameter, centred at the
/// origin. Throws std::invalid_argument for another name.
Shape platonic(const std::string& name, Real diameter);

/// The shape scaled by `factor` > 0 about its frame's origin (margin too).
Shape scaled(const Shape& shape, Real factor);

/// A box as the polytope of its eight corners.
Polytope box_polytope(const Box& box);

/// A rotation drawn uniformly (a normalised 4D Gaussian).
Quat random_rotation(std::mt19937_64& rng);

}  // namespace gjkdem
