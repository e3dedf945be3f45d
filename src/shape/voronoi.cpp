#include "gjkdem/shape/voronoi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <stdexcept>

#include "gjkdem/shape/split.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem {
namespace {

// The facet of `cell` on the plane dot(u, x) = offset (u unit, pointing
// out of the cell): area, centroid and polar moment; area 0 where none.
CellFace face_on(const PolytopeData& d, const Vec3& u, Real offset, Real tol) {
  CellFace face;
  for (std::size_t f = 0; f + 1 < d.facet_begin.size(); ++f) {
    if (dot(d.facet_normals[f], u) < 1 - 1e-6) continue;
    const std::uint32_t begin = d.facet_begin[f], end = d.facet_begin[f + 1];
    bool on = true;
    for (std::uint32_t k = begin; k < end && on; ++k) on = std::fabs(dot(u, d.vertices[d.facet_vertices[k]]) - offset) <= tol;
    if (!on) continue;
    // A fan from the first vertex: area, centroid, then the polar moment
    // about the centroid (each triangle's integral of |r|^2 from its corners).
    const Vec3 o = d.vertices[d.facet_vertices[begin]];
    Real area = 0;
    Vec3 moment;
    for (std::uint32_t k = begin + 1; k + 1 < end; ++k) {
      const Vec3 p = d.vertices[d.facet_vertices[k]], q = d.vertices[d.facet_vertices[k + 1]];
      const Real a = Real(0.5) * dot(cross(p - o, q - o), u);
      area += a;
      moment += (o + p + q) * (a / 3);
    }
    if (!(area > 0)) return face;
    face.area = area;
    face.centroid = moment / area;
    for (std::uint32_t k = begin + 1; k + 1 < end; ++k) {
      const Vec3 p0 = o - face.centroid, p1 = d.vertices[d.facet_vertices[k]] - face.centroid,
                 p2 = d.vertices[d.facet_vertices[k + 1]] - face.centroid;
      const Real a = Real(0.5) * dot(cross(p1 - p0, p2 - p0), u);
      face.polar_moment += a / 6 *
          (dot(p0, p0) + dot(p1, p1) + dot(p2, p2) + dot(p0, p1) + dot(p1, p2) + dot(p2, p0));
    }
    return face;
  }
  return face;
}

}  // namespace

VoronoiCells voronoi_cells(const Polytope& solid, std::span<const Vec3> sites) {
  const PolytopeData& d = *solid.data;
  if (!(d.volume > 0)) throw std::invalid_argument("voronoi_cells: the solid has no volume");
  const Real size = std::cbrt(d.volume);
  const Real tol = 1e-9 * size;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    if (!is_finite(sites[i]) || !(facet_distance(d, sites[i]) <= tol))
      throw std::invalid_argument("voronoi_cells: site " + std::to_string(i) + " lies outside the solid");
    for (std::size_t j = 0; j < i; ++j)
      if (length(sites[i] - sites[j]) < tol)
        throw std::invalid_argument("voronoi_cells: sites " + std::to_string(j) + " and " + std::to_string(i) +
                                    " coincide");
  }
  VoronoiCells out;
  out.cells.reserve(sites.size());
  // Cell i is the solid cut by the bisector planes of site i and the others,
  // nearest first (their planes cut most, so later planes miss the cell at
  // once and cost no hull). Once a site lies beyond twice the cell's radius
  // about site i (and the face tolerance, and a margin far above the
  // round-off of the plane tests), every farther plane misses the cell: the
  // sites are sorted by distance a chunk at a time and the walk stops there,
  // with the cuts, in order, of the walk over every site. The sites whose
  // planes came within the face tolerance are kept for the faces below.
  const Real face_tol = kCellFaceRelTol * size;
  Real scale = size;  // of the coordinates, for the round-off of dot products
  for (const Vec3& v : d.vertices) scale = std::max(scale, max_abs(v));
  const Real stop_margin = 4 * face_tol + kCellStopRoundoffRel * scale;
  std::vector<std::uint32_t> order(sites.size());
  std::vector<Real> d2(sites.size());
  std::vector<std::vector<std::uint32_t>> near(sites.size());
  const auto radius_about = [](const Polytope& cell, const Vec3& centre) {
    Real r2 = 0;
    for (const Vec3& v : cell.data->vertices) r2 = std::max(r2, dot(v - centre, v - centre));
    return std::sqrt(r2);
  };
  for (std::size_t i = 0; i < sites.size(); ++i) {
    Polytope cell = solid;
    Real radius = radius_about(cell, sites[i]);
    for (std::uint32_t j = 0; j < order.size(); ++j) {
      order[j] = j;
      d2[j] = dot(sites[j] - sites[i], sites[j] - sites[i]);
    }
    const auto closer = [&](std::uint32_t x, std::uint32_t y) { return d2[x] != d2[y] ? d2[x] < d2[y] : x < y; };
    std::size_t sorted = 0, chunk = 32;
    for (std::size_t k = 0; k < order.size(); ++k) {
      if (k == sorted) {
        sorted = std::min(order.size(), sorted + chunk);
        std::partial_sort(order.begin() + static_cast<std::ptrdiff_t>(k), order.begin() + static_cast<std::ptrdiff_t>(sorted),
                          order.end(), closer);
        chunk *= 2;
      }
      const std::uint32_t j = order[k];
      if (j == i) continue;
      if (std::sqrt(d2[j]) > 2 * radius + stop_margin) break;  // this plane and every farther one miss the cell
      const Vec3 normal = sites[j] - sites[i];
      const Real offset = dot(normal, (sites[i] + sites[j]) * Real(0.5));
      Real reach = -std::numeric_limits<Real>::infinity();
      for (const Vec3& v : cell.data->vertices) reach = std::max(reach, dot(normal, v));
      if (reach > offset - 2 * face_tol * length(normal)) near[i].push_back(j);  // a face may lie on its plane
      if (reach <= offset) continue;  // the plane misses the cell
      if (std::optional<Polytope> below = polytope_below(cell, normal, offset)) {
        cell = std::move(*below);
        radius = radius_about(cell, sites[i]);
      }
    }
    out.cells.push_back(std::move(cell));
  }
  // A face of cell i on the plane of i and j lies within the face tolerance
  // of that plane: j is among the sites kept for i.
  const Real smallest = kSmallestCellFaceRel * size * size;
  for (std::uint32_t i = 0; i < sites.size(); ++i) {
    std::sort(near[i].begin(), near[i].end());
    for (const std::uint32_t j : near[i]) {
      if (j <= i) continue;
      const Vec3 normal = sites[j] - sites[i];
      const Vec3 u = normal / length(normal);
      CellFace face = face_on(*out.cells[i].data, u, dot(u, (sites[i] + sites[j]) * Real(0.5)), face_tol);
      if (!(face.area > smallest)) continue;
      face.a = i, face.b = j, face.normal = u;
      out.faces.push_back(face);
    }
  }
  return out;
}

}  // namespace gjkdem
