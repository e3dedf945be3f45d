#pragma once
// Generators' bodies outside the container that holds the others (the scene
// reader's warning): a generator's bodies split by a closed mesh wall, some
// inside and some outside, are mostly a region drawn past a container's side
// (a box region in a drum), and those outside fall away for the whole run.
// Said as a warning, since a closed mesh may also be an obstacle bodies
// surround. Internal to src/io.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gjkdem/io/mesh.hpp"
#include "gjkdem/shape/aabb.hpp"

namespace gjkdem::io::detail {

/// A scene's mesh wall, where the scene puts it.
struct ContainerWall {
  std::string label;           ///< the wall's table and file
  TriangleMesh mesh;
  Aabb box;
  std::optional<bool> closed;  ///< watertight, once asked
};

/// Triangles times bodies a check may visit (about a second); past it a wall is not checked.
inline constexpr double kMaxContainmentWork = 2e7;

/// A warning per closed wall holding some of `who`'s bodies (at `positions`)
/// but not all. Asks each wall whether it is closed once, when first needed.
std::vector<std::string> bodies_outside_containers(std::vector<ContainerWall>& walls, const std::string& who,
                                                   std::span<const Vec3> positions);

}  // namespace gjkdem::io::detail
