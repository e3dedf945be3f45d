#pragma once
// A thin shell: a triangle surface, open or closed (a triangle soup: a
// scoop, a plate, a tray), with a thickness. Each triangle is the seed's
// triangle with a margin rho = thickness / 2 (contact/surface_margin.hpp),
// and the shell is a rigid body of its own: what a mesh wall is, moving
// freely. Made once per template by make_shell, with a tree of its
// triangles' boxes (grown by the margin), all in its own frame.
#include <stdexcept>
#include <vector>

#include "gjkdem/shape/box_tree.hpp"
#include "gjkdem/shape/mass_properties.hpp"
#include "gjkdem/shape/surface.hpp"

namespace gjkdem {

struct Shell {
  std::vector<Vec3> vertices;
  std::vector<TriangleIndices> triangles;
  std::vector<Aabb> triangle_boxes;  ///< each grown by the margin
  BoxTree tree;                      ///< of triangle_boxes, ids the triangles
  Real margin = 0;                   ///< rho: half the thickness
  Real area = 0;                     ///< of the triangles (one side)
  MassProperties mass;               ///< of its plates, per unit density (mass_properties)
};

/// A shell that breaks a rule: the message names the triangle or vertex.
struct ShellError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// Checks the shell (finite vertices, at least one triangle, indices in
/// range, no triangle without area, a finite thickness > 0) and builds its
/// tree; vertices no triangle uses are dropped (the others keep their
/// order). Throws ShellError.
Shell make_shell(std::vector<Vec3> vertices, std::vector<TriangleIndices> triangles, Real thickness);

/// Volume, centroid and inertia (per unit density) of the shell as its
/// triangles' plates of its thickness, each centred on its triangle: exact
/// for one flat piece (a plate is the box it is), the plates' overlaps and
/// gaps at creases left out (of order thickness^2 per unit of crease).
MassProperties mass_properties(const Shell& shell);

}  // namespace gjkdem
