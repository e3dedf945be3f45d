#pragma once
// Grains that break during a run (issue 31; docs/breakage.md): at the end of
// a step, each breakable grain whose stress (from the step's contact forces,
// break_criterion.hpp) reaches its strength splits in two along its break
// plane (split_body.hpp). The first fragment keeps the grain's id, the
// second takes the next free id; fragments get templates of their own, added
// after the builder's, and their draws of strength come from their
// generation, so that a fragment is stronger as it is smaller.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

/// Whether a body of template `t` and material `m` can break: moving, of a
/// material with a strength, one solid polyhedron or box (curved shapes,
/// compounds and surface grains do not split yet), and not smaller than the
/// material's `unbreakable_below`.
bool breakable(const ShapeTemplate& t, const Material& m, const Body& b) noexcept;

/// The most bodies a grain of template `t` and material `m` can add by
/// breaking again and again: each split leaves at least (3/4)^3 of a grain
/// on either side (a plane through a convex body's centroid, Gruenbaum
/// 1960) and only grains of volume pi s^3 / 6 or more break (s:
/// `unbreakable_below`), so it ends in at most (64/27) (d / s)^3 fragments
/// (d: its size, grain_size). 0 for a grain that cannot break. The builder
/// reserves room for them: the bodies never move in memory (Python's views
/// of them stay valid).
std::uint64_t most_fragments(const ShapeTemplate& t, const Material& m) noexcept;
/// The same, summed over the world's moving bodies (a real: no overflow).
Real most_fragments(const World& world) noexcept;

/// Whether any material of the world has a strength (then every step ends
/// with break_grains).
bool world_breaks(const World& world) noexcept;

/// A grain's size for its strength: the diameter of the sphere of its
/// volume (m), sphere_diameter of its volume.
Real grain_size(const ShapeTemplate& t) noexcept;
Real sphere_diameter(Real volume) noexcept;

/// A fragment's template: its solid (in the fragment's shape frame), its
/// generation, and its closed surface where the world has surface grains.
/// The one way a fragment's template is made: at the split from the piece
/// itself, elsewhere (a checkpoint, another rank) from make_polytope of the
/// piece's vertices, which gives the piece again bit for bit
/// (tests/shape/split_test.cpp).
ShapeTemplate fragment_template(const Polytope& solid, std::uint32_t generation, bool with_surface);

/// How many of the world's templates its builder made: those of generation
/// 0, which come first.
std::size_t built_templates(const World& world) noexcept;

/// A grain that breaks and what it becomes: its two fragments' hulls (about
/// their centroids, on the grain's shape axes), states and templates (made by
/// fragment_template from those hulls, so a domain that is sent the hulls
/// makes the same templates).
struct GrainSplit {
  std::uint64_t parent = 0;      ///< the grain's id
  std::uint32_t generation = 0;  ///< of the fragments
  bool surface = false;          ///< the fragments' templates take closed surfaces
  struct Piece {
    std::vector<Vec3> vertices;
    Vec3 position;
    Quat orientation;
    Vec3 velocity;
    Vec3 angular_momentum;
  };
  std::array<Piece, 2> fragments{};
  std::array<ShapeTemplate, 2> templates{};
};

/// The grains whose stress at the last force evaluation reaches their
/// strength, in id order: those of the world, or those a domain owns
/// (`domain` not null), whose contacts it lists in full.
std::vector<GrainSplit> find_splits(const World& world, const DomainRole* domain);

/// Carries out `splits` (in id order): their templates appended in order,
/// the first fragment of each in its grain's place with its id, the second
/// appended with the next of the ids from `next_id`, the grains' pairs
/// dropped, every box made again where the bodies are. A domain holding a grain (owned or
/// not) places its fragments; every domain appends every template, so that
/// template indices agree across ranks.
void apply_splits(World& world, std::span<GrainSplit> splits, std::uint64_t next_id, DomainRole* domain);

/// Splits every breakable grain of the world whose stress at the last force
/// evaluation (world.results.contacts, whose forces are current) reaches its
/// strength, in id order; its pairs' springs are dropped, its fragments
/// start with no force (the world's forces are no longer current) and every
/// box is made again where the bodies are. Returns how many grains broke. A
/// domain run breaks its domains' grains with break_domain_grains
/// (domains.hpp).
int break_grains(World& world);

}  // namespace gjkdem::dem
