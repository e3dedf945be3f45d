#pragma once
// Checkpoints: everything a stopped run needs to continue bit for bit, in a
// portable, self-describing binary format (docs/checkpoints.md):
//
//   magic "GJKDEMCK" | u32 format version | u32 header bytes (40) |
//   u64 payload bytes | u64 checksum (FNV-1a 64 of the payload) |
//   u64 scene fingerprint | payload
//
// Every number is little-endian (IEEE-754 doubles, unsigned integers), written
// field by field, never as a struct (no padding, no machine byte order). The
// payload is a list of sections, each a four-letter tag and a u64 length,
// the first (INFO) the text naming the format and its sections; their
// layout is docs/checkpoints.md's (the body section's columns come from
// body_channels.hpp). A reader refuses another format version, a checksum that
// does not match, a checkpoint of another scene (its fingerprint), and any
// count or length that does not fit in the file, each with a message saying so.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gjkdem/dem/run.hpp"

namespace gjkdem::io {

struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr std::uint32_t kCheckpointVersion = 11;

/// What a run folder keeps beside the world and the run state.
struct RunLogState {
  std::uint64_t trace_bytes = 0;   ///< size of trace.csv at the checkpoint
  std::uint64_t energy_bytes = 0;  ///< size of energy.csv then
  std::uint64_t cell_bytes = 0;    ///< size of cell.csv then (periodic worlds)
  double wall_seconds = 0;         ///< run time before this point
  std::vector<std::pair<std::string, Real>> frames;  ///< frame files and times so far
};

struct Checkpoint {
  dem::RunState run;
  RunLogState logs;
};

/// FNV-1a 64 of some bytes: the scene fingerprint and the payload checksum.
std::uint64_t fnv1a64(std::string_view bytes) noexcept;

/// The checkpoint as bytes.
std::string encode_checkpoint(const dem::World& world, const Checkpoint& checkpoint, std::uint64_t fingerprint);

/// How a checkpoint is taken up.
enum class Restore {
  SameRun,  ///< the run it was saved from goes on (its clock; the scene's fingerprint must match)
  NewRun,   ///< a new run starts from its state: time 0, no wall work yet, forces recomputed, any fingerprint
};

/// Restores bytes into a world built with the same bodies, shapes and walls
/// (ids, shape digests, fixed bodies' places, plane walls; materials and
/// settings may differ). Throws CheckpointError, naming `name` and what
/// differs, for anything that does not fit.
Checkpoint decode_checkpoint(std::string_view bytes, dem::World& world, std::uint64_t fingerprint,
                             const std::string& name, Restore how = Restore::SameRun);

/// Written to a temporary file, flushed and renamed, so a crash never leaves
/// half a checkpoint. Throws std::runtime_error when it cannot be written.
void save_checkpoint(const std::filesystem::path& file, const dem::World& world, const Checkpoint& checkpoint,
                     std::uint64_t fingerprint);

/// The fragments' templates of a checkpoint (grains that broke,
/// docs/breakage.md) appended to a world made from the run's scene, after
/// its own: what the run's frames name. Throws CheckpointError.
void load_fragment_templates(const std::filesystem::path& file, dem::World& world);

Checkpoint load_checkpoint(const std::filesystem::path& file, dem::World& world, std::uint64_t fingerprint,
                           Restore how = Restore::SameRun);

}  // namespace gjkdem::io
