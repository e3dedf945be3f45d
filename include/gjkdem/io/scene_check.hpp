#pragma once
// A dry run (`gjkdem run --check`, Python's gjkdem.check_scene): every check
// a run makes before its first step, then a few steps into a scratch folder,
// to time them and to weigh a frame and a checkpoint, and what the whole run
// would be from those. Nothing is written where the run would write.
#include <cstdint>
#include <string>
#include <vector>

#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/math/real.hpp"

namespace gjkdem::io {

struct SceneCheck {
  std::size_t bodies = 0, moving = 0, fixed = 0;  ///< at the start
  std::size_t templates = 0;                      ///< shape templates
  std::uint64_t inflow_room = 0;                  ///< bodies the inflows may still insert
  int threads = 0;                                ///< the run's (0: every core)
  Real duration = 0, dt = 0;                      ///< s
  bool dt_auto = true;
  std::uint64_t steps = 0, outputs = 0;           ///< of the whole run (outputs: frames, step 0's included)
  std::string out_dir;                            ///< where the run would write
  /// The sample: steps taken and their wall time per step (the first
  /// output's writing left out), and the run's time at that pace (s): a
  /// lower bound for a pour, whose contacts form later.
  std::uint64_t sampled_steps = 0;
  double seconds_per_step = 0, estimated_seconds = 0;
  /// Bytes of one output (its frame files) and of a checkpoint, at the
  /// start's body count, and of the whole run's folder from them.
  std::uint64_t output_bytes = 0, checkpoint_bytes = 0, estimated_bytes = 0;
  std::vector<std::string> warnings;              ///< the scene's (meshes made convex and the like)
  /// Why the run would fail in its first steps (a guard, a pair the law
  /// cannot take); empty when the sample ran.
  std::string failure;
};

/// Checks the scene in `scene_file` (empty: the built-in default scene):
/// throws SceneError as a run would; runs it for about `sample_seconds` of
/// wall time (at least one step, at most the whole run) with `threads`
/// (< 0: the scene's).
SceneCheck check_scene(const std::string& scene_file, int threads = -1, double sample_seconds = 2.0,
                       const dem::BuildProgress& on_build = {});

/// The check as lines of text for a terminal.
std::string describe(const SceneCheck& check);

}  // namespace gjkdem::io
