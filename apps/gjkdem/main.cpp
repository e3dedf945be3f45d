// gjkdem: pair queries and benchmarks in the format of query-format.md, and
// DEM simulations from scene files (scene-format.md).
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"gjkdem: exact contact detection and DEM simulation of convex and non-convex particles"};
  app.require_subcommand(1);

  gjkdem::app::QueryOptions query;
  CLI::App* q = app.add_subcommand("query", "answer pair queries (JSON Lines in, JSON Lines out)");
  q->add_option("--in", query.in, "input file (default: standard input)");
  q->add_option("--out", query.out, "output file (default: standard output)");
  q->add_option("--tessellate", query.tessellate,
                "compute curved overlaps on tessellations with N support directions (approximate; 0: leave them null)")
      ->check([](const std::string& v) -> std::string {
        // 0 (off), or enough directions for a solid tessellation.
        try {
          const long n = std::stol(v);
          if (n == 0 || (n >= 8 && n <= 1000000)) return "";
        } catch (const std::exception&) {
        }
        return "must be 0 or between 8 and 1000000";
      });

  gjkdem::app::BenchOptions bench;
  CLI::App* b = app.add_subcommand(
      "bench", "time one query type over every pair of a file (distance on triangle pairs: the batched kernel)");
  b->add_option("--in", bench.in, "input file (default: standard input)");
  b->add_option("--query", bench.query, "intersect | distance | penetration | contact")->capture_default_str();
  b->add_option("--repeat", bench.repeat, "timed passes over all pairs")->capture_default_str();

  gjkdem::app::RunOptions run;
  CLI::App* r = app.add_subcommand("run", "run a DEM simulation (no SCENE: the built-in default scene)");
  r->add_option("scene", run.scene, "scene file (TOML, scene-format.md)")->check(CLI::ExistingFile);
  r->add_option("--out", run.out, "output folder (default: the scene's [output].dir)");
  r->add_option("--resume", run.resume, "continue the stopped run in this folder")->check(CLI::ExistingDirectory);
  r->add_option("--from", run.start_from,
                 "start from the last state of this run folder (or checkpoint file), the clock at 0: same bodies, "
                 "shapes and walls; materials, law, gravity, motions, duration and outputs may change");
  r->add_flag("--overwrite", run.overwrite, "replace a run already in the output folder");
  r->add_option("--threads", run.threads, "threads (0: all cores; default: the scene's)")->check(CLI::Range(0, 4096));
  r->add_option("--stop-after", run.stop_after, "stop as if interrupted after this many steps")
      ->check(CLI::Range(0LL, 1LL << 60));
  r->add_flag("--quiet", run.quiet, "no progress output");
  r->add_flag("--check", run.check,
              "a dry run: every check, a few steps timed in a scratch folder, then the bodies, steps, a time and an "
              "output size estimate; nothing is written (exit 1: the run would fail)");
  r->get_option("--resume")->excludes(r->get_option("scene"));
  r->get_option("--resume")->excludes(r->get_option("--out"));  // a resumed run writes where it ran
  r->get_option("--resume")->excludes(r->get_option("--overwrite"));
  r->get_option("--resume")->excludes(r->get_option("--from"));  // a resumed run goes on from its own state

  gjkdem::app::ViewOptions view;
  CLI::App* v = app.add_subcommand("view", "show a run folder in the browser (serves it on 127.0.0.1)");
  v->add_option("run", view.run, "run folder (written by gjkdem run)")->required()->check(CLI::ExistingDirectory);
  v->add_option("--port", view.port, "port (0: any free one)")->capture_default_str()->check(CLI::Range(0, 65535));
  v->add_option("--web", view.web, "the viewer's page folder (default: the installed one)");

  gjkdem::app::AnalyzeOptions analyze;
  CLI::App* a = app.add_subcommand("analyze", "measure every frame of a run: solid fraction, coordination, stress, "
                                               "normal forces (writes OUT/analysis/)");
  a->add_option("run", analyze.run, "run folder (written by gjkdem run)")->required()->check(CLI::ExistingDirectory);
  a->add_option("--region", analyze.region, "box x0,y0,z0,x1,y1,z1 (m; default: around the moving bodies)");
  a->add_option("--cylinder", analyze.cylinder, "cylinder bx,by,bz,ax,ay,az,radius,height: from base b along axis a");
  a->add_option("--sphere", analyze.sphere, "ball cx,cy,cz,radius");
  a->add_option("--every", analyze.every, "analyse every Nth frame")->capture_default_str()->check(CLI::Range(1, 1 << 30));
  a->add_flag("--quiet", analyze.quiet, "no progress output");

  gjkdem::app::ExportOptions exported;
  CLI::App* x = app.add_subcommand("export", "write a run's last saved state as a scene: its moving bodies where "
                                              "they were, to start other runs from (docs/scenes.md)");
  x->add_option("run", exported.run, "run folder (written by gjkdem run)")->required()->check(CLI::ExistingDirectory);
  x->add_option("--out", exported.out, "scene file to write (default: standard output)");

  // Bad options exit 2 like any refused input (CLI11's own codes are 100+).
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success) ? code : 2;
  }
  try {
    if (q->parsed()) return gjkdem::app::run_query(query);
    if (b->parsed()) return gjkdem::app::run_bench(bench);
    if (r->parsed()) return gjkdem::app::run_simulation(run);
    if (v->parsed()) return gjkdem::app::view_run(view);
    if (a->parsed()) return gjkdem::app::analyze_run(analyze);
    if (x->parsed()) return gjkdem::app::export_state(exported);
  } catch (const std::exception& e) {
    std::cerr << "gjkdem: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
