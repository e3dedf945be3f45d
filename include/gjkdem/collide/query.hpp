#pragma once
// Narrow-phase queries between two placed convex shapes: the boolean overlap
// test, distance with witness points, and penetration (depth, normal, witness
// points) by GJK then EPA.
//
// Conventions (docs/conventions.md): every output is in world coordinates; the
// normal is a unit vector pointing from A towards B. Separated: witness_b -
// witness_a = distance * normal. Intersecting: witness_a - witness_b = depth *
// normal, where witness_a is A's deepest point inside B and translating B by
// depth * normal leaves the shapes just touching. Touching counts as
// intersecting. Margins are handled exactly (see shape.hpp).
#include "gjkdem/collide/gjk_cache.hpp"
#include "gjkdem/collide/settings.hpp"
#include "gjkdem/collide/status.hpp"
#include "gjkdem/shape/shape.hpp"

namespace gjkdem {

struct DistanceResult {
  bool intersect = false;   ///< shapes share a point (distance 0, witnesses unset)
  Real distance = 0;        ///< >= 0
  Vec3 witness_a;           ///< closest point on A (world)
  Vec3 witness_b;           ///< closest point on B (world)
  Vec3 normal;              ///< unit, A -> B; zero when intersecting
  GjkStatus status = GjkStatus::Separated;
  int iterations = 0;       ///< GJK iterations
};

struct PenetrationResult {
  bool intersect = false;   ///< shapes share a point
  Real distance = 0;        ///< >= 0; 0 when intersecting
  Real depth = 0;           ///< >= 0; 0 when separated
  Vec3 witness_a;           ///< closest (separated) or deepest (intersecting) point of A, world
  Vec3 witness_b;           ///< same for B
  Vec3 normal;              ///< unit, A -> B
  GjkStatus gjk_status = GjkStatus::Separated;
  EpaStatus epa_status = EpaStatus::NotRun;
  int iterations = 0;       ///< GJK iterations
  int epa_iterations = 0;   ///< EPA expansions
};

/// True when A and B share at least one point. Stops as soon as a separating
/// plane (or an enclosing simplex) is found: the seed's Algorithm 14.
bool intersect(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
               GjkCache* cache = nullptr, const QuerySettings& settings = {}) noexcept;

/// Distance and closest points; stops at intersection without computing depth.
DistanceResult distance(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                        GjkCache* cache = nullptr, const QuerySettings& settings = {}) noexcept;

/// Full query: distance when separated, depth and normal (EPA) when intersecting.
PenetrationResult penetration(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                              GjkCache* cache = nullptr, const QuerySettings& settings = {}) noexcept;

/// How A and B overlap, against a depth (a length >= 0): apart (no common
/// point), within it (touching, or a penetration depth of at most `depth`),
/// or beyond it. As penetration() would say, but a deep overlap is proved by
/// the overlap test's last simplex (or, with margins, by the test on shrunk
/// margins), without EPA.
enum class DepthClass { Apart, Within, Beyond };
DepthClass classify_depth(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b, Real depth,
                          const QuerySettings& settings = {}) noexcept;

}  // namespace gjkdem
