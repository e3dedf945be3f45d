#pragma once
// A closed triangle surface, convex or not, and the solid it bounds: the
// shape of a non-convex grain taken as scanned (no hull, no decomposition).
// Made once per template by make_surface, which checks what the contact
// model relies on and names the edge, vertex or triangles at fault: closed
// and manifold (every edge in exactly two triangles, every vertex one fan),
// consistently oriented outward ((v1 - v0) x (v2 - v0) points out of the
// solid), no triangle without area, no unused vertex, no two triangles
// meeting anywhere but in their shared edge or vertex (decided exactly:
// predicates.hpp). It keeps its edges and a tree of its triangles' boxes
// (box_tree.hpp), all in its own frame.
#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

#include "gjkdem/math/transform.hpp"
#include "gjkdem/shape/aabb.hpp"
#include "gjkdem/shape/mass_properties.hpp"
#include "gjkdem/shape/box_tree.hpp"
#include "gjkdem/shape/box.hpp"
#include "gjkdem/shape/polytope.hpp"

namespace gjkdem {

using TriangleIndices = std::array<std::uint32_t, 3>;
struct DeepPointsSlot;

/// What is wrong with a triangle's corners as indices into `vertex_count`
/// vertices: one out of range, or a vertex named twice; "" when nothing is.
/// The one index rule of every triangle mesh taken (surfaces, shells, mesh
/// walls); callers put "triangle N " before it.
std::string triangle_index_problem(const TriangleIndices& corners, std::size_t vertex_count);
/// Whether a triangle names one vertex twice (so it has no area).
constexpr bool repeats_a_vertex(const TriangleIndices& c) noexcept {
  return c[0] == c[1] || c[1] == c[2] || c[2] == c[0];
}

struct Surface {
  std::vector<Vec3> vertices;
  std::vector<TriangleIndices> triangles;              ///< counter-clockwise seen from outside
  std::vector<std::array<std::uint32_t, 2>> edges;     ///< each edge once, lower vertex index first
  /// Per triangle, the edge of each side k: from corner k to corner k + 1.
  std::vector<std::array<std::uint32_t, 3>> triangle_edges;
  /// Per edge, its two triangles: [0] runs it from edges[e][0] to edges[e][1], [1] the other way.
  std::vector<std::array<std::uint32_t, 2>> edge_triangles;
  /// The edges at each vertex: vertex_edges[vertex_edge_begin[v] .. vertex_edge_begin[v + 1]).
  std::vector<std::uint32_t> vertex_edge_begin, vertex_edges;
  std::vector<Aabb> triangle_boxes, edge_boxes;
  BoxTree tree;  ///< of triangle_boxes, ids the triangles
  Aabb box;
  Real volume = 0;  ///< of the solid (mass_properties)
  Vec3 centroid;    ///< of the solid, in the surface's frame (moved with it)
  /// Where its deep points are kept, made when first asked for
  /// (deep_points.hpp); shared by its copies, null in a moved one.
  std::shared_ptr<DeepPointsSlot> deep;
};

/// A surface that breaks a rule: the message names the edge, vertex or
/// triangles (0-based indices).
struct SurfaceError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// Checks the surface (file comment) and builds its edges and tree. Throws
/// SurfaceError. Coordinates must be finite.
Surface make_surface(std::vector<Vec3> vertices, std::vector<TriangleIndices> triangles);

/// The surface moved rigidly by `pose` (its vertices, boxes and tree's
/// boxes in the new frame; the tree's shape and everything checked kept):
/// to compare two surfaces posed apart, move one into the other's frame.
Surface moved(const Surface& surface, const Transform& pose);
/// The same into `into`, whose memory is reused (a step's scratch).
void move_into(const Surface& surface, const Transform& pose, Surface& into);
/// The same where `copy` is already a copy of `surface`, moved or not: only
/// its vertices and boxes are rewritten (its topology is that of `surface`).
void repose(const Surface& surface, const Transform& pose, Surface& copy);

/// The boundary of a solid polytope (its hull triangles) as a surface: a
/// convex body as a surface grain's contacts see it. Throws SurfaceError for
/// a flat polytope.
Surface polytope_surface(const Polytope& polytope);
/// The boundary of a big solid polytope (kSurfaceRouteMinTriangles hull
/// triangles or more) as polytope_surface gives it, made on the first call
/// (thread-safe) and kept with the polytope's data for every copy of it.
/// Null for smaller or flat polytopes, and where the hull's triangles do not
/// make a valid surface (a hull that is not manifold).
std::shared_ptr<const Surface> hull_surface(const Polytope& polytope);
/// The boundary of a solid box (its 12 triangles). Throws SurfaceError for
/// a flat box.
Surface box_surface(const Box& box);

/// Volume, centroid and inertia (per unit density) of the solid, exactly
/// from its triangles (the divergence theorem).
MassProperties mass_properties(const Surface& surface);

/// How many times the closed triangles wind about p: each triangle's signed
/// solid angle seen from p (Van Oosterom and Strackee), summed over 4 pi. 1
/// inside an outward surface, 0 outside, with no special case for rays
/// through edges or corners (a point on the surface gets about 1/2).
Real winding_number(std::span<const Vec3> vertices, std::span<const TriangleIndices> triangles, const Vec3& p);

/// True when triangles s and t of the surface meet anywhere but in the edge
/// or vertex they share (exact).
bool triangles_clash(const Surface& surface, std::uint32_t s, std::uint32_t t);

/// The triangles about vertex v (`fan`: all of them, in the order their
/// shared edges chain them) in runs, by index: any two triangles of one run
/// meet only at v and in the edge they share, by a sufficient test that is
/// exact. Seen along the fan's mean normal, a run is consecutive triangles
/// that turn the same way about v and fall short of a round (no direction
/// from v in two of its corners), or the whole fan where its turns agree and
/// make one round (each direction in exactly one corner, counted half-open):
/// each triangle is then a one-to-one image, two images meet only at v or
/// along a shared side, and so do the triangles. A flat cap or a cone is one
/// run; a fold starts new runs; a triangle alone in its run has no verdict.
/// make_surface checks pairs of triangles across runs only.
std::vector<std::uint32_t> fan_runs(const Surface& surface, std::uint32_t v, std::span<const std::uint32_t> fan);

/// True when the closed triangles abc and def share a point (exact).
bool triangles_meet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e, const Vec3& f);

}  // namespace gjkdem
