#pragma once
// Inflow: a region (a box, a cylinder or disc, a ball) that inserts bodies during a run, at a rate in bodies
// or kilograms per second, each at a random place and orientation where it
// touches nothing (an exact test against every body near it and the plane
// walls). What each body looks like (its variant, drawn with the inflow's
// number probabilities) and where it goes are drawn from a counter-based
// generator keyed by the inflow's seed, the body's number and the attempt,
// so a run gives the same bodies for any thread count and after a resume:
// an inflow's state is three numbers (InflowState, saved in checkpoints).
//
// Body n (from 0) is due once the clock passes start + n / rate, or, for a
// mass rate, once mass_rate (t - start) covers the mass inserted before it
// plus half its own; none after `stop` or beyond `count`. A body that finds
// no room in kInflowAttemptsPerStep tries stays due: the inflow falls behind
// (InflowState::behind counts the steps) until its region clears.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "gjkdem/dem/body.hpp"
#include "gjkdem/dem/periodic.hpp"
#include "gjkdem/dem/round_region.hpp"
#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

struct Body;
struct World;

inline constexpr int kInflowAttemptsPerStep = 8;

struct Inflow {
  std::vector<std::uint32_t> templates;  ///< one per variant (World::templates)
  std::vector<Real> cumulative;          ///< number probabilities of the variants, summed; the last is 1
  Vec3 lo, hi;                           ///< the region where bodies' centres of mass are placed (m), or its bounding box
  std::optional<RoundRegion> round{};    ///< a cylinder (a disc when flat) or ball instead of the box
  std::uint32_t material = 0;
  Vec3 velocity;                         ///< of inserted bodies (m/s)
  Real rate = 0;                         ///< bodies per second (0: mass_rate instead)
  Real mass_rate = 0;                    ///< kg per second
  Real start = 0;                        ///< s
  Real stop = std::numeric_limits<Real>::infinity();  ///< s
  std::uint64_t count = 0;               ///< most bodies inserted (0: no limit but `stop`)
  std::uint64_t seed = 0;
};

struct InflowState {
  std::uint64_t inserted = 0;  ///< bodies so far
  std::uint64_t attempts = 0;  ///< placements tried so far (keys the draws)
  Real mass = 0;               ///< kg so far
  Real energy = 0;             ///< kinetic and potential energy the bodies brought in (J)
  std::uint64_t behind = 0;    ///< steps that ended with a due body unplaced
};

/// The variant body n of an inflow takes.
std::uint32_t inflow_variant(const Inflow& inflow, std::uint64_t n) noexcept;

/// The most bodies an inflow can insert, from its count, or its rate and
/// time span (its lightest variant for a mass rate).
std::uint64_t inflow_capacity(const Inflow& inflow, const Makeup& makeup) noexcept;

/// The builder refuses inflows that could insert more.
inline constexpr std::uint64_t kMaxInflowBodies = 10'000'000;

/// What the inflows read of the world when they place bodies at `time`:
/// the make-up of what they insert, the plane walls and periodic cell a new
/// body must keep clear of, and gravity (the energy a body brings in).
struct InflowSite {
  Makeup makeup;
  std::span<const PlaneWall> planes;
  PeriodicCell cell;
  Real time = 0;
  Vec3 gravity;
};
/// A world's (world.hpp).
InflowSite inflow_site(const World& world);

/// Inserts the bodies the inflows owe at site.time, clear of `bodies`, and
/// appends them to it with the next ids (from `next_id`: a domain run
/// places them among the bodies near the regions only). Returns how many.
std::size_t run_inflows(std::span<const Inflow> inflows, std::span<InflowState> states, const InflowSite& site,
                        std::vector<Body>& bodies, std::uint64_t next_id);

/// Whether an inflow owes a body at `time`.
bool inflows_due(std::span<const Inflow> inflows, std::span<const InflowState> states, const Makeup& makeup,
                 Real time);

/// Whether a body (moved by `shift`: a periodic image) lies near enough to
/// the inflow's region to stop a body from being placed there.
bool near_inflow(std::span<const ShapeTemplate> templates, const Inflow& inflow, const Body& body,
                 const Vec3& shift = {}) noexcept;

/// A uniform number in [0, 1) from a key (splitmix64 of the key's parts).
Real keyed_uniform(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c) noexcept;

}  // namespace gjkdem::dem
