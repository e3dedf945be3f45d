#pragma once
// Opening the input and output streams named on the command line.
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

namespace gjkdem::app {

/// The named file, or standard input when `path` is empty or "-".
inline std::istream& open_input(const std::string& path, std::unique_ptr<std::ifstream>& holder) {
  if (path.empty() || path == "-") return std::cin;
  holder = std::make_unique<std::ifstream>(path);
  if (!*holder) throw std::runtime_error("cannot open input file '" + path + "'");
  return *holder;
}

inline std::ostream& open_output(const std::string& path, std::unique_ptr<std::ofstream>& holder) {
  if (path.empty() || path == "-") return std::cout;
  holder = std::make_unique<std::ofstream>(path);
  if (!*holder) throw std::runtime_error("cannot open output file '" + path + "'");
  return *holder;
}

}  // namespace gjkdem::app
