// Bonded assemblies: a convex solid cut into Voronoi pieces glued face to
// face (world_builder.hpp: BondedDef; bonds.hpp; docs/breakage.md).
#include <algorithm>
#include <cmath>
#include <string>

#include "gjkdem/dem/bonds.hpp"
#include "gjkdem/dem/inflow.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/shape/shape_factories.hpp"
#include "gjkdem/shape/tessellate.hpp"
#include "gjkdem/shape/voronoi.hpp"
#include "gjkdem/tolerances.hpp"
#include "number_text.hpp"

namespace gjkdem::dem {
namespace {

using detail::number_text;

constexpr std::uint64_t kSiteKey = 0x424f4e4453495445;  // keys the sites' draws apart from other draws
constexpr int kSiteTries = 1000;                        // per site: rejection from the bounding box

// The solid an assembly is cut from, in its shape's frame.
Polytope solid_of(const BodyShape& s, int tessellation, const std::string& label) {
  if (is_compound(s) || s.surface || s.shell)
    throw BuildError(label + ": a bonded assembly is cut from one convex shape, not a compound, a surface or a shell");
  const bool sharp = s.shape.margin == 0;
  if (const Polytope* p = std::get_if<Polytope>(&s.shape.core); p && sharp) {
    if (!(p->data->volume > 0)) throw BuildError(label + ": the shape of a bonded assembly has no volume");
    return *p;
  }
  if (const Box* b = std::get_if<Box>(&s.shape.core); b && sharp) {
    if (!(b->half_extents.x > 0 && b->half_extents.y > 0 && b->half_extents.z > 0))
      throw BuildError(label + ": the box of a bonded assembly has no volume");
    return box_polytope(*b);
  }
  if (sharp && (std::holds_alternative<Point>(s.shape.core) || std::holds_alternative<Segment>(s.shape.core) ||
                std::holds_alternative<Triangle>(s.shape.core)))
    throw BuildError(label + ": the shape of a bonded assembly has no volume");
  Polytope p = tessellate(s.shape, tessellation).polytope;
  if (!(p.data->volume > 0)) throw BuildError(label + ": the tessellation of the bonded assembly's shape is flat");
  return p;
}

}  // namespace

std::vector<std::uint32_t> WorldBuilder::add_bonded(const BondedDef& d) {
  const std::string label = d.label.empty() ? "bonded assembly " + std::to_string(world_.bodies.size()) : d.label;
  check_material(d.material, label);
  const Material& material = world_.materials[d.material];
  if (!(material.glue.tensile_strength > 0))
    throw BuildError(label + ": material '" + material.name +
                     "' has no glue (give it bond_tensile_strength and bond_shear_strength)");
  if (d.pieces < 2 || d.pieces > kMaxBondedPieces)
    throw BuildError(label, "pieces", "must be between 2 and " + std::to_string(kMaxBondedPieces));
  if (d.relaxations < 0 || d.relaxations > 100) throw BuildError(label, "relaxations", "must be between 0 and 100");
  for (const Vec3& v : {d.position, d.velocity, d.angular_velocity})
    if (!is_finite(v)) throw BuildError(label + ": position, velocity and angular velocity must be finite");
  const Polytope solid = solid_of(d.shape, settings_.tessellation, label);
  say(label + ": cutting it into " + std::to_string(d.pieces) + " pieces");
  const PolytopeData& s = *solid.data;

  // Sites drawn uniformly inside the solid, then Lloyd's iterations.
  Vec3 lo = s.vertices[0], hi = s.vertices[0];
  for (const Vec3& v : s.vertices) lo = min(lo, v), hi = max(hi, v);
  std::vector<Vec3> sites;
  for (std::uint32_t k = 0; k < d.pieces; ++k) {
    for (int attempt = 0;; ++attempt) {
      if (attempt == kSiteTries)
        throw BuildError(label + ": could not draw " + std::to_string(d.pieces) + " sites inside its shape");
      const std::uint64_t draw = static_cast<std::uint64_t>(attempt) * 3;
      const Vec3 p{lo.x + (hi.x - lo.x) * keyed_uniform(d.seed ^ kSiteKey, k, draw, 0),
                   lo.y + (hi.y - lo.y) * keyed_uniform(d.seed ^ kSiteKey, k, draw + 1, 0),
                   lo.z + (hi.z - lo.z) * keyed_uniform(d.seed ^ kSiteKey, k, draw + 2, 0)};
      if (facet_distance(s, p) < 0) {
        sites.push_back(p);
        break;
      }
    }
  }
  VoronoiCells cells;
  try {
    cells = voronoi_cells(solid, sites);
    for (int r = 0; r < d.relaxations; ++r) {
      for (std::uint32_t k = 0; k < d.pieces; ++k) sites[k] = cells.cells[k].data->centroid;
      cells = voronoi_cells(solid, sites);
    }
  } catch (const std::invalid_argument& e) {
    throw BuildError(label + ": its pieces could not be cut (" + e.what() + "); try another seed");
  }

  // The pieces, as bodies moving with the whole.
  const auto to_world = [&](const Vec3& p) { return d.position + rotate(d.rotation, apply(d.shape.pose, p)); };
  const Vec3 centre = to_world(s.centroid);
  std::vector<std::uint32_t> indices;
  for (std::uint32_t k = 0; k < d.pieces; ++k) {
    BodyDef piece;
    piece.shape = BodyShape{Shape{cells.cells[k]}, d.shape.pose};
    piece.material = d.material;
    piece.position = d.position;
    piece.rotation = d.rotation;
    piece.velocity = d.velocity + cross(d.angular_velocity, to_world(cells.cells[k].data->centroid) - centre);
    piece.angular_velocity = d.angular_velocity;
    piece.label = label + ".piece[" + std::to_string(k) + "]";
    indices.push_back(add_body(piece));
  }
  assemblies_.emplace_back(indices.front(), indices.back() + 1);
  for (const CellFace& f : cells.faces) {
    const Body& a = world_.bodies[indices[f.a]];
    const Body& b = world_.bodies[indices[f.b]];
    const Vec3 normal = rotate(d.rotation, apply_rotation(d.shape.pose, f.normal));
    const Bond bond = glue_bodies(a, b, material, to_world(f.centroid), normal, f.area, f.polar_moment);
    // Bonded pieces do not touch: a bond much softer than the material lets
    // them sink into each other unopposed (a stiffness of 1e-300 flattened
    // an assembly to a third of its height, its pieces overlapping by 3.5%
    // of its volume).
    const Real spacing = length(b.position - a.position);
    const Real least = kMinBondStiffnessRel * material.youngs_modulus / spacing;
    if (!(bond.normal_stiffness >= least && bond.shear_stiffness >= least))
      throw BuildError(label + ": material '" + material.name + "': its bonds (bond_normal_stiffness " +
                       number_text(bond.normal_stiffness) + ", bond_shear_stiffness " + number_text(bond.shear_stiffness) +
                       " Pa/m) are too soft to hold pieces " + number_text(spacing) +
                       " m apart, which do not touch while bonded: give at least " + number_text(least) +
                       " Pa/m (1e-3 of E / spacing), or leave them 0 (E / spacing)");
    world_.bonds.push_back(bond);
  }
  return indices;
}

}  // namespace gjkdem::dem
