#pragma once
// A convex polytope cut by a plane: the two convex pieces a grain breaks into
// (issue 31, breakage). Each piece is the hull of its side's vertices and the
// points where the polytope's edges cross the plane, so the pieces share the
// cut polygon and their volumes, first and second moments add up to the
// polytope's to round-off (tests/shape/split_test.cpp).
#include <optional>

#include "gjkdem/math/vec3.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem {

/// The pieces of a polytope on either side of the plane dot(normal, x) =
/// offset (in the polytope's frame; normal need not be unit). `below` holds
/// dot(normal, x) <= offset. A side without volume (the plane misses the
/// polytope, touches it, or cuts off a piece flatter than the hull's
/// tolerance) is empty, and then the other side is the polytope itself.
struct PolytopeSplit {
  std::optional<Polytope> below, above;
};

/// Throws std::invalid_argument for a zero or non-finite normal or a
/// non-finite offset, or a polytope without volume.
PolytopeSplit split_polytope(const Polytope& polytope, const Vec3& normal, Real offset);

/// split_polytope(...).below without the piece above made (only its hull,
/// to tell a sliver from a cut): the cells of voronoi_cells, cut again and
/// again, keep one side. A sliver above is pressed onto the plane (its
/// corners projected), so that the result never pokes above it.
std::optional<Polytope> polytope_below(const Polytope& polytope, const Vec3& normal, Real offset);

}  // namespace gjkdem
