#pragma once
// A world's state written as a scene: a settled bed reused as the start of
// other studies, edited as any scene is (docs/scenes.md, "A run's state as
// a scene").
#include <filesystem>
#include <string>
#include <string_view>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::io {

/// The scene `scene_text` (its files relative to `base_dir`) with its bodies,
/// generators and inflows replaced by `world`'s bodies as they are now: one
/// [[body]] each (material, position, rotation, velocity, angular velocity,
/// name; fixed ones, a generator's rough floor included, as fixed), their
/// shapes in the [shapes] table, one per template (`state_<k>`).
/// Everything else (settings, materials, walls, driven bodies with their
/// motions) is the scene's own, its files named by absolute paths; a
/// periodic cell takes the world's bounds. `header` opens the text as a
/// comment.
/// Throws SceneError for what a scene cannot express yet (a sheared cell,
/// the bonds of bonded assemblies).
std::string export_scene(std::string_view scene_text, const std::filesystem::path& base_dir, const dem::World& world,
                         std::string_view header);

/// The last saved state of a run folder (its checkpoint.bin) as a scene.
std::string export_run_scene(const std::filesystem::path& run_dir);

}  // namespace gjkdem::io
