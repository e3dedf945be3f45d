// Two convex bodies passing through each other: a body's centre inside the
// other. A convex body's centre lies inside it, beyond the reach of any
// shallow contact; once it is inside the other body the overlap is deeper
// than the body is thick there, and the contact (whose normal follows the
// shallowest way out) pushes the two on through, not apart. The normal
// itself cannot tell: two spheres passing through each other keep a normal
// along their centres, which flips as they pass. (Mesh walls have their own
// check: wall_crossing.cpp.)
#include "gjkdem/collide/query.hpp"
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

}  // namespace

StepReport find_body_crossing(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                              const PeriodicCell& cell, std::span<const StepContact> contacts) {
  for (const StepContact& c : contacts) {
    if (!c.active || c.a_is_plane || c.surface) continue;
    const Body &a = bodies[c.a], &b = bodies[c.b];
    const ShapeTemplate &ta = templates[a.shape], &tb = templates[b.shape];
    if (!convex_solid(ta) || !convex_solid(tb)) continue;
    // Shallow contacts (all but the deepest few) need no test.
    if (!(c.geometry.depth > kDeepOverlapRel * std::fmin(ta.curvature_radius, tb.curvature_radius))) continue;
    const Vec3 shift = image_shift_of(cell, c);  // b at its image
    const PartPose pa = part_pose(ta, a, 0);
    PartPose pb = part_pose(tb, b, 0);
    pb.pose.translation += shift;
    const Shape centre{Point{}};
    if (intersect(centre, Transform::from(b.position + shift, Quat{}), *pa.shape, pa.pose) ||
        intersect(centre, Transform::from(a.position, Quat{}), *pb.shape, pb.pose))
      return {StepStatus::ThroughBody, a.id, b.id};
  }
  return {};
}

}  // namespace gjkdem::dem::detail
