// gjkdem analyze OUT: the measurements of every frame of a run (io/analysis.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <optional>
#include <stdexcept>
#include <vector>

#include <unistd.h>

#include "commands.hpp"
#include "gjkdem/io/analysis.hpp"

namespace gjkdem::app {

namespace {

/// `count` comma-separated numbers, as `option` wants them (`form`); throws
/// std::invalid_argument.
std::vector<double> numbers(const std::string& text, int count, const char* option, const char* form) {
  std::istringstream in(text);
  std::vector<double> v(static_cast<std::size_t>(count));
  char comma;
  const std::string wants = std::string(option) + " wants " + std::to_string(count) + " numbers " + form + ", got \"" + text + "\"";
  for (int k = 0; k < count; ++k)
    if (!(in >> v[static_cast<std::size_t>(k)]) || (k < count - 1 && !(in >> comma && comma == ',')))
      throw std::invalid_argument(wants);
  std::string rest;
  if (in >> rest) throw std::invalid_argument(wants);
  for (const double x : v)
    if (!std::isfinite(x)) throw std::invalid_argument(std::string(option) + ": every number must be finite");
  return v;
}

/// --region, --cylinder or --sphere -> a region; throws std::invalid_argument.
std::optional<dem::MeasureRegion> parse_region(const AnalyzeOptions& opt) {
  if (!opt.region.empty() + !opt.cylinder.empty() + !opt.sphere.empty() > 1)
    throw std::invalid_argument("give one of --region, --cylinder and --sphere");
  dem::MeasureRegion r;
  if (!opt.region.empty()) {
    const std::vector<double> v = numbers(opt.region, 6, "--region", "x0,y0,z0,x1,y1,z1");
    r.lo = {v[0], v[1], v[2]}, r.hi = {v[3], v[4], v[5]};
    if (!(r.lo.x < r.hi.x && r.lo.y < r.hi.y && r.lo.z < r.hi.z) || !std::isfinite(r.volume()))
      throw std::invalid_argument("--region: x0 < x1, y0 < y1 and z0 < z1, all finite");
  } else if (!opt.cylinder.empty()) {
    const std::vector<double> v = numbers(opt.cylinder, 8, "--cylinder", "bx,by,bz,ax,ay,az,radius,height");
    r.round = dem::RoundRegion{.base = {v[0], v[1], v[2]}, .axis = {v[3], v[4], v[5]}, .radius = v[6], .height = v[7]};
    if (!(length(r.round->axis) > 0) || !(v[6] > 0) || !(v[7] > 0) || !std::isfinite(r.volume()))
      throw std::invalid_argument("--cylinder: the axis must not be zero, the radius and height > 0");
  } else if (!opt.sphere.empty()) {
    const std::vector<double> v = numbers(opt.sphere, 4, "--sphere", "cx,cy,cz,radius");
    r.round = dem::RoundRegion{.kind = dem::RoundRegion::Kind::Ball, .base = {v[0], v[1], v[2]}, .radius = v[3]};
    if (!(v[3] > 0) || !std::isfinite(r.volume())) throw std::invalid_argument("--sphere: the radius must be > 0");
  } else {
    return std::nullopt;
  }
  return r;
}

}  // namespace

int analyze_run(const AnalyzeOptions& opt) {
  io::AnalysisOptions options;
  try {
    options.region = parse_region(opt);
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
  std::printf("gjkdem analyze: %zu frames (up to %zu bodies) in %.3f s (%.1f ms a frame); wrote %s/analysis/measures.csv, "
              "normal_forces.csv and sizes.csv\n",
              s.frames, s.largest_frame, s.seconds, s.frames ? 1e3 * s.seconds / static_cast<double>(s.frames) : 0.0,
              opt.run.c_str());
  return 0;
}

}  // namespace gjkdem::app
