#pragma once
// What a run writes (../shared/spec/scene-format.md): ParaView frames (legacy
// VTK polydata, binary, one file per frame, and a frames.vtk.series index with
// the simulated times) and rows of trace.csv and energy.csv.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world.hpp"
#include "gjkdem/io/number_text.hpp"

namespace gjkdem::io {

/// Polygons drawn for one shape template, in the template's local frame.
struct DisplayMesh {
  std::vector<Vec3> vertices;
  std::vector<std::uint32_t> polygon_begin;  ///< polygon k: indices[polygon_begin[k] .. polygon_begin[k+1])
  std::vector<std::uint32_t> indices;
};

/// Facets of polytopes and boxes, the triangle of a triangle, and a
/// tessellation (64 directions) of curved shapes.
DisplayMesh display_mesh(const Shape& shape);

/// Of a template: its shape, or each part of a compound placed in its frame.
DisplayMesh display_mesh(const dem::ShapeTemplate& shape);

/// One frame: every body's polygons placed in the world, with cell data body
/// id, fixed flag, velocity and angular velocity. Throws std::runtime_error
/// when the file cannot be written.
void write_vtk_frame(const std::filesystem::path& file, const dem::World& world,
                     std::span<const DisplayMesh> meshes);

/// The index ParaView reads to give each frame its simulated time.
void write_frame_series(const std::filesystem::path& file, std::span<const std::pair<std::string, Real>> frames);

/// Writes `text` to `file` through a temporary file (FILE.tmp), flushed, and
/// a rename: a crash or a full disk leaves the previous file whole. Throws
/// std::runtime_error when it cannot be written.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

/// The whole of `file`, or nothing when it cannot be read (callers say why
/// in their own terms).
std::optional<std::string> read_file(const std::filesystem::path& file);

/// Outputs between checkpoints where a scene or a Python run does not say.
inline constexpr int kDefaultCheckpointEvery = 10;

/// A body written to trace.csv every output, under its name.
struct TracedBody {
  std::string name;
  std::uint32_t body = 0;  ///< index into world.bodies
};

/// The world's named bodies (World::names), as trace.csv logs them.
std::vector<TracedBody> traced_bodies(const dem::World& world);

std::string trace_header();
/// One trace.csv row (with newline): time,name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz.
std::string trace_row(const dem::World& world, const std::string& name, const dem::Body& body);
/// energy.csv's optional columns: `split`, the energy splits stored
/// (split_energy, after inflow_energy: a world whose grains can break);
/// `applied`, the applied loads' work (applied_work, last).
struct EnergyColumns {
  bool applied = false;
  bool split = false;
};
std::string energy_header(EnergyColumns columns = {});
/// One energy.csv row (with newline): time,kinetic,potential,elastic,dissipated,contacts,wall_work,inflow_energy
/// then the optional columns.
std::string energy_row(Real time, const dem::EnergyBalance& energy, int contacts, EnergyColumns columns = {});

/// A wall time as "4m05s" or "1h02m" ("?" when negative or not finite).
std::string duration_text(double seconds);

/// A run's progress as `gjkdem run` and Python's run(progress=True) print
/// it: "t = 0.1234 / 1 s   12.3%  4567 steps/s  ETA 1m05s" for the world at
/// `time` of a run lasting `duration`, `step` of `steps_total` done at
/// `steps_per_second`.
std::string progress_line(Real time, Real duration, std::uint64_t step, std::uint64_t steps_total,
                          double steps_per_second);

/// When a run's progress is shown (`gjkdem run`, Python's progress=True):
/// every 0.25 s on a terminal (redrawn in place), every 10 s elsewhere (a
/// log, a notebook), and at the end; the pace counted from `first_step`.
class ProgressClock {
 public:
  ProgressClock(bool terminal, std::uint64_t first_step);
  /// progress_line when one is due now (always when `final`), else empty.
  std::string due(Real time, Real duration, std::uint64_t step, std::uint64_t steps_total, bool final);
  bool terminal() const noexcept { return terminal_; }

 private:
  bool terminal_;
  std::uint64_t first_;
  std::chrono::steady_clock::time_point start_, last_;
};

/// cell.csv (periodic worlds): time, the cell's lengths and tilts (m), its
/// volume (m^3), velocity gradient (1/s) and the contacts' stress (Pa,
/// compression positive), components xx yy zz xy xz yz.
std::string cell_header();
std::string cell_row(const dem::World& world);

}  // namespace gjkdem::io
