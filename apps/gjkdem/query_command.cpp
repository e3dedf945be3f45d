// gjkdem query: answer every pair of a JSON Lines file, in input order. A bad
// line yields an error object naming the line and the problem; processing goes
// on and the exit status is 1 at the end.
#include <iostream>
#include <string>

#include "commands.hpp"
#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/io/query_jsonl.hpp"
#include "input_lines.hpp"

namespace gjkdem::app {

int run_query(const QueryOptions& opt) {
  std::unique_ptr<std::ifstream> in_file;
  std::unique_ptr<std::ofstream> out_file;
  std::istream& in = open_input(opt.in, in_file);
  std::ostream& out = open_output(opt.out, out_file);
  OverlapWorkspace work;
  std::string line;
  long line_no = 0;
  int errors = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (io::is_skipped_line(line)) continue;
    std::string id = "null";
    try {
      const io::PairInput p = io::parse_pair(line, id);
      const PenetrationResult r = penetration(p.a.shape, p.a.pose, p.b.shape, p.b.pose);
      const OverlapResult o = overlap(p.a.shape, p.a.pose, p.b.shape, p.b.pose, work);
      io::OverlapFields f;
      f.computed = o.status != OverlapStatus::Unsupported;
      f.volume = o.volume;
      f.has_centroid = o.status == OverlapStatus::Overlapping;
      f.centroid = o.centroid;
      f.has_normal = o.has_normal;
      f.contact_normal = o.contact_normal;
      out << io::format_result(p.id_json, r, f) << '\n';
    } catch (const std::exception& e) {
      ++errors;
      out << io::format_error(id, "line " + std::to_string(line_no) + ": " + e.what()) << '\n';
    }
  }
  out.flush();
  if (in.bad()) {
    std::cerr << "gjkdem query: read error after line " << line_no << "\n";
    return 1;
  }
  if (errors > 0) std::cerr << "gjkdem query: " << errors << " line(s) had errors\n";
  return errors > 0 ? 1 : 0;
}

}  // namespace gjkdem::app
