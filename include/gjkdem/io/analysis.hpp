#pragma once
// `gjkdem analyze OUT`: the measurements of dem/measure.hpp on every frame a
// run wrote to view/, written to OUT/analysis/measures.csv (one row a frame)
// and OUT/analysis/normal_forces.csv (the distribution of the normal contact
// forces a frame). Columns and conventions: docs/measurements.md.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gjkdem/dem/measure.hpp"
#include "gjkdem/io/view_format.hpp"

namespace gjkdem::io {

struct AnalysisOptions {
  std::optional<dem::MeasureRegion> region;  ///< empty: the box around the moving bodies, frame by frame
  std::uint64_t every = 1;                   ///< analyse every this many frames
};

struct AnalysisSummary {
  std::size_t frames = 0;      ///< frames analysed
  double seconds = 0;          ///< wall time of the measurements (reading and writing excluded)
  std::size_t largest_frame = 0;  ///< bodies of the largest frame
};

/// Bins of the normal force distribution: f / mean f in [0, kForceBinWidth * kForceBins), and one
/// bin beyond.
inline constexpr int kForceBins = 20;
inline constexpr double kForceBinWidth = 0.25;

/// Puts the bodies of `frame` into `world` (made from the run's scene: its
/// templates) and returns the frame's contacts. Throws ViewFormatError when
/// the frame names templates or planes the scene does not have.
std::vector<dem::MeasuredContact> load_frame(dem::World& world, const ViewFrame& frame);

std::string measures_header();
std::string measures_row(std::uint64_t frame, double time, const dem::Measures& m);
std::string normal_forces_header();
/// kForceBins + 1 rows: frame,time,low,high,count,density (f / mean f; density per unit of it).
std::string normal_forces_rows(std::uint64_t frame, double time, const dem::Measures& m);

/// Analyses the run in `dir`. The shapes come from `world` when given (the
/// World that wrote the folder from Python, which keeps no scene; it is
/// copied, not changed), else from the folder's scene. `progress` (optional)
/// is called after each frame with the frames done and to do.
AnalysisSummary analyze_run(const std::filesystem::path& dir, const AnalysisOptions& options,
                            const std::function<void(std::size_t, std::size_t)>& progress = {},
                            const dem::World* world = nullptr);

}  // namespace gjkdem::io
