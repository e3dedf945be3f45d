#pragma once
// Convex polytope: the convex hull of a point cloud. Only the hull vertices are
// kept. Large hulls carry their vertex adjacency so that support() can hill-climb
// from a hint instead of scanning every vertex. The data are immutable and
// shared, so many particles can use one template.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem {

struct PolytopeData {
  std::vector<Vec3> vertices;            ///< hull vertices, local frame
  std::vector<std::uint32_t> adj_begin;  ///< CSR offsets into adj (size vertices+1); empty: scan
  std::vector<std::uint32_t> adj;        ///< neighbour vertex indices
  Real radius = 0;                       ///< max |vertex|
};

struct Polytope {
  std::shared_ptr<const PolytopeData> data;
};

/// Builds the hull of `points` (local frame). Throws std::invalid_argument when
/// points is empty or holds a non-finite coordinate.
Polytope make_polytope(std::span<const Vec3> points);

inline Vec3 support(const Polytope& p, const Vec3& d, int& hint) noexcept {
  const PolytopeData& s = *p.data;
  const Vec3* v = s.vertices.data();
  const int n = static_cast<int>(s.vertices.size());
  if (s.adj.empty()) {
    int best = 0;
    Real best_dot = dot(v[0], d);
    for (int i = 1; i < n; ++i) {
      const Real t = dot(v[i], d);
      if (t > best_dot) { best_dot = t; best = i; }
    }
    hint = best;
    return v[best];
  }
  // Hill climbing: a linear function's local maximum on the vertex graph of a
  // convex polytope is global, and strict improvement guarantees termination.
  int cur = (hint >= 0 && hint < n) ? hint : 0;
  Real cur_dot = dot(v[cur], d);
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
