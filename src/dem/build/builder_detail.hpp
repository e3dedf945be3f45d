#pragma once
// What the builder's files share (src/dem/build/): the shapes the volume law
// clips, the shapes without volume, and the surface grains meet a convex
// shape by. Private to src/dem/build.
#include <memory>

#include "gjkdem/shape/shape.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem::dem::detail {

/// A solid polytope or box without margin: what the volume law clips.
bool solid_polytope(const Shape& s);

/// Flat cores without a margin: a point, a segment, a triangle, a flat
/// polytope or box. Curved cores and anything with a margin have volume.
bool without_volume(const Shape& s);

/// The closed surface surface grains meet a convex shape of volume by: a
/// solid polytope's hull triangles (a big hull's own, kept with it:
/// hull_surface), a curved shape's inscribed tessellation (throws
/// SurfaceError for a flat one).
std::shared_ptr<const Surface> boundary_surface(const Shape& s, int tessellation);

}  // namespace gjkdem::dem::detail
