// gjkdem analyze OUT: the measurements of every frame of a run (io/analysis.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "commands.hpp"
#include "gjkdem/io/analysis.hpp"

namespace gjkdem::app {

namespace {

/// "x0,y0,z0,x1,y1,z1" -> a region; throws std::invalid_argument.
dem::MeasureRegion parse_region(const std::string& text) {
  std::istringstream in(text);
  double v[6];
  char comma;
  for (int k = 0; k < 6; ++k)
    if (!(in >> v[k]) || (k < 5 && !(in >> comma && comma == ',')))
      throw std::invalid_argument("--region wants six numbers x0,y0,z0,x1,y1,z1, got \"" + text + "\"");
  std::string rest;
  if (in >> rest) throw std::invalid_argument("--region wants six numbers x0,y0,z0,x1,y1,z1, got \"" + text + "\"");
  const dem::MeasureRegion r{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  if (!(r.lo.x < r.hi.x && r.lo.y < r.hi.y && r.lo.z < r.hi.z) || !std::isfinite(r.volume()))
    throw std::invalid_argument("--region: x0 < x1, y0 < y1 and z0 < z1, all finite");
  return r;
}

}  // namespace

int analyze_run(const AnalyzeOptions& opt) {
  io::AnalysisOptions options;
  try {
    if (!opt.region.empty()) options.region = parse_region(opt.region);
  } catch (const std::invalid_argument& e) {
    std::cerr << "gjkdem: " << e.what() << "\n";
    return 2;
  }
  options.every = opt.every;
  // Progress on a terminal only (a log gets the summary line).
  const bool progress = !opt.quiet && isatty(STDERR_FILENO);
  const io::AnalysisSummary s = io::analyze_run(opt.run, options, [&](std::size_t done, std::size_t todo) {
    if (progress) std::fprintf(stderr, "\ranalyze: frame %zu of %zu", done, todo);
  });
  if (progress) std::fprintf(stderr, "\n");
  std::printf("gjkdem analyze: %zu frames (up to %zu bodies) in %.3f s (%.1f ms a frame); wrote %s/analysis/measures.csv "
              "and normal_forces.csv\n",
              s.frames, s.largest_frame, s.seconds, s.frames ? 1e3 * s.seconds / static_cast<double>(s.frames) : 0.0,
              opt.run.c_str());
  return 0;
}

}  // namespace gjkdem::app
