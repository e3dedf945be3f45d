#pragma once
// The view format (docs/view-format.md): a run's frames in compact binary,
// for the browser viewer (`gjkdem view`), the measurements (`gjkdem analyze`)
// and Python. The templates' surfaces are written once (view/shapes.bin);
// a frame holds the bodies' poses and velocities and the touching contacts
// in single precision, about 61 bytes per body and 44 per contact.
#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::io {

inline constexpr std::uint32_t kViewVersion = 4;
/// The oldest version readers take (version 2 frames hold no bonds, 3 no
/// channel block).
inline constexpr std::uint32_t kOldestViewVersion = 2;
/// A contact's first side with this bit set is plane wall (side - kViewPlaneSide).
inline constexpr std::uint32_t kViewPlaneSide = 0x80000000u;
inline constexpr std::uint8_t kViewFixed = 1, kViewDriven = 2;

struct ViewFormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A template's surface in the body's frame.
struct ViewMesh {
  std::vector<float> vertices;          ///< x, y, z per vertex
  std::vector<std::uint32_t> triangles; ///< three vertex indices each, counter-clockwise from outside
};

struct ViewShapes {
  std::vector<ViewMesh> templates;
  std::vector<std::uint32_t> plane_ids;
};

/// A body channel of a frame's channel block (version 4): the framed rows
/// of dem::kBodyChannels present in the world, `components` values a body.
struct ViewChannel {
  std::string name;
  std::string unit;  ///< SI, as the table gives it (printable ASCII)
  std::uint32_t components = 0;
  std::vector<float> values;  ///< components per body, in the frame's body order
};

/// One frame, arrays as stored (structure of arrays, single precision).
struct ViewFrame {
  double time = 0;
  std::uint64_t step = 0;
  std::vector<float> positions, orientations, velocities, angular_velocities;  ///< 3, 4 (w x y z), 3, 3 per body
  std::vector<std::uint32_t> templates, ids;
  std::vector<std::uint8_t> flags;
  std::vector<std::uint32_t> contact_a, contact_b;           ///< first side (or kViewPlaneSide + plane), second body
  std::vector<float> contact_points, contact_normals, contact_forces;  ///< 3 per contact; forces on the second body
  std::vector<float> plane_points, plane_normals;           ///< 3 per plane wall
  /// The periodic cell now (version 2): axes bit 0 x, 1 y, 2 z (0: none),
  /// lo, hi and tilts xy, xz, yz.
  std::uint32_t cell_axes = 0;
  std::array<float, 9> cell{};
  /// The bonds of bonded assemblies (version 3; docs/breakage.md): their
  /// two bodies (indices into this frame), the glued face's centre now, and
  /// whether they hold (1) or broke (0).
  std::vector<std::uint32_t> bond_first, bond_second;
  std::vector<float> bond_points;  ///< 3 per bond
  std::vector<std::uint8_t> bond_intact;
  std::vector<ViewChannel> channels;  ///< the channel block (version 4), in the table's order
  std::size_t body_count() const { return templates.size(); }
  std::size_t bond_count() const { return bond_first.size(); }
  std::size_t contact_count() const { return contact_b.size(); }
};

/// The surfaces of the world's templates and its plane walls' ids.
ViewShapes view_shapes(const dem::World& world);
/// The world's state now (bodies, touching contacts of the last force
/// evaluation, plane walls), after `step` steps.
ViewFrame view_frame(const dem::World& world, std::uint64_t step);

std::string encode(const ViewShapes& shapes);
std::string encode(const ViewFrame& frame);
/// Throw ViewFormatError naming what is wrong (magic, version, a length
/// that does not fit, an index out of range).
ViewShapes decode_view_shapes(const std::string& bytes);
ViewFrame decode_view_frame(const std::string& bytes);

/// The files of a run folder's view/ (RunPaths::view()).
std::filesystem::path view_shapes_file(const std::filesystem::path& view_dir);
std::filesystem::path view_frame_file(const std::filesystem::path& view_dir, std::uint64_t frame);
std::filesystem::path view_index_file(const std::filesystem::path& view_dir);

/// Throws ViewFormatError saying so when the run folder `run_dir` holds no
/// view frames (no view/index.csv).
void require_view_frames(const std::filesystem::path& run_dir);

/// A row of view/index.csv.
struct ViewIndexRow {
  std::uint64_t frame = 0;
  double time = 0;
  std::uint64_t step = 0, bodies = 0, contacts = 0;
};
std::string view_index_header();
std::string view_index_row(const ViewIndexRow& row);
/// The rows of an index file (ViewFormatError when it is malformed).
std::vector<ViewIndexRow> read_view_index(const std::filesystem::path& file);

/// A file read and decoded (ViewFormatError naming it when it cannot be read
/// or is not one).
ViewShapes read_view_shapes(const std::filesystem::path& file);
ViewFrame read_view_frame(const std::filesystem::path& file);

}  // namespace gjkdem::io
