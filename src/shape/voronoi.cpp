#include "gjkdem/shape/voronoi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <stdexcept>

#include "gjkdem/shape/split.hpp"

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
  for (std::size_t i = 0; i < sites.size(); ++i) {
    Polytope cell = solid;
    // Nearest sites first: their planes cut most, so later planes miss the
    // cell at once (the support test) and cost no hull.
    std::vector<std::uint32_t> order(sites.size());
    for (std::uint32_t j = 0; j < order.size(); ++j) order[j] = j;
    std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
      const Real dx = dot(sites[x] - sites[i], sites[x] - sites[i]), dy = dot(sites[y] - sites[i], sites[y] - sites[i]);
      return dx != dy ? dx < dy : x < y;
    });
    for (const std::uint32_t j : order) {
      if (j == i) continue;
      const Vec3 normal = sites[j] - sites[i];
      const Real offset = dot(normal, (sites[i] + sites[j]) * Real(0.5));
      Real reach = -std::numeric_limits<Real>::infinity();
      for (const Vec3& v : cell.data->vertices) reach = std::max(reach, dot(normal, v));
      if (reach <= offset) continue;  // the plane misses the cell
      PolytopeSplit s = split_polytope(cell, normal, offset);
      if (s.below) cell = std::move(*s.below);
    }
    out.cells.push_back(std::move(cell));
  }
  const Real smallest = kSmallestCellFaceRel * size * size;
  for (std::uint32_t i = 0; i < sites.size(); ++i)
    for (std::uint32_t j = i + 1; j < sites.size(); ++j) {
      const Vec3 normal = sites[j] - sites[i];
      const Vec3 u = normal / length(normal);
      CellFace face = face_on(*out.cells[i].data, u, dot(u, (sites[i] + sites[j]) * Real(0.5)), 1e-7 * size);
      if (!(face.area > smallest)) continue;
      face.a = i, face.b = j, face.normal = u;
      out.faces.push_back(face);
    }
  return out;
}

}  // namespace gjkdem
