#pragma once
// Running a world: advancing it to a time in fixed steps, with observers
// called at the output cadence (frames, logs and checkpoints are observers,
// io/run_observers.hpp; so are viewers and Python callbacks), the energy
// balance, and a stop request polled between steps. A run that stops can be
// continued from its RunState and the world (a checkpoint holds both).
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem {

/// Where a run stands. Everything here is saved in a checkpoint.
struct RunState {
  Real dt = 0;                        ///< s
  std::uint64_t steps_total = 0;      ///< the run ends after this many steps
  std::uint64_t steps_per_output = 1; ///< observers see the world every this many steps (and at the end)
  std::uint64_t step = 0;             ///< steps done
  std::uint64_t outputs = 0;          ///< outputs done (the first, at step 0, included)
  Real initial_energy = 0;            ///< kinetic + potential + elastic at the start (J)
};

/// A run of `duration` seconds in steps of dt, an output every `output_every`
/// seconds (rounded to whole steps, at least one). Throws std::invalid_argument
/// unless 0 < dt <= duration, 0 < output_every, all finite, and the run takes
/// fewer than 2^53 steps.
RunState plan_run(Real duration, Real dt, Real output_every);

/// Where the energy went (J): dissipated = initial + wall_work + inflow +
/// applied_work + split - kinetic - potential - elastic, what damping and
/// friction took out of the system; wall_work is what driven walls and
/// bodies put in (World::wall_work), inflow what inserted bodies brought
/// (InflowState), applied_work what applied loads did (the bodies'
/// Body::applied_work, in id order), split what the splits of broken grains
/// stored in their fragments' contacts (World::split_energy).
struct EnergyBalance {
  Real kinetic = 0, potential = 0, elastic = 0, dissipated = 0, wall_work = 0, inflow = 0, applied_work = 0, split = 0;
};

EnergyBalance energy_balance(const World& world, Real initial_energy) noexcept;

/// What the run loop does when it sees a run blowing up.
enum class GuardAction {
  Stop,  ///< fail the run with the guard's message (the default)
  Warn,  ///< tell the observers (on_warning) once per guard and go on
  Off,   ///< check nothing but finiteness
};

/// The physics guards, checked before the first step and at every output:
/// - the time step against the stability limit of the stiffest contact
///   (stable_time_step);
/// - a body travelling more than `max_travel` of its reach in one step (a
///   fast body tunnels through others: contacts are missed), and a driven
///   wall or body travelling more than that of the smallest moving body's;
/// - energy appearing from nowhere: kinetic + elastic energy exceeding what
///   the start, the loss of potential energy, the work of driven walls and
///   the bodies inflows brought can supply by more than `max_energy_gain` of that supply (1: the energy
///   doubled).
/// Whatever the action, a run whose state or energy is not finite fails.
struct RunGuards {
  GuardAction action = GuardAction::Stop;
  Real max_travel = 0.5;       ///< fraction of a body's reach per step
  Real max_energy_gain = 1.0;  ///< unexplained energy, relative to what the start and gravity supply
};

enum class RunStatus {
  Completed,  ///< all steps done
  Stopped,    ///< the stop request was seen; continue with run() again
  Failed,     ///< `error` says why; the world is left where it failed
};

struct RunOutcome {
  RunStatus status = RunStatus::Completed;
  std::string error;
};

/// Sees a run. Observers are called in the order given; an exception thrown
/// by one fails the run with its message (thrown by on_step: before the
/// next step).
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  /// At step 0 of a new run and every steps_per_output steps (and after the
  /// last step): the world after `state.step` steps, `state.outputs` counting
  /// this output.
  virtual void on_output(const World& world, const RunState& state) = 0;
  /// After every step (keep it cheap).
  virtual void on_step(const World& /*world*/, const RunState& /*state*/) {}
  /// A guard saw trouble and the run goes on (GuardAction::Warn).
  virtual void on_warning(const World& /*world*/, const RunState& /*state*/, const std::string& /*message*/) {}
  /// When run() returns.
  virtual void on_stop(const World& /*world*/, const RunState& /*state*/, const RunOutcome& /*outcome*/) {}
};

/// What a step listener may change: the moving bodies of the world a rank
/// steps that it owns (a whole world's: every moving body; fixed bodies
/// belong to no rank). Their applied loads (Body::applied_force,
/// applied_torque) are the channel for forces from outside; a listener may
/// also set velocities. Changes to other bodies are lost, or differ between
/// rank counts.
struct OwnedBodies {
  World& world;                      ///< the whole world, or a rank's domain of it
  const DomainRole* role = nullptr;  ///< null: the world is whole
  bool owns(std::size_t i) const noexcept { return !world.bodies[i].fixed && (!role || role->owns(i)); }
};

/// Takes part in a run from outside the engine (a fluid coupling, a field,
/// a controller): called on every rank before the force evaluations at
/// step 0 and at every `every()` steps, with the state at that step's end
/// (positions moved, velocities half kicked) and `state.step` the steps
/// done before it. Applied loads set here act from that evaluation on; a
/// resumed run calls it where the run that did not stop did, and the loads
/// it set last come back from the checkpoint. An exception fails the run
/// with its message. What it does must depend on each body alone (its own
/// state, its id): then the run gives the same bits for any thread or rank
/// count.
class StepListener {
 public:
  virtual ~StepListener() = default;
  virtual std::uint64_t every() const { return 1; }
  virtual void before_forces(OwnedBodies bodies, const RunState& state) = 0;
};

/// Advances `world` until state.steps_total, calling the observers.
/// `stop_requested` (optional) is asked before every step. On a new run
/// (state.step == 0 and no output yet) the forces are evaluated, the initial
/// energy recorded and the first output made before the first step. The
/// loop is run_domains's (domains.hpp) on one rank: one loop for every run.
/// Step listeners (a run with any sets World::applied_loads) are called in
/// the order given.
RunOutcome run(World& world, RunState& state, std::span<RunObserver* const> observers,
               const std::function<bool()>& stop_requested = {}, const RunGuards& guards = {},
               std::span<StepListener* const> listeners = {});

/// The longest stable time step (s) of the world's stiffest contact: 2 / omega
/// of the stiffest linear or volume contact (for the volume law, a face of
/// the body's cross-section pressed in), the Rayleigh time step over the
/// Mindlin factor for Hertz (world.hpp).
/// Infinite without moving bodies. (critical_time_step is a safe fraction
/// of it.)
Real stable_time_step(const World& world);

/// What the guards find in the world's state now (empty: nothing), given the
/// run's time step and initial energy.
std::string check_guards(const World& world, const RunState& state, const RunGuards& guards);

/// What fails a run whatever the guards: a body whose state is not finite,
/// or an energy that is not (the message; "" when all is finite).
std::string check_finite(const World& world);

/// A message for a failed step, naming the pair.
std::string describe_failure(const World& world, const StepReport& report);

}  // namespace gjkdem::dem
