#include "gjkdem/io/run_observers.hpp"

#include <cstdio>
#include <cstring>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/io/view_format.hpp"

namespace gjkdem::io {

namespace fs = std::filesystem;

void prepare_run_folder(const RunPaths& paths, bool overwrite) {
  std::error_code ec;
  if (fs::exists(paths.dir, ec) && !fs::is_directory(paths.dir, ec))
    throw RunFolderError(paths.dir.string() + " exists and is not a folder");
  std::vector<fs::path> ours;
  for (const fs::path& p : {paths.run_json(), paths.scene(), paths.trace(), paths.energy(), paths.cell(), paths.checkpoint(),
                            fs::path(paths.checkpoint().string() + ".tmp"), fs::path(paths.run_json().string() + ".tmp")})
    if (fs::exists(p, ec)) ours.push_back(p);
  if (fs::is_directory(paths.frames(), ec))
    for (const fs::directory_entry& e : fs::directory_iterator(paths.frames(), ec)) {
      const std::string name = e.path().filename().string();
      if ((name.rfind("frame_", 0) == 0 && e.path().extension() == ".vtk") || name == "frames.vtk.series")
        ours.push_back(e.path());
    }
  if (fs::is_directory(paths.view(), ec))
    for (const fs::directory_entry& e : fs::directory_iterator(paths.view(), ec)) {
      const std::string name = e.path().filename().string();
      if ((name.rfind("frame_", 0) == 0 && (e.path().extension() == ".bin" || name.ends_with(".bin.tmp"))) ||
          name == "shapes.bin" || name == "index.csv" || name == "shapes.bin.tmp" || name == "index.csv.tmp")
        ours.push_back(e.path());
    }
  if (!ours.empty() && !overwrite)
    throw RunFolderError(paths.dir.string() + " already holds a run (" + ours.front().filename().string() +
                             "); choose another [output].dir or --out, or set [output].overwrite = true (or "
                             "--overwrite) to replace it");
  for (const fs::path& p : ours) fs::remove(p);
  fs::create_directories(paths.frames());
}

void remove_stale_temporaries(const RunPaths& paths) {
  std::error_code ec;
  fs::remove(paths.checkpoint().string() + ".tmp", ec);
  fs::remove(paths.run_json().string() + ".tmp", ec);
  if (fs::is_directory(paths.view(), ec))
    for (const fs::directory_entry& e : fs::directory_iterator(paths.view(), ec))
      if (e.path().extension() == ".tmp") fs::remove(e.path(), ec);
}

RunFolderLock::RunFolderLock(const fs::path& dir) {
  const fs::path file = dir / ".gjkdem.lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RunFolderError("cannot open " + file.string() + ": " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw RunFolderError("another gjkdem run is using " + dir.string() + " (it holds " + file.string() + ")");
  }
}

RunFolderLock::~RunFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

FrameWriter::FrameWriter(fs::path dir, const dem::World& world, bool enabled) : dir_(std::move(dir)), enabled_(enabled) {
  if (enabled_)
    for (const dem::ShapeTemplate& t : world.templates) meshes_.push_back(display_mesh(t));
}

void FrameWriter::on_output(const dem::World& w, const dem::RunState& state) {
  if (!enabled_) return;
  while (meshes_.size() < w.templates.size()) meshes_.push_back(display_mesh(w.templates[meshes_.size()]));  // fragments
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06llu.vtk", static_cast<unsigned long long>(state.outputs - 1));
  write_vtk_frame(dir_ / name, w, meshes_);
  frames.emplace_back(name, w.time);
  write_frame_series(dir_ / "frames.vtk.series", frames);
}

ViewWriter::ViewWriter(fs::path dir, const dem::World& world, bool enabled, std::uint64_t resumed_outputs)
    : dir_(std::move(dir)), enabled_(enabled) {
  if (!enabled_) return;
  fs::create_directories(dir_);
  write_file_atomically(view_shapes_file(dir_), encode(view_shapes(world)));
  shapes_written_ = world.templates.size();
  std::string index = view_index_header();
  if (resumed_outputs > 0) {
    // The frames the checkpoint had stay; later ones are written again.
    std::vector<ViewIndexRow> rows;
    try {
      rows = read_view_index(view_index_file(dir_));
    } catch (const ViewFormatError& e) {
      throw CheckpointError(std::string(e.what()) + ": the run folder was changed");
    }
    for (const ViewIndexRow& row : rows)
      if (row.frame < resumed_outputs) index += view_index_row(row);
  }
  write_file_atomically(view_index_file(dir_), index);
  index_.open(view_index_file(dir_), std::ios::binary | std::ios::app);
  if (!index_) throw std::runtime_error("cannot open " + view_index_file(dir_).string());
}

void ViewWriter::on_output(const dem::World& w, const dem::RunState& state) {
  if (!enabled_) return;
  if (w.templates.size() != shapes_written_) {  // fragments of broken grains: their shapes before the frame
    write_file_atomically(view_shapes_file(dir_), encode(view_shapes(w)));
    shapes_written_ = w.templates.size();
  }
  const ViewFrame frame = view_frame(w, state.step);
  const std::uint64_t number = state.outputs - 1;
  write_file_atomically(view_frame_file(dir_, number), encode(frame));
  // The row goes in after its frame is whole: a reader polling the index
  // never opens a frame being written.
  index_ << view_index_row({number, frame.time, frame.step, frame.body_count(), frame.contact_count()});
  index_.flush();
  if (!index_) throw std::runtime_error("cannot write " + view_index_file(dir_).string());
}

void CsvLog::start(const fs::path& file, const std::string& header) {
  file_ = file;
  if (out_.is_open()) out_.close();  // started again (EnergyWriter::take_applied_work)
  out_.clear();
  out_.open(file, std::ios::binary | std::ios::trunc);
  bytes_ = 0;
  append(header);
}

void CsvLog::resume(const fs::path& file, std::uint64_t bytes) {
  file_ = file;
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec || size < bytes)
    throw CheckpointError(file.string() + " is shorter than the checkpoint says it was: the run folder was changed");
  fs::resize_file(file, bytes);
  out_.open(file, std::ios::binary | std::ios::app);
  bytes_ = bytes;
  if (!out_) throw std::runtime_error("cannot open " + file.string());
}

void CsvLog::rewrite(const std::string& text) {
  if (out_.is_open()) out_.close();
  write_file_atomically(file_, text);
  out_.clear();
  out_.open(file_, std::ios::binary | std::ios::app);
  if (!out_) throw std::runtime_error("cannot open " + file_.string());
  bytes_ = text.size();
}

void CsvLog::append(const std::string& rows) {
  out_ << rows;
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write " + file_.string());
  bytes_ += rows.size();
}

void TraceWriter::on_output(const dem::World& w, const dem::RunState&) {
  std::string rows;
  for (const TracedBody& t : traced_) rows += trace_row(w, t.name, w.bodies[t.body]);
  if (!rows.empty()) append(rows);
}

void EnergyWriter::on_output(const dem::World& w, const dem::RunState& state) {
  const dem::EnergyBalance e = dem::energy_balance(w, state.initial_energy);
  append(energy_row(w.time, e, w.stats.contacts, {.applied = applied, .split = splits}));
}

bool EnergyWriter::take_applied_work() {
  if (applied) return false;
  applied = true;
  if (bytes() == energy_header({.split = splits}).size()) {
    start(file(), energy_header({.applied = true, .split = splits}));
    return true;
  }
  const std::optional<std::string> text = read_file(file());
  if (!text || text->size() != bytes() || !text->starts_with(energy_header({.split = splits})))
    throw std::runtime_error(file().string() + " is not the energy log this run wrote: the run folder was changed");
  std::string with = energy_header({.applied = true, .split = splits});
  for (std::size_t at = energy_header({.split = splits}).size(); at < text->size();) {
    const std::size_t end = text->find('\n', at);
    if (end == std::string::npos) break;  // (every row ends with its newline)
    with.append(*text, at, end - at).append(",0\n");
    at = end + 1;
  }
  rewrite(with);
  return true;
}

void RunFolderWriters::take_applied_work(const dem::World& world, const dem::RunState& state) {
  if (energy_.take_applied_work()) checkpoints_.save_again(world, state);
}

void CellWriter::on_output(const dem::World& w, const dem::RunState&) {
  if (w.cell.now.active()) append(cell_row(w));
}

Checkpointer::Checkpointer(fs::path file, int every, std::uint64_t fingerprint, const FrameWriter& frames,
                           const CsvLog& trace, const CsvLog& energy, const CsvLog& cell, double wall_before)
    : file_(std::move(file)), every_(every), fingerprint_(fingerprint), frames_(frames), trace_(trace),
      energy_(energy), cell_(cell), wall_before_(wall_before), started_(std::chrono::steady_clock::now()) {}

double Checkpointer::wall_seconds() const {
  return wall_before_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void Checkpointer::save(const dem::World& w, const dem::RunState& state) {
  Checkpoint c;
  c.run = state;
  c.logs = {trace_.bytes(), energy_.bytes(), cell_.bytes(), wall_seconds(), frames_.frames};
  save_checkpoint(file_, w, c, fingerprint_);
}

void Checkpointer::save_again(const dem::World& w, const dem::RunState& state) {
  std::error_code ec;
  if (fs::exists(file_, ec)) save(w, state);
}

void Checkpointer::on_output(const dem::World& w, const dem::RunState& state) {
  if (every_ > 0 && state.outputs % static_cast<std::uint64_t>(every_) == 0) {
    save(w, state);
    if (saved) saved(w, state);
  }
}

void Checkpointer::on_stop(const dem::World& w, const dem::RunState& state, const dem::RunOutcome& outcome) {
  // A stopped run goes on from here; a completed one's last state is where
  // another run may start (--from).
  if (outcome.status == dem::RunStatus::Stopped || (outcome.status == dem::RunStatus::Completed && every_ > 0))
    save(w, state);
}

RunInfoWriter::RunInfoWriter(fs::path file, const std::string& info_json, const Checkpointer& clock)
    : file_(std::move(file)), info_json_(info_json), clock_(clock) {}

void RunInfoWriter::started(const dem::World& w, const dem::RunState& state) { write("running", w, state, ""); }

void RunInfoWriter::on_stop(const dem::World& w, const dem::RunState& state, const dem::RunOutcome& outcome) {
  switch (outcome.status) {
    case dem::RunStatus::Completed:
      write("completed", w, state, "");
      break;
    case dem::RunStatus::Stopped:
      write("interrupted", w, state, "");
      break;
    case dem::RunStatus::Failed:
      write("failed", w, state, outcome.error);
      break;
  }
}

void RunInfoWriter::on_warning(const dem::World& w, const dem::RunState& state, const std::string& message) {
  warnings_.push_back("t = " + std::to_string(w.time) + " s: " + message);
  write("running", w, state, "");
}

void RunInfoWriter::write(const std::string& status, const dem::World& w, const dem::RunState& state,
                          const std::string& error) {
  nlohmann::ordered_json info = nlohmann::ordered_json::parse(info_json_);
  info["status"] = status;
  if (status == "interrupted" && !stopped_by.empty()) info["stopped_by"] = stopped_by;
  else if (status == "interrupted" && ranks > 1) info["stopped_by"] = "another rank's stop request";  // not rank 0's
  if (!error.empty()) info["error"] = error;
  for (const std::string& warning : warnings_) info["warnings"].push_back(warning);
  info["ranks"] = ranks;
  info["steps"] = state.step;
  info["steps_total"] = state.steps_total;
  info["simulated_time"] = w.time;
  info["frames"] = state.outputs;
  info["bodies_now"] = w.bodies.size();
  if (w.broken > 0) info["grains_broken"] = w.broken;  // breakage (docs/breakage.md)
  if (!w.bonds.empty()) info["bonds"] = w.bonds.size(), info["bonds_broken"] = dem::broken_bonds(w.bonds);
  info["wall_time_s"] = clock_.wall_seconds();
  write_file_atomically(file_, info.dump(2) + "\n");
}

RunFolderWriters::RunFolderWriters(const RunPaths& folder, const dem::World& world, const RunWriterOptions& options)
    : RunFolderWriters(folder, world, options, nullptr) {}

RunFolderWriters::RunFolderWriters(const RunPaths& folder, const dem::World& world, const RunWriterOptions& options,
                                   const Checkpoint& restored)
    : RunFolderWriters(folder, world, options, &restored) {}

RunFolderWriters::RunFolderWriters(const RunPaths& folder, const dem::World& world, const RunWriterOptions& options,
                                   const Checkpoint* restored)
    : frames_(folder.frames(), world, options.frames),
      view_(folder.view(), world, options.view, restored ? restored->run.outputs : 0),
      trace_(options.traced),
      checkpoints_(folder.checkpoint(), options.checkpoint_every, options.fingerprint, frames_, trace_, energy_, cell_,
                   restored ? restored->logs.wall_seconds : 0),
      info_(folder.run_json(), options.info_json, checkpoints_) {
  energy_.applied = world.applied_loads;
  energy_.splits = dem::world_breaks(world);
  if (restored) {
    frames_.frames = restored->logs.frames;
    trace_.resume(folder.trace(), restored->logs.trace_bytes);
    energy_.resume(folder.energy(), restored->logs.energy_bytes);
    if (world.cell.now.active()) cell_.resume(folder.cell(), restored->logs.cell_bytes);
  } else {
    trace_.start(folder.trace(), trace_header());
    energy_.start(folder.energy(), energy_header({.applied = energy_.applied, .split = energy_.splits}));
    if (world.cell.now.active()) cell_.start(folder.cell(), cell_header());
  }
  // After a kill, run.json tells how far the last checkpoint got.
  checkpoints_.saved = [this](const dem::World& w, const dem::RunState& s) { info_.started(w, s); };
}

}  // namespace gjkdem::io
