// The engine as a library: a world built in code (no scene file), run with an
// observer that prints the energy balance, checkpointed to memory half way
// and continued. Build: part of the project; or, with gjkdem installed,
//   find_package(gjkdem) and target_link_libraries(pour PRIVATE gjkdem::gjkdem).
#include <cstdio>
#include <random>

#include "gjkdem/dem/run.hpp"
#include "gjkdem/dem/world_builder.hpp"
#include "gjkdem/io/checkpoint.hpp"
#include "gjkdem/shape/shape_factories.hpp"

using namespace gjkdem;

// Prints time, contacts and the energy balance at every output.
class EnergyPrinter : public dem::RunObserver {
 public:
  void on_output(const dem::World& world, const dem::RunState& state) override {
    const dem::EnergyBalance e = dem::energy_balance(world, state.initial_energy);
    std::printf("t = %.3f s  contacts %4d  kinetic %.3e J  dissipated %.3e J\n", world.time, world.stats.contacts,
                e.kinetic, e.dissipated);
  }
};

int main() {
  dem::WorldSettings settings;  // the volume law, gravity -z
  dem::WorldBuilder builder(settings);
  const std::uint32_t rock = builder.add_material({"rock", 2500, 1e7, 0.25, 0.4, 0.5});
  builder.add_box_walls({-0.05, -0.05, 0}, {0.05, 0.05, 0.2}, /*open_top=*/true, 0.01, rock, "box");
  std::mt19937_64 rng(1);
  dem::RegionFill fill;
  for (int k = 0; k < 10; ++k) fill.variants.push_back({random_polyhedron(12, 0.015, rng), {}});
  fill.count = 100;
  fill.lo = {-0.05, -0.05, 0.02};
  fill.hi = {0.05, 0.05, 0.2};
  fill.material = rock;
  fill.label = "grains";
  builder.fill_region(fill, rng);
  builder.add_body({.shape = {Shape{Ellipsoid{{0.01, 0.006, 0.004}}}, {}}, .material = rock,
                    .position = {0, 0, 0.25}, .velocity = {0, 0, -1}, .label = "pebble"});
  dem::World world = builder.build();

  dem::RunState run = dem::plan_run(0.2, dem::critical_time_step(world), 0.02);
  EnergyPrinter printer;
  dem::RunObserver* observers[] = {&printer};
  // Stop half way, keep a checkpoint in memory, continue from it.
  dem::RunOutcome outcome = dem::run(world, run, observers, [&] { return run.step == run.steps_total / 2; });
  const std::string saved = io::encode_checkpoint(world, {run, {}}, /*fingerprint=*/0);
  std::printf("stopped at t = %.3f s; checkpoint of %zu bytes\n", world.time, saved.size());
  const io::Checkpoint restored = io::decode_checkpoint(saved, world, 0, "memory");
  run = restored.run;
  outcome = dem::run(world, run, observers);
  std::printf("%s after %llu steps of %.2e s\n", outcome.status == dem::RunStatus::Completed ? "completed" : "failed",
              static_cast<unsigned long long>(run.step), run.dt);
  return outcome.status == dem::RunStatus::Completed ? 0 : 1;
}
