// What build() checks of a world's start (world_builder.hpp): explicit bodies
// clear of each other, fixed bodies and planes; a periodic cell that holds
// every body; inflows whose regions can insert something.
#include "gjkdem/dem/world_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/contact/half_space.hpp"
#include "gjkdem/dem/surface_contact.hpp"
#include "gjkdem/tolerances.hpp"
#include "number_text.hpp"

namespace gjkdem::dem {

using detail::number_text;

namespace {

// How deep a part of body a and a part of body b overlap at the start, by
// their route (pair_route): a surface's or a shell's triangles and a mesh
// wall's piece by the margin model; a shell and another part by the shell's
// patches; two parts by their surfaces' patches (infinite: one wholly inside
// the other), or by their penetration where neither has a surface (a world
// without surfaces) or one is a mesh wall's piece; 0 where one part has no
// surface to meet the other's by (no volume: the run reports the pair).
Real start_overlap(std::span<const ShapeTemplate> templates, const Body& a, std::uint32_t pa, const Body& b,
                   std::uint32_t pb, SurfaceScratch& scratch, std::vector<SurfacePatchContact>& patches,
                   std::vector<std::uint32_t>& hosts) {
  const ShapeTemplate &ta = templates[a.shape], &tb = templates[b.shape];
  const PartPose at_a = part_pose(ta, a, pa), at_b = part_pose(tb, b, pb);
  const PartKind ka = part_kind(ta, pa), kb = part_kind(tb, pb);
  patches.clear();
  switch (pair_route(ka, kb)) {
    case ContactRoute::Margin: {
      const bool piece_is_a = ka == PartKind::WallPiece;
      const MarginTriangle piece = placed_margin_triangle(piece_is_a ? ta : tb, (piece_is_a ? at_a : at_b).pose);
      margin_patches(margin_triangles(piece_is_a ? tb : ta, piece_is_a ? pb : pa), (piece_is_a ? at_b : at_a).pose,
                     {&piece, 1}, scratch, patches, hosts);
      break;
    }
    case ContactRoute::Shell: {
      const bool shell_is_a = ka == PartKind::Shell;
      const ShapeTemplate &shell = shell_is_a ? ta : tb, &other = shell_is_a ? tb : ta;
      const PartPose &at_shell = shell_is_a ? at_a : at_b, &body = shell_is_a ? at_b : at_a;
      if (shell_patches(shell, at_shell.pose, other, shell_is_a ? pb : pa, body, shell_is_a, scratch, patches) ==
          GeometryStatus::Unsupported)
        return 0;  // the run reports the pair
      break;
    }
    case ContactRoute::Patches:
    case ContactRoute::Convex: {
      if (ka == PartKind::WallPiece || kb == PartKind::WallPiece) {  // a convex part and a piece
        const PartPose &piece = ka == PartKind::WallPiece ? at_a : at_b, &body = ka == PartKind::WallPiece ? at_b : at_a;
        const PenetrationResult pr = penetration(*body.shape, body.pose, *piece.shape, piece.pose);
        return pr.intersect ? pr.depth : 0;
      }
      const std::shared_ptr<const Surface>&sa = surface_of(ta, pa), &sb = surface_of(tb, pb);
      if (!sa && !sb) {  // convex parts (a world without surfaces): their penetration
        const PenetrationResult pr = penetration(*at_a.shape, at_a.pose, *at_b.shape, at_b.pose);
        return pr.intersect ? pr.depth : 0;
      }
      if (!sa || !sb) return 0;
      if (surface_patches(sa, at_a.pose, sb, at_b.pose, scratch, patches) !=
          GeometryStatus::Touching)
        return std::numeric_limits<Real>::infinity();
      break;
    }
  }
  Real depth = 0;
  for (const SurfacePatchContact& p : patches) depth = std::fmax(depth, p.geometry.depth);
  return depth;
}

}  // namespace

// Explicit bodies must not overlap each other, fixed bodies or planes
// (touching is fine: stacks start touching). Generated bodies are placed
// clear of everything added before them.
void WorldBuilder::check_explicit_bodies() const {
  const World& w = world_;
  if (!check_overlaps_ || explicit_.empty()) return;
  std::vector<bool> is_explicit(w.bodies.size(), false);
  for (std::uint32_t i : explicit_) is_explicit[i] = true;
  std::vector<std::uint32_t> assembly(w.bodies.size(), 0);  // 1 + a bonded assembly's index, 0 for none
  for (std::size_t k = 0; k < assemblies_.size(); ++k)
    for (std::uint32_t i = assemblies_[k].first; i < assemblies_[k].second; ++i) assembly[i] = static_cast<std::uint32_t>(k + 1);
  std::vector<Transform> poses(w.bodies.size());
  std::vector<Aabb> boxes(w.bodies.size());  // of bounding spheres
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    poses[i] = shape_pose(w.templates[w.bodies[i].shape], w.bodies[i]);
    const Real r = bounding_radius(given_shapes_[w.bodies[i].shape]);
    boxes[i] = {poses[i].translation - Vec3{r, r, r}, poses[i].translation + Vec3{r, r, r}};
  }
  for (std::uint32_t i : explicit_) {
    const Body& a = w.bodies[i];
    const Shape& sa = given_shapes_[a.shape];
    const Real tol = kStartOverlapRelTol * bounding_radius(sa);
    for (const PlaneWall& p : w.planes)
      if (!a.fixed && half_space_contact(sa, poses[i], p.point, p.normal).depth > tol)
        throw BuildError(labels_[i] + " starts inside a plane wall (point " + number_text(p.point.x) + ", " +
                             number_text(p.point.y) + ", " + number_text(p.point.z) + ")",
                         {i});
  }
  SweepWorkspace sweep;
  std::vector<BodyPair> pairs;
  overlapping_pairs(boxes, sweep, pairs);
  SurfaceScratch surface_scratch;
  std::vector<SurfacePatchContact> patches;
  std::vector<std::uint32_t> hosts;
  for (const auto& [i, j] : pairs) {  // i < j; reported as the explicit one of smaller index first
    if (!is_explicit[i] && !is_explicit[j]) continue;
    if (assembly[i] != 0 && assembly[i] == assembly[j]) continue;  // cells of one solid: they tile it (voronoi.hpp)
    const Body& a = w.bodies[i];
    const Body& b = w.bodies[j];
    if (a.fixed && b.fixed) continue;
    const Shape& sa = given_shapes_[a.shape];
    const Shape& sb = given_shapes_[b.shape];
    const Real tol = kStartOverlapRelTol * bounding_radius(is_explicit[i] ? sa : sb);
    const ShapeTemplate &ta = w.templates[a.shape], &tb = w.templates[b.shape];
    Real depth = 0;
    // Part by part (a compound's hull is not its solid), surfaces by their
    // patches (hooked rings' hulls overlap).
    if (holds_surface(ta) || holds_surface(tb) || !ta.parts.empty() || !tb.parts.empty()) {
      const std::size_t a_parts = std::max<std::size_t>(ta.parts.size(), 1), b_parts = std::max<std::size_t>(tb.parts.size(), 1);
      for (std::uint32_t pa = 0; pa < a_parts; ++pa)
        for (std::uint32_t pb = 0; pb < b_parts; ++pb)
          depth = std::fmax(depth, start_overlap(w.templates, a, pa, b, pb, surface_scratch, patches, hosts));
    } else {
      const PenetrationResult pr = penetration(sa, poses[i], sb, poses[j]);
      if (pr.intersect) depth = pr.depth;
    }
    if (depth > tol) {
      const std::uint32_t first = is_explicit[i] ? i : j, second = first == i ? j : i;
      if (std::isinf(depth))
        throw BuildError(labels_[first] + " and " + labels_[second] +
                             " start one wholly inside or through the other (their overlap has no contact area)",
                         {first, second});
      throw BuildError(labels_[first] + " overlaps " + labels_[second] + " by " + number_text(depth) +
                           " m at the start",
                       {first, second});
    }
  }
}

// A periodic cell must hold every body with room to spare: a pair may meet
// through one image only. Moving bodies start inside it. (What the cell and
// its control must be alone: check_cell, in the constructor.)
void WorldBuilder::check_periodic_cell() {
  const PeriodicCell& cell = settings_.periodic;
  const CellControl& control = settings_.cell_control;
  const char* names[3] = {"x", "y", "z"};
  if (!continued_) world_.cell.now = cell, world_.cell.rate = {}, world_.cell.stress = {};
  if (!cell.active()) return;
  for (int a = 0; a < 3; ++a) {
    if (!cell.axes[a]) continue;
    const Real need = shortest_period(world_), length = cell_width(world_.cell.now, a);
    if (!(length > need))
      throw BuildError(std::string("the periodic cell is ") + number_text(length) + " m wide across " +
                       names[a] + ": it must exceed four times the largest body's reach (" + number_text(need) + " m)");
  }
  // A fixed body (a wall piece) about as long as the period could meet a
  // body directly and through its image at once; a pair keeps one image, so
  // the contact would jump between the two. Refuse it: such a wall must be
  // cut along the periodic axis (a mesh with more segments there).
  const Real two_reaches = shortest_period(world_) / 2;
  for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
    const Body& b = world_.bodies[i];
    if (!b.fixed) continue;
    const Aabb box = aabb(given_shapes_[b.shape], shape_pose(world_.templates[b.shape], b));
    for (int a = 0; a < 3; ++a) {
      const Real period = world_.cell.now.hi[a] - world_.cell.now.lo[a], extent = box.hi[a] - box.lo[a];
      if (cell.axes[a] && extent > period - two_reaches)
        throw BuildError(labels_[i] + " spans " + number_text(extent) + " m along the periodic axis " + names[a] +
                             ", more than the period less two of the largest body's reach (" +
                             number_text(period - two_reaches) +
                             " m): a body could touch it directly and through its image at once. Cut it along " +
                             names[a] + " (a mesh with more segments there)",
                         {static_cast<std::uint32_t>(i)});
    }
  }
  world_.settings.periodic = cell;
  world_.settings.cell_control = control;
  const Makeup makeup{world_.templates, world_.materials};
  wrap_bodies(world_.cell.now, world_.cell.rate, world_.search.boxes, {world_.bodies, &makeup, nullptr, &world_.wall_work});
}

// An inflow whose region lies wholly beyond a plane wall that never moves,
// or inside a fixed body that never moves, could never insert a body: the
// run would say nothing and insert nothing.
void WorldBuilder::check_inflow_regions() const {
  for (std::size_t k = 0; k < world_.inflows.size(); ++k) {
    const Inflow& f = world_.inflows[k];
    const std::string& label = k < inflow_labels_.size() ? inflow_labels_[k] : "an inflow";
    Vec3 corners[8];
    for (int c = 0; c < 8; ++c)
      corners[c] = {c & 1 ? f.hi.x : f.lo.x, c & 2 ? f.hi.y : f.lo.y, c & 4 ? f.hi.z : f.lo.z};
    for (const PlaneWall& p : world_.planes) {
      if (p.motion != 0) continue;
      bool beyond = true;
      for (const Vec3& c : corners) beyond = beyond && dot(c - p.point, p.normal) < 0;
      if (beyond)
        throw BuildError(label + ": its region lies wholly beyond the plane wall with id " + std::to_string(p.id) +
                         ": no body could ever be inserted there");
    }
    for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
      const Body& b = world_.bodies[i];
      // (A compound's given shape is its hull: a hopper of parts holds room
      // inside. A surface grain's solid is its surface's: a bowl's hollow is
      // free. A shell has no inside.)
      const ShapeTemplate& t = world_.templates[b.shape];
      if (!b.fixed || b.motion != 0 || !t.parts.empty() || t.shell) continue;
      const Shape& shape = given_shapes_[b.shape];
      const Transform pose = shape_pose(t, b);
      bool inside = true;
      for (const Vec3& c : corners)
        inside = inside && (t.surface_grain ? winding_number(t.surface->vertices, t.surface->triangles,
                                                             apply_inverse(pose, c)) > 0.5
                                            : intersect(Shape{Point{}}, Transform::from(c, Quat{}), shape, pose));
      if (inside)
        throw BuildError(label + ": its region lies wholly inside " + labels_[i] +
                         ": no body could ever be inserted there", {static_cast<std::uint32_t>(i)});
    }
  }
}

}  // namespace gjkdem::dem
