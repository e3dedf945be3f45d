// A moving body gone through a mesh wall: its centre crossed a piece's
// triangle in one step. A mesh wall is thin, and its contact pushes a body
// away from the nearer face: past the middle, on through. (A plane wall's
// counterpart is the narrow phase's GeometryStatus::Through.)
#include "step/stages.hpp"

namespace gjkdem::dem::detail {
namespace {

// Does the segment p -> q cross triangle (a, b, c), from one side strictly
// to the other side or onto it?
bool crosses(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const Real sp = dot(p - a, n), sq = dot(q - a, n);
  if (sp == 0 || (sp > 0 ? sq > 0 : sq < 0)) return false;
  const Vec3 x = p + (q - p) * (sp / (sp - sq));
  return dot(cross(b - a, x - a), n) >= 0 && dot(cross(c - b, x - b), n) >= 0 && dot(cross(a - c, x - c), n) >= 0;
}

}  // namespace

StepReport find_wall_crossing(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                              std::span<const MotionFrame> motion_frames, const PeriodicCell& cell,
                              std::span<const StepContact> contacts, Real dt) {
  if (!(dt > 0)) return {};
  for (const StepContact& c : contacts) {
    if (c.a_is_plane) continue;
    const Body& a = bodies[c.a];
    const Body& b = bodies[c.b];
    const bool piece_is_a = templates[a.shape].wall_face && !b.fixed;
    if (!piece_is_a && !(templates[b.shape].wall_face && !a.fixed)) continue;
    const Body& piece = piece_is_a ? a : b;
    const Body& mover = piece_is_a ? b : a;
    // The contact's image shift moves b: take the mover into the piece's image.
    const Vec3 shift = image_shift_of(cell, c);
    const Vec3 x = mover.position + (piece_is_a ? shift : -shift);
    Vec3 velocity = mover.velocity;
    if (piece.motion) velocity -= point_velocity(motion_frames[piece.motion - 1], x);
    const Transform pose = part_pose(templates[piece.shape], piece, 0).pose;
    const Triangle& face = *templates[piece.shape].wall_face;
    if (crosses(x - velocity * dt, x, apply(pose, face.v[0]), apply(pose, face.v[1]), apply(pose, face.v[2])))
      return {StepStatus::ThroughWall, piece.id, mover.id};
  }
  return {};
}

}  // namespace gjkdem::dem::detail
