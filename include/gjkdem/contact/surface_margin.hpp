#pragma once
// A closed surface (shape/surface.hpp) against triangles with a margin (each
// triangle's Minkowski sum with a ball of its radius rho: the pieces of an
// open surface, a mesh wall, as the seed's triangle-pair query sees them).
// Every pair of a triangle and a triangle of the surface whose boxes come
// within rho runs in one batch of the kernel (collide/triangle_contact.hpp),
// and the pairs closer than rho become contacts, one per patch (the seed's
// redundant-contact filtering): close pairs whose surface triangles share
// corners are one patch, as the pieces of an overlap are, whichever of the
// triangles they touch, so a seam of the open surface adds no contact.
//
// A pair at distance d > 0 gives the margin model's exact depth rho - d
// along its witnesses. A pair that crosses (d = 0: the surface has gone
// more than rho into the margin) has no witness direction; it pushes along
// the triangle's normal, to the side of the solid's point `inside` (its
// centroid; TriangleSet), by rho plus
// how far the surface triangle's lowest corner lies behind the triangle's
// plane.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/collide/triangle_contact.hpp"
#include "gjkdem/contact/manifold.hpp"
#include "gjkdem/math/union_find.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem {

/// A triangle with a margin.
struct MarginTriangle {
  std::array<Vec3, 3> corners;
  Real rho = 0;  ///< > 0
};

/// One patch's contact, and which triangle its deepest pair touches.
struct MarginContact {
  ContactPoint contact;  ///< normal from the triangle to the surface; point midway across the margin
  std::uint32_t triangle = 0;
};

/// Memory reused from call to call (one per thread).
struct SurfaceMarginScratch {
  struct Pair {
    std::uint32_t triangle, facet;  ///< a margin triangle, a triangle of the surface
  };
  std::vector<std::uint32_t> near;
  std::vector<Pair> pairs;
  TrianglePairs batch;
  std::vector<TriangleDistanceBlock> distances;
  struct Close {
    ContactPoint contact;
    std::uint32_t pair;
  };
  std::vector<Close> close;        ///< one per pair closer than its rho
  std::vector<std::uint32_t> local_of;  ///< per vertex of the surface: its local id, or ~0 (not met)
  std::vector<std::uint32_t> met;       ///< the vertices met, by local id
  UnionFind patch_of;                   ///< of the local ids
  std::vector<Real> vertex_distance;    ///< by local id, to its nearest margin triangle
  std::vector<Vec3> vertex_nearest;     ///< by local id, the point of that triangle nearest it
  std::vector<Real> vertex_rho;         ///< by local id, that triangle's margin
  std::vector<std::uint32_t> touched;
  std::vector<std::uint32_t> roots;  ///< per patch, its vertices' root
  std::vector<Vec3> weighted;        ///< per patch, the corners' weighted sum
  std::vector<Real> weight;
};

/// The triangles met by margin triangles: a closed surface's (a solid), or
/// a thin shell's (shape/shell.hpp), with a tree of their boxes.
struct TriangleSet {
  std::span<const Vec3> vertices;
  std::span<const TriangleIndices> triangles;
  const BoxTree* tree = nullptr;
  Vec3 inside;  ///< a point of the solid (its centroid): the side crossing pairs push it to
  Real margin = 0;  ///< its own (a thin shell's half thickness), added to each margin triangle's
};
inline TriangleSet triangles_of(const Surface& s) noexcept { return {s.vertices, s.triangles, &s.tree, s.centroid}; }

/// The contacts of `surface` with `triangles`, everything in the surface's
/// frame; its point `inside` (or `centre`: the solid's centre of mass)
/// tells crossing pairs which side the solid lies on. One contact a patch, in the order of the patches'
/// first pairs (by triangle, then the surface's triangle): the depth and
/// normal of its deepest pair, its point the depth-weighted mean, midway
/// across the margin, of its corners within a margin (each corner counted
/// once, for its nearest triangle), or the deepest pair's where no corner
/// is. `out` is overwritten.
void surface_margin_contacts(const TriangleSet& surface, std::span<const MarginTriangle> triangles,
                             SurfaceMarginScratch& scratch, std::vector<MarginContact>& out);

}  // namespace gjkdem
