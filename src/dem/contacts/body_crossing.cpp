// Two bodies passing through each other: a deep point of one inside the
// other. A convex body's centre lies inside it, beyond the reach of any
// shallow contact; once it is inside the other body the overlap is deeper
// than the body is thick there, and the contact (whose normal follows the
// shallowest way out) pushes the two on through, not apart. The normal
// itself cannot tell: two spheres passing through each other keep a normal
// along their centres, which flips as they pass. A surface grain's centre
// may lie outside it (a torus, a U): its deep points (shape/deep_points.hpp)
// stand for it, and its patches' overlaps are summed per piece, so a patch
// deep enough to reach one has each side's points tested against the other.
// (Mesh walls have their own check: wall_crossing.cpp.)
#include "gjkdem/collide/query.hpp"
#include "gjkdem/shape/deep_points.hpp"
#include "gjkdem/tolerances.hpp"
#include "step/stages.hpp"

namespace gjkdem::dem::detail {
namespace {

// One convex solid, its centre inside it: not a compound (its centre may
// lie between its parts), a surface grain (non-convex), a shell or a wall's
// piece.
bool convex_solid(const ShapeTemplate& t) noexcept {
  return t.parts.empty() && !t.wall_face && part_kind(t, 0) == PartKind::Convex;
}

// Whether p (world frame) lies in the solid of template `t` posed at `pose`.
bool inside(const ShapeTemplate& t, const Transform& pose, const Vec3& p) {
  if (t.surface_grain) {
    const Surface& s = *t.surface;
    return winding_number(s.vertices, s.triangles, apply_inverse(pose, p)) > 0.5;
  }
  return intersect(Shape{Point{}}, Transform::from(p, Quat{}), t.shape, pose);
}

// Whether a patch as deep as `depth` (its volume over its area) has reached
// a deep point of body `body` that lies inside `other` (at `other_pose`): a
// surface grain's deep points once the patch passes kDeepReachRel of the
// shallowest, a convex solid's centre once it passes kDeepOverlapRel of its
// radius of curvature (as between two convex bodies); nothing for
// compounds, shells and wall pieces.
bool reached(const ShapeTemplate& t, const Body& body, Real depth, const ShapeTemplate& other,
             const Transform& other_pose) {
  if (t.surface_grain && t.parts.empty()) {
    // The points are made once a patch is deep enough to reach some.
    DeepPointsSlot* slot = t.surface->deep.get();
    if (!slot || !(depth > slot->reach_bound)) return false;
    const std::vector<DeepPoint>& deep = deep_points(*t.surface, *slot);
    if (deep.empty() || !(depth > kDeepReachRel * deep.back().depth)) return false;
    const Transform pose = part_pose(t, body, 0).pose;
    for (const DeepPoint& d : deep)
      if (inside(other, other_pose, apply(pose, d.point))) return true;
    return false;
  }
  return convex_solid(t) && depth > kDeepOverlapRel * t.curvature_radius && inside(other, other_pose, body.position);
}

// Whether `t` at `pose` can hold a point inside: a whole surface grain or a
// convex solid.
bool solid(const ShapeTemplate& t) noexcept { return (t.surface_grain && t.parts.empty()) || convex_solid(t); }

// A patch between two bodies, one a surface grain: a deep point of either
// inside the other.
bool surface_pair_crossing(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                           const PeriodicCell& cell, const StepContact& c) {
  const Body &a = bodies[c.a], &b = bodies[c.b];
  const ShapeTemplate &ta = templates[a.shape], &tb = templates[b.shape];
  if (!(ta.surface_grain || tb.surface_grain) || !solid(ta) || !solid(tb)) return false;
  const Vec3 shift = image_shift_of(cell, c);  // b at its image
  const Real depth = c.geometry.depth;
  Transform pose_a = part_pose(ta, a, 0).pose, pose_b = part_pose(tb, b, 0).pose;
  pose_b.translation += shift;
  if (reached(ta, a, depth, tb, pose_b)) return true;
  pose_a.translation -= shift;  // a seen from b's image
  return reached(tb, b, depth, ta, pose_a);
}

}  // namespace

StepReport find_body_crossing(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                              const PeriodicCell& cell, std::span<const StepContact> contacts) {
  for (const StepContact& c : contacts) {
    if (!c.active || c.a_is_plane) continue;
    if (c.surface) {
      if (surface_pair_crossing(bodies, templates, cell, c)) return {StepStatus::ThroughBody, bodies[c.a].id, bodies[c.b].id};
      continue;
    }
    const Body &a = bodies[c.a], &b = bodies[c.b];
    const ShapeTemplate &ta = templates[a.shape], &tb = templates[b.shape];
    if (!convex_solid(ta) || !convex_solid(tb)) continue;
    // Shallow contacts (all but the deepest few) need no test.
    if (!(c.geometry.depth > kDeepOverlapRel * std::fmin(ta.curvature_radius, tb.curvature_radius))) continue;
    const Vec3 shift = image_shift_of(cell, c);  // b at its image
    const Transform pose_a = part_pose(ta, a, 0).pose;
    Transform pose_b = part_pose(tb, b, 0).pose;
    pose_b.translation += shift;
    if (inside(ta, pose_a, b.position + shift) || inside(tb, pose_b, a.position))
      return {StepStatus::ThroughBody, a.id, b.id};
  }
  return {};
}

}  // namespace gjkdem::dem::detail
