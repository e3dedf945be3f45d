#pragma once
// Subcommands of the gjkdem program; each returns the process exit status.
#include <string>

namespace gjkdem::app {

struct QueryOptions {
  std::string in;   ///< input file; empty: standard input
  std::string out;  ///< output file; empty: standard output
  /// > 0: overlaps that have no exact computation (curved shapes, margins) are
  /// computed on tessellations with this many support directions (approximate).
  int tessellate = 0;
};
int run_query(const QueryOptions& opt);

struct BenchOptions {
  std::string in;
  std::string query = "penetration";  ///< intersect | distance | penetration | contact
  int repeat = 10;
};
int run_bench(const BenchOptions& opt);

}  // namespace gjkdem::app
