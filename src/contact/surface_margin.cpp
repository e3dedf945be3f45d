#include "gjkdem/contact/surface_margin.hpp"

#include <algorithm>
#include <cmath>

#include "gjkdem/shape/triangle.hpp"

namespace gjkdem {

void surface_margin_contacts(const TriangleSet& s, std::span<const MarginTriangle> triangles,
                             SurfaceMarginScratch& w, std::vector<MarginContact>& out) {
  const Vec3& centre = s.inside;
  out.clear();
  w.pairs.clear();
  for (std::uint32_t i = 0; i < triangles.size(); ++i) {
    const MarginTriangle& t = triangles[i];
    const Vec3 grow{t.rho, t.rho, t.rho};
    w.near.clear();
    query_box_tree(*s.tree, {min(min(t.corners[0], t.corners[1]), t.corners[2]) - grow,
                            max(max(t.corners[0], t.corners[1]), t.corners[2]) + grow},
                   w.near);
    // In the surface's triangle order, not the tree's: the patches then do
    // not depend on how the tree split the surface (moved, it splits otherwise).
    std::sort(w.near.begin(), w.near.end());
    for (const std::uint32_t f : w.near) w.pairs.push_back({i, f});
  }
  if (w.pairs.empty()) return;
  w.batch.clear();
  for (const SurfaceMarginScratch::Pair& p : w.pairs) {
    const std::array<Vec3, 3>& c = triangles[p.triangle].corners;
    const TriangleIndices& v = s.triangles[p.facet];
    w.batch.push_back(c[0], c[1], c[2], s.vertices[v[0]], s.vertices[v[1]], s.vertices[v[2]]);
  }
  triangle_distances(w.batch, w.distances);

  // Each close pair's contact; its surface triangle's corners joined into patches.
  // The corners of the close pairs' triangles get local ids as they are met
  // (set back at the end), so that the work follows the contact, not the
  // surface's size.
  constexpr std::uint32_t kNone = ~0u;
  w.local_of.resize(s.vertices.size(), kNone);
  w.met.clear();
  w.patch_of.reset(0);
  const auto local = [&](std::uint32_t v) {
    if (w.local_of[v] == kNone) {
      w.local_of[v] = static_cast<std::uint32_t>(w.met.size());
      w.met.push_back(v);
      w.patch_of.add();
    }
    return w.local_of[v];
  };
  w.close.clear();
  for (std::uint32_t i = 0; i < w.pairs.size(); ++i) {
    const TriangleDistanceBlock& r = w.distances[i / kTriangleLanes];
    const std::size_t l = i % kTriangleLanes;
    const Real d = r.distance[l];
    const MarginTriangle& t = triangles[w.pairs[i].triangle];
    if (!(d < t.rho)) continue;
    const TriangleIndices& v = s.triangles[w.pairs[i].facet];
    const std::uint32_t first = local(v[0]);
    w.patch_of.join(first, local(v[1])), w.patch_of.join(first, local(v[2]));
    const Vec3 on_triangle{r.witness_a[0][l], r.witness_a[1][l], r.witness_a[2][l]};
    if (d > 0) {
      const Vec3 on_surface{r.witness_b[0][l], r.witness_b[1][l], r.witness_b[2][l]};
      const Vec3 n = (on_surface - on_triangle) / d;
      // Midway between the margin's boundary (rho out) and the surface (d out).
      w.close.push_back({{on_triangle + n * ((t.rho + d) / 2), n, t.rho - d}, i});
      continue;
    }
    // Crossing: along the normal, to the solid's side.
    const Vec3 face = cross(t.corners[1] - t.corners[0], t.corners[2] - t.corners[0]);
    const Vec3 up = dot(centre - t.corners[0], face) >= 0 ? normalized(face) : -normalized(face);
    Real lowest = 0;  // of the surface triangle's corners above the plane (<= 0: it crosses)
    for (const std::uint32_t k : v) lowest = std::fmin(lowest, dot(s.vertices[k] - t.corners[0], up));
    w.close.push_back({{on_triangle + up * ((t.rho + lowest) / 2), up, t.rho - lowest}, i});
  }
  if (w.close.empty()) return;

  // Patches in the order of their first close pairs; each takes its deepest.
  std::vector<std::uint32_t>& roots = w.roots;
  roots.clear();
  for (const SurfaceMarginScratch::Close& c : w.close) {
    const std::uint32_t root = w.patch_of.find(w.local_of[s.triangles[w.pairs[c.pair].facet][0]]);
    const auto at = std::find(roots.begin(), roots.end(), root);
    if (at == roots.end()) {
      roots.push_back(root);
      out.push_back({c.contact, w.pairs[c.pair].triangle});
    } else if (c.contact.depth > out[at - roots.begin()].contact.depth) {
      out[at - roots.begin()] = {c.contact, w.pairs[c.pair].triangle};
    }
  }

  // The corners within a margin, each for its nearest triangle: a flat
  // face's point lies under the face's middle, where one pair's witness
  // would lie at any of its corners, and a corner over a seam counts once.
  w.vertex_distance.assign(w.met.size(), INFINITY);  // by local id
  w.vertex_nearest.resize(w.met.size());
  w.vertex_rho.resize(w.met.size());
  for (const SurfaceMarginScratch::Close& c : w.close) {
    const MarginTriangle& t = triangles[w.pairs[c.pair].triangle];
    for (const std::uint32_t k : s.triangles[w.pairs[c.pair].facet]) {
      const Vec3 q = closest_point_on_triangle(s.vertices[k], t.corners[0], t.corners[1], t.corners[2]);
      const Real d = length(s.vertices[k] - q);
      const std::uint32_t at = w.local_of[k];
      if (d < w.vertex_distance[at]) w.vertex_distance[at] = d, w.vertex_nearest[at] = q, w.vertex_rho[at] = t.rho;
    }
  }
  w.touched = w.met;
  std::sort(w.touched.begin(), w.touched.end());  // sums in vertex order
  std::vector<Vec3>& weighted = w.weighted;
  std::vector<Real>& weight = w.weight;
  weighted.assign(out.size(), Vec3{});
  weight.assign(out.size(), 0);
  for (const std::uint32_t k : w.touched) {
    const std::uint32_t at = w.local_of[k];
    const Real d = w.vertex_distance[at], rho = w.vertex_rho[at];
    if (!(d < rho)) continue;
    const std::size_t p = std::find(roots.begin(), roots.end(), w.patch_of.find(at)) - roots.begin();
    const Vec3 v = s.vertices[k];
    const Vec3 q = w.vertex_nearest[at];
    // Midway between the corner and the margin's boundary beyond it.
    weighted[p] += (q + v + (d > 0 ? (v - q) * (rho / d) : Vec3{})) * (0.5 * (rho - d));
    weight[p] += rho - d;
  }
  for (const std::uint32_t k : w.met) w.local_of[k] = kNone;  // left as found, for the next call
  for (std::size_t p = 0; p < out.size(); ++p)
    if (weight[p] > 0) out[p].contact.point = weighted[p] / weight[p];
}

}  // namespace gjkdem
