#pragma once
// Triangle meshes from OBJ and STL (ASCII and binary) files, and their use as
// convex particle shapes. An I/O boundary: every problem is reported with the
// file name (and line, for text formats) as a MeshError.
#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjkdem/shape/polytope.hpp"

namespace gjkdem::io {

struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct TriangleMesh {
  std::vector<Vec3> vertices;                          ///< positions (STL corners welded when equal)
  std::vector<std::array<std::uint32_t, 3>> triangles; ///< indices into vertices
  /// Where each object's triangles start (OBJ `o` and `g` lines begin objects,
  /// as convex-decomposition tools write them); {0} for one object.
  std::vector<std::size_t> object_begin{0};
  /// The first OBJ polygon face that could not be cut into triangles inside
  /// itself (no area, or crossing itself): "FILE: line N: why". It was
  /// fanned from its first corner instead, which a convex hull does not mind
  /// but a surface, a shell or a mesh wall would take as its triangles
  /// (refuse_uncut_polygons). "" when none.
  std::string uncut_polygon;
};

/// Throws MeshError(mesh.uncut_polygon) when a polygon face could not be
/// cut: for the readers that take the mesh's triangles as they are.
void refuse_uncut_polygons(const TriangleMesh& mesh);

/// Reads .obj or .stl (by extension, case-insensitive; STL ASCII or binary by
/// content). Throws MeshError for a missing, unreadable, malformed or empty
/// file, a non-finite coordinate, something other than a regular file (a
/// directory, a FIFO, a device) or a file above 1 GiB.
TriangleMesh read_mesh(const std::filesystem::path& file);

/// Every edge shared by exactly two triangles, oppositely oriented: the mesh
/// bounds a solid.
bool is_watertight(const TriangleMesh& mesh);

/// How many times the mesh winds about p: the triangles' solid angles seen
/// from p over 4 pi. For a watertight mesh, 1 inside (-1 when its triangles
/// face inward) and 0 outside; near the surface in between.
Real winding_number(const TriangleMesh& mesh, const Vec3& p);

struct ConvexMesh {
  Polytope polytope;                  ///< the convex hull of the mesh's vertices
  bool watertight = false;            ///< every edge shared by exactly two triangles, oppositely oriented
  bool convex = false;                ///< watertight and enclosing the same volume as its hull
  std::vector<std::string> warnings;  ///< what was changed, and why, naming the file
};

/// The mesh as a convex particle: its convex hull, with a warning when the mesh
/// was not convex or not watertight (the warning of a mesh of one object
/// points to compounds). Throws MeshError when the mesh is flat (no volume).
/// `name` is used in messages (usually the file name).
ConvexMesh convex_from_mesh(const TriangleMesh& mesh, const std::string& name);

/// Each object of the mesh as a convex part of a compound (convex_from_mesh
/// of its triangles; parts named "name, object k" in messages).
std::vector<ConvexMesh> convex_parts_from_mesh(const TriangleMesh& mesh, const std::string& name);

}  // namespace gjkdem::io
