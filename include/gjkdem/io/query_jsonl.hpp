#pragma once
// Reading and writing the pair-query format (../shared/spec/query-format.md):
// one JSON object per line in, one per line out. This is an I/O boundary: it
// validates everything and throws QueryFormatError with a message that names
// the field at fault; the CLI adds the line number.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include <memory>

#include "gjkdem/collide/query.hpp"
#include "gjkdem/collide/surface_distance.hpp"
#include "gjkdem/contact/surface_overlap.hpp"

namespace gjkdem::io {

struct QueryFormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A shape read from the format: shapes are given in world coordinates, so the
/// reader moves each core to a local frame centred on the shape (small local
/// coordinates keep round-off low at large offsets) and returns the pose.
struct PlacedInput {
  Shape shape;
  Transform pose;
  /// A `mesh` (query-format-mesh.md): its checked surface, in world
  /// coordinates (`shape` and `pose` unused); null for the convex shapes.
  std::shared_ptr<const Surface> surface;
};

struct PairInput {
  std::string id_json = "null";  ///< the input's id, re-serialised as JSON
  PlacedInput a, b;
};

/// Parses one input line (already known not to be blank or a comment).
/// On failure throws QueryFormatError; `id_json` receives the id when readable.
PairInput parse_pair(std::string_view line, std::string& id_json);

/// Input nesting arrays and objects deeper than this is refused (by every
/// reader of the format: the text, and Python's lists and dicts).
inline constexpr int kMaxJsonDepth = 64;

/// A query line longer than this (bytes) is refused unread: parsing costs
/// about 20 times a line's size in memory, and this still holds a mesh of a
/// million triangles (about 55 MB written with full precision).
inline constexpr std::size_t kMaxLineBytes = std::size_t{64} << 20;

/// Where a SHAPE object's coordinates are: in the world (the query format:
/// every shape placed by its fields), or in its own frame (scenes and
/// Python), where a shape placed by a "center" is centred on the origin
/// when it gives none (polytopes, triangles and capsules are placed by
/// their points).
enum class ShapeFrame { World, Own };

/// Parses one SHAPE object given as JSON text (a convex shape: a `mesh` is
/// refused, as it is a surface, read only in pairs).
PlacedInput parse_shape(std::string_view json_text, ShapeFrame frame = ShapeFrame::World);

/// Optional volume-based fields; absent ones are written as null.
struct OverlapFields {
  bool computed = false;
  Real volume = 0;
  bool has_centroid = false;
  Vec3 centroid;
  bool has_normal = false;
  Vec3 contact_normal;
};

/// One result line (no trailing newline). An answer that is not finite
/// throws std::range_error (JSON has no nan or inf): the caller writes an
/// error line for it.
std::string format_result(const std::string& id_json, const PenetrationResult& r, const OverlapFields& overlap = {});

/// One result line of a pair of meshes: `distance` of separated solids
/// (null when they intersect), the overlap otherwise. Depth and normal are
/// null (not defined for meshes in this version); `smaller_volume` is the
/// smaller solid's, for piece_meeting (a piece that is that solid whole, or
/// where the surfaces coincide, has no normal). Throws std::range_error as
/// format_result does.
std::string format_surface_result(const std::string& id_json, const SurfaceOverlap& overlap,
                                  const SurfaceDistance* distance, Real smaller_volume);

/// One error line (no trailing newline).
std::string format_error(const std::string& id_json, const std::string& message);

/// True for lines the format skips: blank or starting with '#'.
bool is_skipped_line(std::string_view line);

}  // namespace gjkdem::io
