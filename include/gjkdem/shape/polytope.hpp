#pragma once
// Convex polytope: the convex hull of a point cloud. Only the hull vertices are
// kept. Large hulls carry their vertex adjacency so that support() can hill-climb
// from a hint instead of scanning every vertex. The data are immutable, in one
// block, and shared, so many particles can use one template.
#include <algorithm>
#include <array>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "gjkdem/math/vec3.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {

struct HullSurfaceSlot;  // shape/hull_surface_slot.hpp

/// Cells per cube-face side of the support start table (6 * n * n cells).
inline constexpr int kSupportMapResolution = 4;

/// A polytope's data, in one block of memory: this header, then its arrays
/// in the order a query reads them (the vectorised scan's coordinates, the
/// vertices, the hill-climbing tables, then what clipping uses). A shape that
/// is not in cache then costs a few misses, not one per array: with one
/// shape per particle (scanned rocks) most queries start cold. Made only by
/// make_polytope; immutable.
struct PolytopeData {
  /// Structure-of-arrays copy of the vertices for the vectorised scan: x of all
  /// vertices, then y, then z, each padded to an even count with vertex 0.
  std::span<const Real> soa;
  int soa_stride = 0;                               ///< padded vertex count
  Real radius = 0;                                  ///< max |vertex|
  std::span<const Vec3> vertices;                   ///< hull vertices, local frame
  std::span<const std::uint32_t> adj_begin;         ///< CSR offsets into adj (size vertices+1); empty: scan
  std::span<const std::uint32_t> adj;               ///< neighbour vertex indices
  /// Support vertex of the centre direction of each cube-map cell: hill climbing
  /// starts there, a few steps from the answer whatever the direction.
  std::span<const std::uint32_t> start;
  /// Outward triangles of the hull (indices into vertices); empty when the hull
  /// is flat, a segment or a point.
  std::span<const std::array<std::uint32_t, 3>> triangles;
  /// Facets (coplanar triangles merged, counter-clockwise from outside): facet f
  /// is facet_vertices[facet_begin[f] .. facet_begin[f+1]); empty when flat.
  std::span<const std::uint32_t> facet_begin;
  std::span<const std::uint32_t> facet_vertices;
  std::span<const Vec3> facet_normals;              ///< unit, outward
  Real volume = 0;                                  ///< of the hull; 0 when flat
  Vec3 centroid;                                    ///< of the solid hull; of the vertices when flat
  /// Where a big hull's boundary surface is kept once made (hull_surface,
  /// surface.hpp); null below kSurfaceRouteMinTriangles triangles. Owned by
  /// the block.
  HullSurfaceSlot* surface_slot = nullptr;
};

namespace detail {

/// scan_support_index for larger hulls, out of line: 4 vertices at a time
/// where the processor has AVX2, else the inline 2-wide scan; the same vertex
/// either way (the first one with the maximum, from the same products).
int scan_support_index_wide(const PolytopeData& s, const Vec3& d) noexcept;

/// Index of the first vertex maximising d . v, by one vectorised pass:
/// branch-free, which beats hill climbing on small hulls.
inline int scan_support_index_narrow(const PolytopeData& s, const Vec3& d) noexcept {
  const Real* xs = s.soa.data();
  const Real* ys = xs + s.soa_stride;
  const Real* zs = ys + s.soa_stride;
  const int m = s.soa_stride;
#if defined(__SSE2__)
  const __m128d dx = _mm_set1_pd(d.x), dy = _mm_set1_pd(d.y), dz = _mm_set1_pd(d.z);
  auto dots = [&](int i) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_loadu_pd(xs + i), dx), _mm_mul_pd(_mm_loadu_pd(ys + i), dy)),
                      _mm_mul_pd(_mm_loadu_pd(zs + i), dz));
  };
  // One pass: each lane keeps its first maximum and that vertex's index
  // (lane 0 the even vertices, lane 1 the odd ones); then the larger of the
  // two, the smaller index on a tie: the first vertex with the maximum.
  __m128d best = dots(0);
  __m128d index = _mm_set_pd(1, 0);
  const __m128d two = _mm_set1_pd(2);
  __m128d at = index;
  for (int i = 2; i < m; i += 2) {
    at = _mm_add_pd(at, two);
    const __m128d t = dots(i);
    const __m128d more = _mm_cmpgt_pd(t, best);
    best = _mm_or_pd(_mm_and_pd(more, t), _mm_andnot_pd(more, best));
    index = _mm_or_pd(_mm_and_pd(more, at), _mm_andnot_pd(more, index));
  }
  const double b0 = _mm_cvtsd_f64(best), b1 = _mm_cvtsd_f64(_mm_unpackhi_pd(best, best));
  const int i0 = static_cast<int>(_mm_cvtsd_f64(index)), i1 = static_cast<int>(_mm_cvtsd_f64(_mm_unpackhi_pd(index, index)));
  return (b1 > b0 || (b1 == b0 && i1 < i0)) ? i1 : i0;
#else
  int best = 0;
  Real best_dot = xs[0] * d.x + ys[0] * d.y + zs[0] * d.z;
  for (int i = 1; i < m; ++i) {
    const Real t = xs[i] * d.x + ys[i] * d.y + zs[i] * d.z;
    if (t > best_dot) { best_dot = t; best = i; }
  }
  return best;
#endif
}

inline int scan_support_index(const PolytopeData& s, const Vec3& d) noexcept {
  return s.soa_stride >= kWideScanMinVertices ? scan_support_index_wide(s, d) : scan_support_index_narrow(s, d);
}

/// Cube-map cell of direction d (not zero): face by dominant axis, then a
/// kSupportMapResolution^2 grid on that face.
inline int support_map_cell(const Vec3& d) noexcept {
  const Real ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  const int axis = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
  const Real m = std::fabs(d[axis]);
  const Real u = d[(axis + 1) % 3] / m, v = d[(axis + 2) % 3] / m;  // in [-1, 1]
  constexpr int n = kSupportMapResolution;
  const int iu = std::min(n - 1, static_cast<int>((u + 1) * (Real(0.5) * n)));
  const int iv = std::min(n - 1, static_cast<int>((v + 1) * (Real(0.5) * n)));
  return ((2 * axis + (d[axis] < 0)) * n + iu) * n + iv;
}
}  // namespace detail

struct Polytope {
  std::shared_ptr<const PolytopeData> data;
};

/// Builds the hull of `points` (local frame). Throws std::invalid_argument when
/// points is empty or holds a non-finite coordinate.
Polytope make_polytope(std::span<const Vec3> points);

/// How far p lies outside the solid hull: the largest signed distance of p
/// from its facets' planes (negative inside). -infinity for a flat hull.
Real facet_distance(const PolytopeData& d, const Vec3& p) noexcept;

// Always inlined: the call cost a DEM bed of 12-vertex grains 1.4% of its
// step (5 million calls).
[[gnu::always_inline]] inline Vec3 support(const Polytope& p, const Vec3& d, int& hint) noexcept {
  const PolytopeData& s = *p.data;
  const Vec3* v = s.vertices.data();
  const int n = static_cast<int>(s.vertices.size());
  if (s.adj.empty()) {
    const int best = detail::scan_support_index(s, d);
    hint = best;
    return v[best];
  }
  // Hill climbing: a linear function's local maximum on the vertex graph of a
  // convex polytope is global, and strict improvement guarantees termination.
  // Start from the better of the caller's hint and the cube-map cell's vertex.
  if (!(max_abs(d) > 0)) { hint = 0; return v[0]; }
  int cur = static_cast<int>(s.start[detail::support_map_cell(d)]);
  Real cur_dot = dot(v[cur], d);
  if (hint >= 0 && hint < n && hint != cur) {
    const Real h = dot(v[hint], d);
    if (h > cur_dot) { cur_dot = h; cur = hint; }
  }
  for (bool moved = true; moved;) {
    moved = false;
    for (std::uint32_t k = s.adj_begin[cur], e = s.adj_begin[cur + 1]; k < e; ++k) {
      const int j = static_cast<int>(s.adj[k]);
      const Real t = dot(v[j], d);
      if (t > cur_dot) { cur_dot = t; cur = j; moved = true; }
    }
  }
  hint = cur;
  return v[cur];
}
inline Real bounding_radius(const Polytope& p) noexcept { return p.data->radius; }

}  // namespace gjkdem
