#pragma once
// A run of a scene into its run folder, the one way `gjkdem run` and
// Python's gjkdem.run_scene do it: the folder locked and prepared, the scene
// text saved beside the outputs, every writer of run_observers.hpp set up
// (frames, trace, energy, checkpoints, run.json), or all of it taken up
// again from the folder's checkpoint. The caller adds its own observers
// (a progress bar, Python callbacks) and its stop condition.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "gjkdem/dem/domains.hpp"
#include "gjkdem/io/run_observers.hpp"
#include "gjkdem/io/scene.hpp"

namespace gjkdem::io {

struct SceneRunOptions {
  std::filesystem::path out;  ///< run folder; empty: the scene's output.directory
  bool overwrite = false;     ///< replace an earlier run's files (the scene's output.overwrite also does)
  int threads = -1;           ///< < 0: the scene's simulation.threads; 0: every core
  /// A rank other than 0 of a run on domains: the scene is read, nothing is
  /// written (rank 0 writes the run folder).
  bool follower = false;
  /// Non-empty: the run starts from the last state saved in this run folder
  /// (or checkpoint file), its clock at 0: the scene's bodies, shapes and
  /// walls must be those of that run; its materials, contact law settings,
  /// gravity, motions, duration and outputs may differ (io::Restore::NewRun).
  std::filesystem::path start_from{};
  dem::BuildProgress on_build{};  ///< hears what a long build starts on (WorldBuilder::set_progress)
};

/// The library's version ("0.1.0"), written into run.json.
const char* version() noexcept;

/// run.json's description of a run of `world` in steps of dt (version,
/// bodies, shape templates, threads, dt), to which callers add their own.
std::string run_info_json(const dem::World& world, Real dt);

/// The scene of the run in `dir` (its scene.toml, files relative to where
/// the scene was read from, which run.json records). Throws SceneError.
Scene load_run_scene(const std::filesystem::path& dir);

/// The same, its world restored from the folder's checkpoint: the run's
/// last saved state. Throws SceneError (no checkpoint, the scene),
/// CheckpointError (a checkpoint that does not fit).
Scene load_run_checkpoint(const std::filesystem::path& dir);

class SceneRun {
 public:
  /// A new run of the scene in `scene_file` (empty: the built-in default
  /// scene). Throws SceneError (the scene), RunFolderError (the folder).
  static std::unique_ptr<SceneRun> start(const std::string& scene_file, const SceneRunOptions& options);
  /// Takes up the run in `dir` from its checkpoint (SceneError when the
  /// folder holds none, CheckpointError when it does not match the scene).
  /// `follower`: as in SceneRunOptions (the folder is only read).
  static std::unique_ptr<SceneRun> resume(const std::filesystem::path& dir, int threads = -1, bool follower = false,
                                          const dem::BuildProgress& on_build = {});
  /// True when run.json in `dir` says the run completed.
  static bool completed(const std::filesystem::path& dir);

  SceneRun(const SceneRun&) = delete;
  SceneRun& operator=(const SceneRun&) = delete;
  ~SceneRun();

  /// Runs to the end, or until `stop` (asked after every step) returns a
  /// reason, which run.json records as `stopped_by`; "" goes on. `extra`
  /// observers are called after the writers. With a `transport` of more
  /// than one rank, every rank calls run() together and the world runs on
  /// domains (dem::run_domains): rank 0 writes, observes and decides
  /// when to stop, the others pass no observers.
  /// `listeners` (dem::StepListener) are called on every rank.
  dem::RunOutcome run(std::span<dem::RunObserver* const> extra = {},
                      const std::function<std::string()>& stop = {}, dem::DomainTransport* transport = nullptr,
                      std::span<dem::StepListener* const> listeners = {});

  Scene scene;
  dem::RunState state;
  /// After a run on domains, on rank 0: what the domains did.
  dem::DomainReport domain_report;
  RunPaths folder;
  /// Wall time of the run so far, earlier sittings included (s).
  double wall_seconds() const;

 private:
  SceneRun() = default;
  void open_writers(const std::string& text, const std::string& scene_file, const std::filesystem::path& base,
                    bool resuming, const std::filesystem::path& start_from);

  std::optional<RunFolderLock> lock_;
  std::unique_ptr<RunFolderWriters> writers_;
};

}  // namespace gjkdem::io
