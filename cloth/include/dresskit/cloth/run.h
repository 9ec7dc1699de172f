#pragma once
// Running a simulation: steps a ClothSimulator until a duration, a failed step or rest, hands each
// frame to a callback and sums what the steps did. The one step loop of the toolkit (the CLI, the
// demo's dressing and the benches call it).
#include <functional>
#include <string>
#include <vector>

#include "dresskit/cloth/simulator.h"

namespace dresskit::cloth {

/// When a run counts as at rest and stops early (the energy-based termination of a static drape):
/// the cloth's kinetic energy, as the RMS particle speed √(2 E_kin / M), and its fastest particle
/// both stay below their thresholds for `time` of simulated time.
struct RestOptions {
  bool enabled = true;
  double mean_speed = 0.01;  ///< RMS particle speed [m/s]
  double max_speed = 0.05;   ///< fastest free particle [m/s]
  double time = 0.25;        ///< [s] both must hold this long
  /// A run is never at rest before this much simulated time [s] (a cloth released from rest has no
  /// speed at its first step).
  double earliest = 0.1;
};

/// When a run counts as stalled and fails: its steps have stayed within `factor` of the simulator's
/// smallest step (SimulationOptions::dt_min) for `steps` steps in a row. The adaptive step falls
/// that far only where contacts and length limits cannot all hold (a garment too small for the
/// body pressed against it and itself); at that step a run would take hours of steps for a second.
struct StallOptions {
  bool enabled = true;
  int steps = 50;
  double factor = 4.0;  ///< [unitless]
};

struct RunOptions {
  double duration = 2.0;  ///< simulated time at most [s]
  double fps = 24.0;      ///< frames per simulated second [1/s]
  RestOptions rest;
  StallOptions stall;
  /// Steps at most (0: no bound). A run that reaches it stops with its state kept, stopped_reason
  /// "step limit reached" and a warning saying how far it got: a bound that follows from the run
  /// (callers give a multiple of duration / dt), so that no input makes a run take hours of steps.
  int max_steps = 0;
  /// Optional check after every step (after on_step): a non-empty answer fails the run with it as
  /// the reason (a bench's energy bound, a caller's own limit).
  std::function<std::string()> fail_if;
};

/// What the steps of a run did, summed (times: CPU seconds of the stepping thread).
struct StepTotals {
  int steps = 0, retries = 0, cg_iterations = 0, collisions = 0, tunnelling = 0, deep_pushes = 0;
  int held_steps = 0;  ///< steps whose cloth–cloth pass held every particle (its last resort)
  /// Projective dynamics: steps whose iterations stopped moving (SimulationOptions::
  /// iteration_tolerance) while a free particle still had at least half the heaviest particle's
  /// weight unbalanced: the solver, not the forces, held the cloth (springs too stiff for the
  /// step), and the largest such unbalanced force over that weight [unitless].
  int stuck_steps = 0;
  double worst_stuck = 0.0;
  double smallest_dt = 0.0;  ///< [s] (0 before any step)
  SelfCollisionResult self;  ///< summed over the steps
  double force_seconds = 0, integrate_seconds = 0, constraint_seconds = 0, seam_seconds = 0,
         collision_seconds = 0, self_collision_seconds = 0;
  void add(const StepResult& r);
};

struct RunResult {
  bool ok = true;              ///< false: a step failed (the simulator keeps the last good state)
  /// "at rest", "duration reached", "step limit reached", "stalled: <why>" or "failed: <why>"
  std::string stopped_reason;
  bool stalled = false;        ///< stopped for its steps staying near the smallest (StallOptions)
  std::string failure;         ///< the failed step's reason (empty when ok)
  int frames = 0;              ///< frames handed out after the first (frame 0 is the start)
  double rest_at = -1.0;       ///< simulated time the cloth came to rest [s] (−1: it did not)
  double mean_speed = 0.0, max_speed = 0.0;  ///< at the end [m/s]
  StepTotals totals;
  /// What the caller should tell the user although the run succeeded (one line each): a quarter or
  /// more of the steps stuck (StepTotals::stuck_steps), so "at rest" or the end shape is the
  /// solver's doing.
  std::vector<std::string> warnings;
};

/// RMS speed √(2 E_kin / M) and fastest free particle of the simulator's state [m/s].
void cloth_speeds(const ClothSimulator& sim, double& mean_speed, double& max_speed);

/// Steps sim until `duration`, a failed step, a stall or rest. on_frame(k) is called with k = 0 before the
/// first step and with k = 1, 2, ... at the first state at or after k / fps; on_step (optional)
/// after every successful step.
RunResult run(ClothSimulator& sim, const RunOptions& options, const std::function<void(int)>& on_frame = {},
              const std::function<void(const StepResult&)>& on_step = {});

}  // namespace dresskit::cloth
