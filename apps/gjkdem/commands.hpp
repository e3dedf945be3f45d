#pragma once
// Subcommands of the gjkdem program; each returns the process exit status.
#include <string>

namespace gjkdem::app {

struct QueryOptions {
  std::string in;   ///< input file; empty: standard input
  std::string out;  ///< output file; empty: standard output
};
int run_query(const QueryOptions& opt);

struct BenchOptions {
  std::string in;
  std::string query = "penetration";  ///< intersect | distance | penetration | contact
  int repeat = 10;
};
int run_bench(const BenchOptions& opt);

}  // namespace gjkdem::app
