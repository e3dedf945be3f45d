#pragma once
// The scratch of a step: everything a step computes and throws away, kept in
// the world only so that its memory is reused (what an evaluation finds and
// outputs read is its results: step_results.hpp). Nothing here survives into a
// checkpoint; a world restored without it rebuilds it on its first step.
// (What the broad phase keeps that a bit-exact resume needs is state:
// World::search. What passes between the halves of a step, and a domain's
// role in a domain run, is the step's context: step_context.hpp.)
#include <array>
#include <cstdint>
#include <utility>
#include <span>
#include <vector>

#include "gjkdem/contact/overlap.hpp"
#include "gjkdem/dem/broad_phase.hpp"
#include "gjkdem/dem/contact_geometry.hpp"
#include "gjkdem/dem/motion.hpp"
#include "gjkdem/dem/periodic.hpp"
#include "gjkdem/dem/pair_state.hpp"
#include "gjkdem/dem/step_results.hpp"
#include "gjkdem/dem/surface_contact.hpp"

namespace gjkdem::dem {

/// Which kinds of template a world holds, so that a stage serving one kind
/// skips the contact list of a world without it. During a run templates are
/// only appended (breakage's fragments), never changed: the templates from
/// `seen` on are all that can add a kind (step.cpp).
struct TemplateKinds {
  std::size_t seen = 0;         ///< templates looked at
  bool surface_grains = false;  ///< one is a surface grain (ShapeTemplate::surface_grain)
  bool wall_faces = false;      ///< one is a mesh wall piece (ShapeTemplate::wall_face)
};

struct StepWorkspace {
  TemplateKinds kinds;
  StaticTree fixed_tree;             ///< of the fixed bodies' boxes
  bool static_ready = false;         ///< fixed_tree and moving are built
  SweepWorkspace sweep;
  std::vector<BodyPair> candidates;  ///< body index pairs (i < j) whose boxes overlap, sorted
  std::vector<std::uint8_t> candidate_images;  ///< periodic worlds: the image of each pair's second body
  bool candidates_current = false;   ///< no box changed since the candidates were found
  std::vector<OverlapWorkspace> overlap;  ///< clipping buffers, one per thread
  std::vector<SurfaceScratch> surface;    ///< surface grains' buffers, one per thread
  std::vector<std::uint32_t> surface_listed;                   ///< contacts of surface grains before expansion
  std::vector<std::vector<SurfacePatchContact>> surface_found; ///< and their patches
  std::vector<GeometryStatus> surface_status;                  ///< and whether they could be found
  /// The listed contacts in jobs (surface_jobs: [begin, end) of surface_order):
  /// one contact, or a grain's contacts with the pieces of one mesh wall.
  std::vector<std::uint32_t> surface_order;
  std::vector<std::array<std::uint32_t, 2>> surface_jobs;
  std::vector<std::array<std::uint32_t, 3>> surface_walls;  ///< per listed contact: (grain, its part, wall group)
  std::vector<StepContact> expanded;      ///< the contact list being expanded (swapped with StepResults::contacts)
  std::vector<PairKey> expanded_keys;
  std::vector<std::uint32_t> moving;      ///< indices of the moving and driven bodies
  std::vector<Aabb> moving_boxes;         ///< their boxes, for the sweep (and their periodic images)
  std::vector<std::uint32_t> image_body;  ///< periodic worlds: the body of each swept box
  std::vector<std::uint8_t> image_code;   ///< and its image
};

}  // namespace gjkdem::dem
