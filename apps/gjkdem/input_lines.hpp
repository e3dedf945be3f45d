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

enum class LineRead { Line, TooLong, End };

/// Reads one line of `in` into `line` (without its newline). A line longer
/// than `max_bytes` is read to its end but not kept (TooLong), so memory stays
/// bounded whatever the input.
inline LineRead read_line(std::istream& in, std::string& line, std::size_t max_bytes) {
  line.clear();
  std::streambuf* buf = in.rdbuf();
  bool any = false, too_long = false;
  for (int c = buf->sbumpc();; c = buf->sbumpc()) {
    if (c == std::char_traits<char>::eof()) {
      in.setstate(std::ios::eofbit);
      if (!any) return LineRead::End;
      break;
    }
    any = true;
    if (c == '\n') break;
    if (line.size() < max_bytes) line.push_back(static_cast<char>(c));
    else too_long = true;
  }
  return too_long ? LineRead::TooLong : LineRead::Line;
}

/// Calls on_pair(pair) for every pair line of `in` (blank and '#' lines are
/// skipped); a line that cannot be parsed or is longer than kMaxLineBytes, or
/// whose on_pair throws, goes to on_error(id_json, "line N: what"). Returns
/// the number of errors.
template <class OnPair, class OnError>
int for_each_pair(std::istream& in, OnPair&& on_pair, OnError&& on_error) {
  std::string line;
  long line_no = 0;
  int errors = 0;
  for (LineRead got; (got = read_line(in, line, io::kMaxLineBytes)) != LineRead::End;) {
    ++line_no;
    if (got == LineRead::TooLong) {
      ++errors;
      on_error("null", "line " + std::to_string(line_no) + ": longer than " + std::to_string(io::kMaxLineBytes >> 20) +
                           " MiB, the limit of one query line: refused unread");
      continue;
    }
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
