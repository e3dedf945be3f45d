#pragma once
// The narrow phase of a step: the geometry of one candidate contact under the
// world's contact model. Penetration depth, normal and witness points by
// GJK/EPA for the Hertz and linear laws; the overlap region (volume, S_A,
// Feng's line of action) for the volume law; plane walls as half-spaces.
#include <span>
#include <vector>

#include "gjkdem/collide/gjk_cache.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/contact_geometry.hpp"
#include "gjkdem/dem/material.hpp"
#include "gjkdem/dem/step_workspace.hpp"

namespace gjkdem::dem {

/// Two placed shapes; `cache` is the pair's warm start.
ContactGeometry body_contact(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                             ContactModel model, GjkCache* cache, OverlapWorkspace& work);

/// A plane wall (a) and a placed shape (b).
ContactGeometry plane_contact(const PlaneWall& wall, const Shape& b, const Transform& pose_b, ContactModel model);

/// Under the penetration laws a body touching several pieces of one wall (the
/// triangles of a mesh, the slabs of a box) gets one contact per cluster of
/// nearby, like-facing contacts: the deepest piece carries it, the others
/// are made inactive.
void merge_wall_contacts(std::span<const Body> bodies, std::span<const ShapeTemplate> templates,
                         std::vector<StepContact>& contacts);

}  // namespace gjkdem::dem
