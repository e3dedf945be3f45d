#pragma once
// Where a big polytope keeps its boundary surface (PolytopeData::surface_slot):
// made once, on the first call of hull_surface (surface.hpp), by whichever
// thread asks first. A DEM world asks as it is built (dem::make_hull_surface),
// so its steps never make one; a lone query makes it on first use. Private to
// the shape library and the polytope's block.
#include <memory>
#include <mutex>

namespace gjkdem {

struct Surface;

struct HullSurfaceSlot {
  std::once_flag made;
  std::shared_ptr<const Surface> surface;  ///< null when the hull's triangles make no valid surface
};

}  // namespace gjkdem
