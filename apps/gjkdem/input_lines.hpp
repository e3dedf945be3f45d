#pragma once
// Opening the input and output streams named on the command line, and the
// line loop shared by the subcommands.
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "gjkdem/io/query_jsonl.hpp"

namespace gjkdem::app {

/// The named file, or standard input when `path` is empty or "-".
inline std::istream& open_input(const std::string& path, std::unique_ptr<std::ifstream>& holder) {
  if (path.empty() || path == "-") return std::cin;
  holder = std::make_unique<std::ifstream>(path);
  if (!*holder) throw std::runtime_error("cannot open input file '" + path + "'");
  return *holder;
}

/// Calls on_pair(pair) for every pair line of `in` (blank and '#' lines are
/// skipped); a line that cannot be parsed, or whose on_pair throws, goes to
/// on_error(id_json, "line N: what"). Returns the number of errors.
template <class OnPair, class OnError>
int for_each_pair(std::istream& in, OnPair&& on_pair, OnError&& on_error) {
  std::string line;
  long line_no = 0;
  int errors = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (io::is_skipped_line(line)) continue;
    std::string id = "null";
    try {
      on_pair(io::parse_pair(line, id));
    } catch (const std::exception& e) {
      ++errors;
      on_error(id, "line " + std::to_string(line_no) + ": " + e.what());
    }
  }
  if (in.bad()) throw std::runtime_error("read error after line " + std::to_string(line_no));
  return errors;
}

inline std::ostream& open_output(const std::string& path, std::unique_ptr<std::ofstream>& holder) {
  if (path.empty() || path == "-") return std::cout;
  holder = std::make_unique<std::ofstream>(path);
  if (!*holder) throw std::runtime_error("cannot open output file '" + path + "'");
  return *holder;
}

}  // namespace gjkdem::app
