#pragma once
// The mesh pairs of a query-format file (e.g. ../shared/data/nonconvex/
// rocks.in.jsonl), for the benchmarks of surface queries: lines whose two
// shapes are not both closed meshes are passed over.
#include <cstdio>
#include <fstream>
#include <string>

#include "gjkdem/io/query_jsonl.hpp"

namespace gjkdem::bench {

/// Calls f(id, a, b) for each mesh pair of `path`, the surfaces placed in
/// the world. False (and a message on stderr naming `program`) when the
/// file cannot be read.
template <class F>
bool for_each_mesh_pair(const std::string& path, const char* program, F&& f) {
  std::ifstream file(path);
  if (!file) {
    std::fprintf(stderr, "%s: cannot read '%s'\n", program, path.c_str());
    return false;
  }
  std::string line;
  while (std::getline(file, line)) {
    if (io::is_skipped_line(line)) continue;
    std::string id;
    const io::PairInput p = io::parse_pair(line, id);
    if (p.a.surface && p.b.surface) f(id, *p.a.surface, *p.b.surface);
  }
  return true;
}

}  // namespace gjkdem::bench
