#pragma once
// The observers that write a run folder (../shared/spec/scene-format.md):
// frames, trace.csv, energy.csv, checkpoints and run.json. Each one sees the
// run through dem::RunObserver; together they continue a stopped run from its
// checkpoint with the same bytes as an uninterrupted one.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/io/run_output.hpp"

namespace gjkdem::io {

/// The files of a run folder.
struct RunPaths {
  std::filesystem::path dir;
  std::filesystem::path frames() const { return dir / "frames"; }
  std::filesystem::path view() const { return dir / "view"; }
  std::filesystem::path checkpoint() const { return dir / "checkpoint.bin"; }
  std::filesystem::path trace() const { return dir / "trace.csv"; }
  std::filesystem::path energy() const { return dir / "energy.csv"; }
  std::filesystem::path cell() const { return dir / "cell.csv"; }
  std::filesystem::path run_json() const { return dir / "run.json"; }
  std::filesystem::path scene() const { return dir / "scene.toml"; }
};

/// frames/frame_NNNNNN.vtk at every output, and frames/frames.vtk.series.
class FrameWriter : public dem::RunObserver {
 public:
  FrameWriter(std::filesystem::path dir, const dem::World& world, bool enabled);
  void on_output(const dem::World& world, const dem::RunState& state) override;
  /// Frame files and times so far (a checkpoint keeps them).
  std::vector<std::pair<std::string, Real>> frames;

 private:
  std::filesystem::path dir_;
  std::vector<DisplayMesh> meshes_;
  bool enabled_;
};

/// view/ (docs/view-format.md): the templates' surfaces, then a compact
/// frame and an index row at every output; the surfaces are written again
/// before a frame whose world has more templates (the fragments of grains
/// that broke), so shapes.bin holds every template a frame names. A resumed
/// run cuts the index back to the checkpoint's outputs and writes the later
/// frames again.
class ViewWriter : public dem::RunObserver {
 public:
  /// `resumed_outputs`: outputs the checkpoint had (0 for a new run).
  ViewWriter(std::filesystem::path dir, const dem::World& world, bool enabled, std::uint64_t resumed_outputs);
  void on_output(const dem::World& world, const dem::RunState& state) override;

 private:
  std::filesystem::path dir_;
  std::ofstream index_;
  std::size_t shapes_written_ = 0;  ///< templates in shapes.bin
  bool enabled_;
};

/// A CSV log appended at every output; flushed each time, so a checkpoint
/// can record its length and a resumed run cut it back to that.
class CsvLog : public dem::RunObserver {
 public:
  /// A new log with its header, or (resume) the existing file cut to `bytes`.
  void start(const std::filesystem::path& file, const std::string& header);
  void resume(const std::filesystem::path& file, std::uint64_t bytes);
  /// The whole log replaced by `text` (written atomically), appended to from there.
  void rewrite(const std::string& text);
  std::uint64_t bytes() const { return bytes_; }
  const std::filesystem::path& file() const { return file_; }

 protected:
  void append(const std::string& rows);

 private:
  std::filesystem::path file_;
  std::ofstream out_;
  std::uint64_t bytes_ = 0;
};

/// trace.csv: one row per traced body per output.
class TraceWriter : public CsvLog {
 public:
  explicit TraceWriter(std::vector<TracedBody> traced) : traced_(std::move(traced)) {}
  void on_output(const dem::World& world, const dem::RunState& state) override;

 private:
  std::vector<TracedBody> traced_;
};

/// energy.csv: the energy balance at every output.
/// A world whose grains can break (world_breaks) has a split_energy column
/// after inflow_energy; a world with applied loads (World::applied_loads, as
/// the run starts or is resumed) adds their work as a last column,
/// applied_work.
class EnergyWriter : public CsvLog {
 public:
  void on_output(const dem::World& world, const dem::RunState& state) override;
  /// The applied_work column from now on: a log without rows starts again
  /// with it; a resumed log without it (a run that had no applied loads,
  /// resumed with a listener) gets it on every row so far, 0 (no load did
  /// any work before). Returns whether it changed the file.
  bool take_applied_work();
  bool applied = false;
  bool splits = false;
};

/// cell.csv: a periodic world's cell and stress at every output (nothing
/// in other worlds).
class CellWriter : public CsvLog {
 public:
  void on_output(const dem::World& world, const dem::RunState& state) override;
};

/// checkpoint.bin every `every` outputs (0: never), when the run is stopped,
/// so that it can continue, and (unless `every` is 0) when it completes, so
/// that another run can start from its last state.
class Checkpointer : public dem::RunObserver {
 public:
  Checkpointer(std::filesystem::path file, int every, std::uint64_t fingerprint, const FrameWriter& frames,
               const CsvLog& trace, const CsvLog& energy, const CsvLog& cell, double wall_before);
  void on_output(const dem::World& world, const dem::RunState& state) override;
  void on_stop(const dem::World& world, const dem::RunState& state, const dem::RunOutcome& outcome) override;
  /// A checkpoint again now, when one is on disk: a log it counts the bytes
  /// of changed other than by appending (EnergyWriter::take_applied_work).
  void save_again(const dem::World& world, const dem::RunState& state);
  /// Called after each checkpoint (run.json then records how far the run got).
  std::function<void(const dem::World&, const dem::RunState&)> saved;
  /// Wall time of the run so far (s), earlier sessions included.
  double wall_seconds() const;

 private:
  void save(const dem::World& world, const dem::RunState& state);
  std::filesystem::path file_;
  int every_;
  std::uint64_t fingerprint_;
  const FrameWriter& frames_;
  const CsvLog &trace_, &energy_, &cell_;
  double wall_before_;
  std::chrono::steady_clock::time_point started_;
};

/// run.json: the run's description (`info`, a JSON object) with its status,
/// written atomically when the run starts and when it stops.
class RunInfoWriter : public dem::RunObserver {
 public:
  RunInfoWriter(std::filesystem::path file, const std::string& info_json, const Checkpointer& clock);
  void on_output(const dem::World&, const dem::RunState&) override {}
  /// status "running" (steps so far).
  void started(const dem::World& world, const dem::RunState& state);
  void on_stop(const dem::World& world, const dem::RunState& state, const dem::RunOutcome& outcome) override;
  /// Guard warnings go into run.json's "warnings".
  void on_warning(const dem::World& world, const dem::RunState& state, const std::string& message) override;
  /// What stopped a run that was stopped ("SIGINT", "--stop-after", ...).
  std::string stopped_by;
  /// The MPI ranks the run is on (1: one process; docs/scaling.md).
  int ranks = 1;

 private:
  void write(const std::string& status, const dem::World& world, const dem::RunState& state,
             const std::string& error);
  std::filesystem::path file_;
  std::string info_json_;
  std::vector<std::string> warnings_;
  const Checkpointer& clock_;
};

/// What a run folder's writers are asked to write.
struct RunWriterOptions {
  bool frames = true;                ///< VTK frames at every output
  bool view = true;                  ///< view/ frames at every output (docs/view-format.md)
  int checkpoint_every = kDefaultCheckpointEvery;  ///< outputs between checkpoints (0: only when stopped)
  std::vector<TracedBody> traced;    ///< bodies logged in trace.csv
  std::uint64_t fingerprint = 0;     ///< of the scene (checkpoints of another are refused)
  std::string info_json = "{}";      ///< run.json's description of the run (a JSON object)
};

/// Every writer of a run folder, made together: frames, trace.csv,
/// view/, energy.csv, cell.csv (periodic worlds), checkpoints and run.json. A new run writes the logs' headers;
/// a resumed one takes the frames, logs and wall clock up from the
/// checkpoint the world was restored from.
class RunFolderWriters {
 public:
  RunFolderWriters(const RunPaths& folder, const dem::World& world, const RunWriterOptions& options);
  RunFolderWriters(const RunPaths& folder, const dem::World& world, const RunWriterOptions& options,
                   const Checkpoint& restored);
  RunFolderWriters(const RunFolderWriters&) = delete;
  RunFolderWriters& operator=(const RunFolderWriters&) = delete;

  /// In the order a run calls them.
  std::vector<dem::RunObserver*> observers() { return {&frames_, &view_, &trace_, &energy_, &cell_, &checkpoints_, &info_}; }
  RunInfoWriter& info() { return info_; }
  double wall_seconds() const { return checkpoints_.wall_seconds(); }
  /// energy.csv counts the applied loads' work (EnergyWriter::take_applied_work)
  /// from `world` at `state` on; a changed log is checkpointed at once when
  /// a checkpoint is on disk (its byte counts name the log as it is now).
  void take_applied_work(const dem::World& world, const dem::RunState& state);

 private:
  RunFolderWriters(const RunPaths& folder, const dem::World& world, const RunWriterOptions& options,
                   const Checkpoint* restored);

  FrameWriter frames_;
  ViewWriter view_;
  TraceWriter trace_;
  EnergyWriter energy_;
  CellWriter cell_;
  Checkpointer checkpoints_;
  RunInfoWriter info_;
};

/// A run folder that cannot be used (refused before a run starts).
struct RunFolderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Makes `paths.dir` ready for a new run. A folder holding a run's files
/// (run.json, scene.toml, the logs, a checkpoint, frames or view files) is
/// refused unless `overwrite`; then only those files are removed
/// (frames/frame_*.vtk and frames.vtk.series, view/frame_*.bin, shapes.bin
/// and index.csv; never anything else in the folder, frames/ or view/).
/// Throws RunFolderError naming the folder.
void prepare_run_folder(const RunPaths& paths, bool overwrite);

/// Removes what a killed run may leave behind: temporary files of atomic
/// writes (checkpoint.bin.tmp, run.json.tmp).
void remove_stale_temporaries(const RunPaths& paths);

/// An exclusive lock on a run folder (flock on DIR/.gjkdem.lock), held while
/// a run uses it, so that two runs or resumes never write into one folder.
class RunFolderLock {
 public:
  /// Throws RunFolderError when another process holds the lock.
  explicit RunFolderLock(const std::filesystem::path& dir);
  ~RunFolderLock();
  RunFolderLock(const RunFolderLock&) = delete;
  RunFolderLock& operator=(const RunFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace gjkdem::io
