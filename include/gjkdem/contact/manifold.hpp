#pragma once
// Multi-point contact manifolds for face-face and edge-face contacts between
// polytope-like shapes (polytopes and boxes), and the clustering filter that
// merges redundant contacts of one pair (the seed's post-processing step; for a
// particle against a triangulated wall, the contacts found triangle by
// triangle).
//
// The manifold follows the usual reference/incident-face clipping (e.g.
// Ericson, Real-Time Collision Detection, and Box2D's polygon manifolds): the
// face best aligned with the contact normal is the reference, the other body's
// most anti-aligned face the incident face; the incident polygon is clipped by
// the reference face's side planes, points above the reference plane dropped,
// and at most four points kept, those spanning the largest area.
#include <span>
#include <vector>

#include "gjkdem/collide/query.hpp"

namespace gjkdem {

struct ContactPoint {
  Vec3 point;    ///< world: midway between the two surfaces
  Vec3 normal;   ///< unit, A -> B
  Real depth;    ///< > 0 penetrating, < 0 separated (speculative)
};

struct ContactManifold {
  int count = 0;            ///< 0 to 4
  ContactPoint points[4];
};

/// Manifold for a pair in contact, given the pair's penetration() answer.
/// Shapes that are not polytope-like, or poorly aligned faces (edge-edge,
/// vertex contacts), give a single point at the witnesses' midpoint.
ContactManifold contact_manifold(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                                 const PenetrationResult& contact) noexcept;

/// Merges contacts lying within `merge_distance` of a cluster's first contact
/// and whose normals agree with the cluster's within `merge_cos`. A cluster
/// keeps its deepest contact's normal and depth; its point is the mean of its
/// points weighted by depth (the plain mean when none penetrates). Clusters come
/// out in the order of their first contacts. When `cluster_of` is given it
/// receives, for each input contact, the index of the cluster it joined.
std::vector<ContactPoint> cluster_contacts(std::span<const ContactPoint> contacts, Real merge_distance,
                                           Real merge_cos = kContactMergeCos, std::vector<int>* cluster_of = nullptr);

}  // namespace gjkdem
