#include "gjkdem/io/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/io/run_observers.hpp"
#include "gjkdem/io/run_output.hpp"
#include "gjkdem/io/scene_run.hpp"
#include "gjkdem/math/union_find.hpp"

namespace gjkdem::io {

namespace fs = std::filesystem;

namespace {

Vec3 vec(const std::vector<float>& a, std::size_t k) { return {a[3 * k], a[3 * k + 1], a[3 * k + 2]}; }


}  // namespace

std::vector<dem::MeasuredContact> load_frame(dem::World& w, const ViewFrame& f) {
  // A damaged (or blown-up) frame's numbers are refused, not measured into
  // nan and inf.
  const auto finite = [&](const auto& values, const char* what) {
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i]))
        throw ViewFormatError("frame at t = " + std::to_string(f.time) + " holds a " + what +
                              " that is not finite (entry " + std::to_string(i) + ")");
  };
  if (!std::isfinite(f.time)) throw ViewFormatError("a frame's time is not finite");
  finite(f.positions, "position"), finite(f.orientations, "orientation"), finite(f.velocities, "velocity");
  finite(f.contact_points, "contact point"), finite(f.contact_normals, "contact normal");
  finite(f.contact_forces, "contact force"), finite(f.plane_points, "plane point");
  finite(f.cell, "periodic cell bound");
  w.bodies.resize(f.body_count());
  for (std::size_t k = 0; k < f.body_count(); ++k) {
    if (f.templates[k] >= w.templates.size())
      throw ViewFormatError("frame at t = " + std::to_string(f.time) + " names shape template " +
                            std::to_string(f.templates[k]) + "; the run's scene has " +
                            std::to_string(w.templates.size()) +
                            " (with the fragments its checkpoint holds): scene.toml or checkpoint.bin was changed");
    dem::Body& b = w.bodies[k];
    b = dem::Body{};
    b.id = f.ids[k];
    b.shape = f.templates[k];
    b.fixed = (f.flags[k] & kViewFixed) ? 1 : 0;
    b.position = vec(f.positions, k);
    b.orientation = normalized(Quat{f.orientations[4 * k], f.orientations[4 * k + 1], f.orientations[4 * k + 2],
                                    f.orientations[4 * k + 3]});
    b.velocity = vec(f.velocities, k);
  }
  if (f.plane_points.size() / 3 != w.planes.size())
    throw ViewFormatError("frame at t = " + std::to_string(f.time) + " has " + std::to_string(f.plane_points.size() / 3) +
                          " plane walls; the run's scene has " + std::to_string(w.planes.size()));
  w.time = f.time;
  // A periodic cell as the frame has it (a deforming one moved since the start).
  for (int a = 0; a < 3; ++a)
    if (w.cell.now.axes[a] != ((f.cell_axes >> a & 1) != 0))
      throw ViewFormatError("frame at t = " + std::to_string(f.time) + " has other periodic axes than the run's scene");
  if (f.cell_axes) {
    w.cell.now.lo = {f.cell[0], f.cell[1], f.cell[2]};
    w.cell.now.hi = {f.cell[3], f.cell[4], f.cell[5]};
    w.cell.now.tilt = {f.cell[6], f.cell[7], f.cell[8]};
  }
  std::vector<dem::MeasuredContact> contacts(f.contact_count());
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const bool plane = (f.contact_a[c] & kViewPlaneSide) != 0;
    contacts[c] = {plane ? f.contact_a[c] - kViewPlaneSide : f.contact_a[c], plane, f.contact_b[c],
                   vec(f.contact_points, c), vec(f.contact_normals, c), vec(f.contact_forces, c)};
  }
  return contacts;
}

std::string measures_header() {
  return "frame,time,solid_fraction,coordination,contacts,mean_normal_force,stress_xx,stress_yy,stress_zz,stress_xy,"
         "stress_xz,stress_yz,pressure,grains,region_volume\n";
}

std::string measures_row(std::uint64_t frame, double time, const dem::Measures& m) {
  const Mat3& s = m.stress;
  std::string row = std::to_string(frame);
  row += ',';
  append_number(row, time);
  for (const double x : {m.solid_fraction, m.coordination, static_cast<double>(m.contacts), m.mean_normal_force,
                         s.row[0].x, s.row[1].y, s.row[2].z, s.row[0].y, s.row[0].z, s.row[1].z, m.pressure,
                         static_cast<double>(m.grains), m.region_volume}) {
    row += ',';
    append_number(row, x);
  }
  return row + "\n";
}

// The moving grains' sizes (docs/breakage.md: the diameter of the sphere of
// a grain's volume), and the sizes below which 10, 50 and 90% of their
// volume lies: the product size distribution of grains that break. The
// pieces of a bonded assembly that its intact bonds still hold together
// count as one grain of their volumes' sum; the frame's bonds and broken
// bonds close the row.
std::string sizes_header() { return "frame,time,grains,smallest,d10,d50,d90,largest,bonds,bonds_broken\n"; }

std::string sizes_row(std::uint64_t frame, double time, const dem::World& w, const ViewFrame& f) {
  UnionFind held;
  held.reset(w.bodies.size());
  std::size_t broken = 0;
  for (std::size_t b = 0; b < f.bond_count(); ++b) {
    if (f.bond_intact[b]) held.join(f.bond_first[b], f.bond_second[b]);
    else ++broken;
  }
  std::vector<Real> volume(w.bodies.size(), 0);
  for (std::uint32_t i = 0; i < w.bodies.size(); ++i)
    if (!w.bodies[i].fixed) volume[held.find(i)] += w.templates[w.bodies[i].shape].unit_mass.volume;
  std::vector<std::pair<Real, Real>> grains;  // size, volume
  Real total = 0;
  for (const Real v : volume)
    if (v > 0) grains.emplace_back(dem::sphere_diameter(v), v), total += v;
  std::sort(grains.begin(), grains.end());
  std::string row = std::to_string(frame);
  row += ',';
  append_number(row, time);
  row += ',' + std::to_string(grains.size());
  const auto passing = [&](Real fraction) {  // the smallest size with `fraction` of the volume at or below it
    Real below = 0;
    for (const auto& [size, v] : grains)
      if ((below += v) >= fraction * total) return size;
    return grains.back().first;
  };
  for (const Real fraction : {0.0, 0.1, 0.5, 0.9, 1.0}) {
    row += ',';
    if (grains.empty()) row += '0';
    else append_number(row, fraction == 0 ? grains.front().first : passing(fraction));
  }
  return row + ',' + std::to_string(f.bond_count()) + ',' + std::to_string(broken) + "\n";
}

std::string normal_forces_header() { return "frame,time,low,high,count,density\n"; }

std::string normal_forces_rows(std::uint64_t frame, double time, const dem::Measures& m) {
  std::vector<std::size_t> count(kForceBins + 1, 0);
  if (m.mean_normal_force > 0)
    for (const Real f : m.normal_forces) {
      const auto bin = static_cast<std::size_t>(f / m.mean_normal_force / kForceBinWidth);
      ++count[std::min<std::size_t>(bin, kForceBins)];
    }
  std::string rows;
  const double total = static_cast<double>(m.normal_forces.size());
  for (int k = 0; k <= kForceBins; ++k) {
    const double low = k * kForceBinWidth;
    const bool last = k == kForceBins;
    const double density = total > 0 && !last ? static_cast<double>(count[k]) / total / kForceBinWidth : 0;
    rows += std::to_string(frame);
    rows += ',';
    append_number(rows, time);
    rows += ',';
    append_number(rows, low);
    rows += ',';
    if (last) rows += "inf";
    else append_number(rows, low + kForceBinWidth);
    rows += ',';
    rows += std::to_string(count[k]);
    rows += ',';
    append_number(rows, density);
    rows += '\n';
  }
  return rows;
}

AnalysisSummary analyze_run(const fs::path& dir, const AnalysisOptions& options,
                            const std::function<void(std::size_t, std::size_t)>& progress, const dem::World* given) {
  if (options.every == 0) throw std::invalid_argument("--every must be at least 1");
  require_view_frames(dir);
  const fs::path view = dir / "view";
  const std::vector<ViewIndexRow> index = read_view_index(view_index_file(view));
  if (given) {  // the shapes the folder was written with, or a refusal
    std::ifstream in(view_shapes_file(view), std::ios::binary);
    const std::string written{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (written != encode(view_shapes(*given)))
      throw std::invalid_argument("the World given did not write " + dir.string() +
                                  ": its shapes and walls differ from those of view/shapes.bin");
  }
  dem::World world = given ? *given : load_run_scene(dir).world;

  fs::create_directories(dir / "analysis");
  std::string measures = measures_header(), forces = normal_forces_header(), sizes = sizes_header();
  bool fragments_loaded = given != nullptr;  // a given world holds its fragments' templates
  dem::MeasureWorkspace work;
  AnalysisSummary summary;
  const std::size_t todo = (index.size() + options.every - 1) / options.every;
  for (std::size_t k = 0; k < index.size(); k += options.every) {
    const ViewFrame frame = read_view_frame(view_frame_file(view, index[k].frame));
    const auto started = std::chrono::steady_clock::now();
    // Frames after grains broke name their fragments' templates: the run's
    // checkpoint holds them (its last state names every template made).
    const bool names_more = std::any_of(frame.templates.begin(), frame.templates.end(),
                                        [&](std::uint32_t t) { return t >= world.templates.size(); });
    if (names_more && !fragments_loaded) {
      fragments_loaded = true;
      try {
        load_fragment_templates(RunPaths{dir}.checkpoint(), world);
      } catch (const CheckpointError& e) {
        throw ViewFormatError("frame " + std::to_string(index[k].frame) + " names fragments of broken grains; " +
                              e.what());
      }
    }
    const std::vector<dem::MeasuredContact> contacts = load_frame(world, frame);
    const std::optional<dem::MeasureRegion> region = options.region ? options.region : dem::moving_bodies_box(world);
    dem::Measures m;  // zeros: no region given and no moving body
    if (region) try {
        m = dem::measure(world, contacts, *region, work);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("frame " + std::to_string(index[k].frame) + " (t = " + std::to_string(frame.time) +
                                    " s): " + e.what());
      }
    summary.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    measures += measures_row(index[k].frame, frame.time, m);
    forces += normal_forces_rows(index[k].frame, frame.time, m);
    sizes += sizes_row(index[k].frame, frame.time, world, frame);
    summary.largest_frame = std::max(summary.largest_frame, frame.body_count());
    ++summary.frames;
    if (progress) progress(summary.frames, todo);
  }
  write_file_atomically(dir / "analysis" / "measures.csv", measures);
  write_file_atomically(dir / "analysis" / "normal_forces.csv", forces);
  write_file_atomically(dir / "analysis" / "sizes.csv", sizes);
  return summary;
}

}  // namespace gjkdem::io
