#pragma once
// Scenes: the TOML files of ../shared/spec/scene-format.md (and the keys this
// project adds, docs/scenes.md) turned into a World and the settings of a run.
// An I/O boundary: everything is validated before a run starts, and every
// problem is a SceneError naming the key or file and the line.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/run_output.hpp"

namespace gjkdem::io {

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Scene {
  dem::World world;
  Real duration = 0;            ///< s of simulated time
  Real dt = 0;                  ///< s (resolved when the scene said "auto")
  bool dt_auto = true;
  std::uint64_t seed = 1;
  std::string output_dir = "out";
  Real output_every = 0;        ///< s between frames
  bool overwrite = false;
  int checkpoint_every = kDefaultCheckpointEvery;  ///< frames between checkpoints (0: none)
  bool write_frames = true;
  bool write_view = true;       ///< view/ frames (docs/view-format.md)
  dem::RunGuards guards;        ///< [simulation].guards: "stop" (default), "warn" or "off"
  std::string resolved_json;    ///< the scene with its defaults filled in (JSON object)
  std::vector<std::string> warnings;  ///< meshes convexified and the like
};

/// Reads a scene from TOML text. `source` names it in messages; relative
/// file names (meshes) are taken from `base_dir`; `progress` hears what a
/// long build starts on (WorldBuilder::set_progress).
Scene load_scene(std::string_view toml_text, const std::string& source, const std::filesystem::path& base_dir,
                 const dem::BuildProgress& progress = {});

/// One shape in the scene's vocabulary (docs/scenes.md, "Shapes"), and the
/// warnings reading it gave (a mesh that was not convex, ...).
struct SceneShape {
  dem::BodyShape shape;
  std::vector<std::string> warnings;
};

/// A SHAPE table given as TOML inline-table text (`{ type = "platonic", name
/// = "cube", size = 0.02 }`), as a scene's body takes it; files relative to
/// `base_dir`; a random_polyhedron drawn once from `seed`. Throws SceneError
/// naming `where`. Python's gjkdem.Shape reads the scenes' own types so.
SceneShape read_scene_shape(std::string_view toml_inline_table, const std::filesystem::path& base_dir,
                            const std::string& where, std::uint64_t seed = 1);

/// The text of a file (SceneError "cannot read FILE" when it cannot be read).
std::string read_text_file(const std::filesystem::path& file);

/// Reads a scene file (throws SceneError when it cannot be read).
Scene load_scene_file(const std::filesystem::path& file);

/// The built-in default scene: about 2,000 random polyhedra in a hopper,
/// discharged onto a floor.
std::string_view default_scene_toml();

}  // namespace gjkdem::io
