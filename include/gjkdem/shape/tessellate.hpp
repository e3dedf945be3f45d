#pragma once
// Polytope approximation of any convex shape (curved cores, margins) from its
// support function, with a certified error bound.
#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

struct Tessellation {
  Polytope polytope;  ///< inscribed (its vertices lie on the shape), local frame
  /// Certified bound: max over the polytope's facets of h_shape(n) - offset.
  /// The shape lies between the polytope and the polytope with every facet
  /// pushed out by this distance, so a volume computed on the polytope is a
  /// lower bound that errs by about (surface area) * bound at most.
  Real hausdorff_bound = 0;
};

/// Hull of the support points in `directions` directions (a Fibonacci sphere,
/// plus the six axes). More directions: a tighter bound, about 1/directions
/// relative for smooth shapes; flat faces and edges are reproduced exactly.
Tessellation tessellate(const Shape& shape, int directions);

}  // namespace gjkdem
