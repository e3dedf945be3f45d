#pragma once
// Subcommands of the gjkdem program; each returns the process exit status.
#include <cstdint>
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

namespace gjkdem::app {

struct RunOptions {
  std::string scene;        ///< scene file; empty: the built-in default scene
  std::string out;          ///< output folder; empty: the scene's [output].dir
  std::string resume;       ///< folder of a stopped run to continue
  std::string start_from;   ///< run folder (or checkpoint) whose last state a new run starts from
  bool overwrite = false;   ///< replace a run already in the output folder
  int threads = -1;         ///< -1: the scene's [simulation].threads
  long long stop_after = -1;  ///< stop as if interrupted after this many steps (tests)
  bool quiet = false;       ///< no progress output
  bool check = false;       ///< a dry run: every check and a short timed sample, nothing written (io/scene_check.hpp)
};
/// 0 completed, 1 failed during the run, 2 refused (bad scene or options), 130 interrupted.
int run_simulation(const RunOptions& opt);

}  // namespace gjkdem::app

namespace gjkdem::app {

struct ViewOptions {
  std::string run;   ///< run folder
  int port = 8765;   ///< 0: any free port
  std::string web;   ///< the viewer's page folder; empty: found (view_command.cpp)
};
/// Serves until killed; throws when it cannot start.
int view_run(const ViewOptions& opt);

}  // namespace gjkdem::app

namespace gjkdem::app {

struct AnalyzeOptions {
  std::string run;              ///< run folder
  std::string region;           ///< "x0,y0,z0,x1,y1,z1"; all three empty: around the moving bodies
  std::string cylinder;         ///< "bx,by,bz,ax,ay,az,radius,height"
  std::string sphere;           ///< "cx,cy,cz,radius"
  std::uint64_t every = 1;      ///< every this many frames
  bool quiet = false;
};
/// 0 done, 2 refused (bad options, not a run folder).
int analyze_run(const AnalyzeOptions& opt);

}  // namespace gjkdem::app

namespace gjkdem::app {

struct ExportOptions {
  std::string run;  ///< run folder
  std::string out;  ///< scene file; empty: standard output
};
/// 0 written, 2 refused (no checkpoint, a state a scene cannot hold, a file that cannot be written).
int export_state(const ExportOptions& opt);

}  // namespace gjkdem::app
