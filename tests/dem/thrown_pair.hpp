#pragma once
// Two bodies thrown at each other (issue 54, points 3 and 17), the class of
// Run.NoTwoConvexBodiesPassThroughEachOtherSilently and
// SurfaceGrain.NoTwoSurfaceGrainsPassThroughEachOtherSilently.
#include <string>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"

namespace gjkdem::dem {

struct ThrownPair {
  ContactModel model = ContactModel::Hertz;
  BodyShape shape;
  Quat below, above;        // the bodies' rotations
  Real density_ratio = 1;   // of the one from below, the other's 2500 kg/m^3
  Real speed = 1;           // each one's, along z (m/s)
  Real start = 0.007;       // each centre's distance from z = 0 at the start (m)
  Real travel = 0.03;       // how far each goes in the run (m): met, and gone past
};

// "" when the two bounced (each kept its side) or the run stopped naming
// the pair (passing through, pierced, wholly inside) or the travel guard
// named a body; else what went wrong. The energy guard is lifted: the
// passing itself must be caught, not the energy it makes.
inline std::string thrown_pair_verdict(const ThrownPair& p) {
  WorldSettings settings;
  settings.model = p.model;
  settings.gravity = {};
  WorldBuilder b(settings);
  const std::uint32_t light = b.add_material({"light", 2500, 1e7, 0.25, 0.5, 0.3});
  const std::uint32_t heavy = b.add_material({"heavy", 2500 * p.density_ratio, 1e7, 0.25, 0.5, 0.3});
  b.add_body({.shape = p.shape, .material = heavy, .position = {0, 0, -p.start}, .rotation = p.below,
              .velocity = {0, 0, p.speed}, .label = "below"});
  b.add_body({.shape = p.shape, .material = light, .position = {0.0003, 0.0002, p.start}, .rotation = p.above,
              .velocity = {0, 0, -p.speed}, .label = "above"});
  World w = b.build();
  RunState run = plan_run(p.travel / p.speed, critical_time_step(w), p.travel / 50 / p.speed);
  RunGuards guards;  // the travel guard as it is: faster, a body jumps past the other in a step
  guards.max_energy_gain = 1e9;
  const RunOutcome o = dem::run(w, run, {}, {}, guards);
  if (o.status == RunStatus::Failed) {
    for (const char* said : {"body 0 and body 1 are passing through each other", "passed through the other",
                             "lies wholly inside the other", "of its size in one step"})
      if (o.error.find(said) != std::string::npos) return "";
    return "stopped for another reason: " + o.error;
  }
  if (w.bodies[0].position.z < w.bodies[1].position.z) return "";
  return "through each other, silently";
}

}  // namespace gjkdem::dem
