// gjkdem query: answer every pair of a JSON Lines file, in input order. A bad
// line yields an error object naming the line and the problem; processing goes
// on and the exit status is 1 at the end. Output that cannot be written (a
// full disk) stops it with exit status 2.
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "gjkdem/shape/tessellate.hpp"
#include "input_lines.hpp"

namespace gjkdem::app {

namespace {

// Thrown (outside std::exception, so the line loop does not take it for a bad
// line) when the output cannot be written: a full disk, /dev/full.
struct OutputFailed {};

}  // namespace

int run_query(const QueryOptions& opt) {
  std::unique_ptr<std::ifstream> in_file;
  std::unique_ptr<std::ofstream> out_file;
  std::istream& in = open_input(opt.in, in_file);
  std::ostream& out = open_output(opt.out, out_file);
  OverlapWorkspace work;
  SurfaceOverlapWorkspace surface_work;
  long written = 0;
  auto emit = [&](const std::string& line) {
    out << line << '\n';
    if (!out) throw OutputFailed{};
    ++written;
  };
  int errors = 0;
  try {
    errors = for_each_pair(
        in,
        [&](const io::PairInput& p) {
          if (p.a.surface) {  // and b: pairs of meshes only (parse_pair)
            const SurfaceOverlap o = surface_overlap(*p.a.surface, *p.b.surface, surface_work);
            SurfaceDistance d;
            if (!o.intersect) d = surface_distance(*p.a.surface, *p.b.surface);
            emit(io::format_surface_result(p.id_json, o, o.intersect ? nullptr : &d,
                                           std::fmin(p.a.surface->volume, p.b.surface->volume)));
            return;
          }
          const PenetrationResult r = penetration(p.a.shape, p.a.pose, p.b.shape, p.b.pose);
          OverlapResult o = overlap(p.a.shape, p.a.pose, p.b.shape, p.b.pose, work);
          if (o.status == OverlapStatus::Unsupported && opt.tessellate > 0) {
            const Shape ta{tessellate(p.a.shape, opt.tessellate).polytope};
            const Shape tb{tessellate(p.b.shape, opt.tessellate).polytope};
            o = overlap(ta, p.a.pose, tb, p.b.pose, work);
          }
          io::OverlapFields f;
          f.computed = o.status != OverlapStatus::Unsupported;
          f.volume = o.volume;
          f.has_centroid = o.status == OverlapStatus::Overlapping;
          f.centroid = o.centroid;
          f.has_normal = o.has_normal;
          f.contact_normal = o.contact_normal;
          emit(io::format_result(p.id_json, r, f));
        },
        [&](const std::string& id, const std::string& message) { emit(io::format_error(id, message)); });
    out.flush();
    if (!out) throw OutputFailed{};
  } catch (const OutputFailed&) {
    std::cerr << "gjkdem query: cannot write the results (" << (opt.out.empty() ? "standard output" : opt.out)
              << ", after " << written << " lines): " << std::strerror(errno) << "\n";
    return 2;
  }
  if (errors > 0) std::cerr << "gjkdem query: " << errors << " line(s) had errors\n";
  return errors > 0 ? 1 : 0;
}

}  // namespace gjkdem::app
