// Walls (world_builder.hpp): plane walls, and box, mesh and cylinder walls
// as fixed pieces, each piece of a mesh wall a template of its own.
#include "gjkdem/dem/world_builder.hpp"

#include <cmath>
#include <tuple>

#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem::dem {

void WorldBuilder::add_plane(const Vec3& point, const Vec3& normal, std::uint32_t material, const std::string& label,
                             std::uint32_t motion) {
  check_material(material, label);
  check_motion_number(motion, label);
  if (!is_finite(point) || !is_finite(normal)) throw BuildError(label + ": point and normal must be finite");
  // Scaled first, so that huge components do not overflow the length.
  const Real largest = max_abs(normal);
  const Vec3 unit = largest > 0 ? normalized(normal / largest) : Vec3{};
  if (!(length(unit) > 0.5)) throw BuildError(label + ": the normal must not be zero");
  world_.planes.push_back({kPlaneIdBase + world_.planes.size(), point, unit, material, motion, point, unit});
}

std::uint32_t WorldBuilder::add_fixed_piece(const Shape& shape, const Vec3& position, std::uint32_t material,
                                            std::uint32_t group, const std::string& label, std::uint32_t motion) {
  Body b;
  b.id = next_id();
  b.shape = add_template(BodyShape{shape, {}}, true, label);
  b.material = material;
  b.group = group;
  b.fixed = true;
  b.position = position;
  world_.bodies.push_back(b);
  labels_.push_back(label);
  const std::uint32_t index = static_cast<std::uint32_t>(world_.bodies.size() - 1);
  drive(index, motion);
  return index;
}

void WorldBuilder::add_box_walls(const Vec3& lo, const Vec3& hi, bool open_top, Real t, std::uint32_t material,
                                 const std::string& label, std::uint32_t motion) {
  check_material(material, label);
  check_motion_number(motion, label);
  if (!is_finite(lo) || !is_finite(hi) || !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
    throw BuildError(label + ": max must exceed min on every axis");
  if (!(t > 0) || !std::isfinite(t)) throw BuildError(label + ": the thickness must be > 0");
  const std::uint32_t group = ++groups_;
  const Vec3 c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
  auto slab = [&](const Vec3& half, const Vec3& centre, const char* side) {
    add_fixed_piece(Shape{Box{half}}, centre, material, group, label + side, motion);
  };
  slab({h.x + 2 * t, h.y + 2 * t, t / 2}, {c.x, c.y, lo.z - t / 2}, " (floor)");
  if (!open_top) slab({h.x + 2 * t, h.y + 2 * t, t / 2}, {c.x, c.y, hi.z + t / 2}, " (roof)");
  slab({t / 2, h.y + t, h.z}, {lo.x - t / 2, c.y, c.z}, " (side -x)");
  slab({t / 2, h.y + t, h.z}, {hi.x + t / 2, c.y, c.z}, " (side +x)");
  slab({h.x, t / 2, h.z}, {c.x, lo.y - t / 2, c.z}, " (side -y)");
  slab({h.x, t / 2, h.z}, {c.x, hi.y + t / 2, c.z}, " (side +y)");
}

void WorldBuilder::add_mesh_walls(std::span<const Vec3> vertices,
                                  std::span<const std::array<std::uint32_t, 3>> triangles, Real thick,
                                  std::uint32_t material, const std::string& label, std::uint32_t motion) {
  check_material(material, label);
  check_motion_number(motion, label);
  for (const Vec3& v : vertices)
    if (!is_finite(v)) throw BuildError(label + ": vertices must be finite (a scale beyond double precision?)");
  if (!(thick > 0) || !std::isfinite(thick)) throw BuildError(label + ": the thickness must be > 0 and finite");
  const std::uint32_t group = ++groups_;
  std::size_t index = 0;
  for (const auto& tri : triangles) {
    const std::string triangle = "triangle " + std::to_string(index++), piece = label + " (" + triangle + ")";
    if (const std::string why = triangle_index_problem(tri, vertices.size()); !why.empty())
      throw BuildError(label + ": " + triangle + " " + why);
    const Vec3 a = vertices[tri[0]], b = vertices[tri[1]], c = vertices[tri[2]];
    const Vec3 n3 = cross(b - a, c - a);
    if (!(length(n3) > 0)) continue;  // degenerate triangles hold nothing
    const Vec3 centre = (a + b + c) / 3.0, n = normalized(n3) * (thick / 2);
    Shape shape;
    if (settings_.model == ContactModel::Volume) {
      const Vec3 prism[6] = {a - centre + n, b - centre + n, c - centre + n, a - centre - n, b - centre - n, c - centre - n};
      shape = Shape{make_polytope(prism)};
    } else {
      shape = Shape{Triangle{{a - centre, b - centre, c - centre}}, thick / 2};
    }
    const std::uint32_t placed = add_fixed_piece(shape, centre, material, group, piece, motion);
    world_.templates[world_.bodies[placed].shape].wall_face = Triangle{{a - centre, b - centre, c - centre}};
  }
}

std::string cylinder_segments_problem(std::int64_t segments) {
  constexpr std::int64_t kFewest = 8, kMost = 4096;
  if (segments >= kFewest && segments <= kMost) return "";
  return "must be " + std::to_string(kFewest) + " to " + std::to_string(kMost);
}

Real cylinder_wall_thickness(const CylinderWall& w) { return w.thickness > 0 ? w.thickness : 0.02 * w.radius; }

void cylinder_wall_mesh(const CylinderWall& w, const std::string& label, std::vector<Vec3>& vertices,
                        std::vector<std::array<std::uint32_t, 3>>& triangles) {
  if (!is_finite(w.base) || !is_finite(w.axis) || !(length(w.axis) > 0))
    throw BuildError(label + ": the base and a non-zero axis must be finite");
  if (!(w.radius > 0) || !std::isfinite(w.radius) || !(w.height > 0) || !std::isfinite(w.height))
    throw BuildError(label + ": the radius and height must be finite and > 0");
  if (const std::string why = cylinder_segments_problem(w.segments); !why.empty())
    throw BuildError(label + ": segments " + why);
  if (!(w.thickness >= 0) || !std::isfinite(w.thickness)) throw BuildError(label + ": the thickness must be >= 0");
  const Real t = cylinder_wall_thickness(w);
  const Vec3 a = normalized(w.axis);
  Vec3 u, v;
  orthonormal_basis(a, u, v);
  const int n = w.segments;
  // A piece's middle lies half a thickness behind its inner face: the flats
  // at radius + t/2 (their corners farther out), the caps t/2 beyond the ends.
  const Real corner = (w.radius + t / 2) / std::cos(kPi / n);
  const Vec3 low = w.base - a * (t / 2), high = w.base + a * (w.height + t / 2);
  vertices.clear(), triangles.clear();
  for (int k = 0; k < n; ++k) {
    const Real angle = 2 * kPi * k / n;
    const Vec3 out = (u * std::cos(angle) + v * std::sin(angle)) * corner;
    vertices.push_back(low + out);
    vertices.push_back(high + out);
  }
  const auto at = [n](int k, int level) { return static_cast<std::uint32_t>(2 * ((k % n + n) % n) + level); };
  for (int k = 0; k < n; ++k) {
    triangles.push_back({at(k, 0), at(k + 1, 0), at(k + 1, 1)});
    triangles.push_back({at(k, 0), at(k + 1, 1), at(k, 1)});
  }
  // Caps: fans about their centres, the side walls' ends reaching them. All
  // triangles face out (counter-clockwise seen from outside), so a capped
  // cylinder is a closed mesh (the scene's containment check takes it).
  for (const auto& [capped, centre, level] : {std::tuple{w.bottom, low, 0}, std::tuple{w.top, high, 1}}) {
    if (!capped) continue;
    const auto middle = static_cast<std::uint32_t>(vertices.size());
    vertices.push_back(centre);
    for (int k = 0; k < n; ++k)
      triangles.push_back(level ? std::array{middle, at(k, 1), at(k + 1, 1)} : std::array{middle, at(k + 1, 0), at(k, 0)});
  }
}

void WorldBuilder::add_cylinder_walls(const CylinderWall& wall, std::uint32_t material, const std::string& label,
                                      std::uint32_t motion) {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  cylinder_wall_mesh(wall, label, vertices, triangles);
  add_mesh_walls(vertices, triangles, cylinder_wall_thickness(wall), material, label, motion);
}

}  // namespace gjkdem::dem
