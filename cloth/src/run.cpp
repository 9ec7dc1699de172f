#include "dresskit/cloth/run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dresskit::cloth {

void StepTotals::add(const StepResult& r) {
  ++steps;
  retries += r.retries;
  cg_iterations += r.solver_iterations;
  collisions += r.collisions;
  tunnelling += r.tunnelling;
  deep_pushes += r.deep_pushes;
  held_steps += r.self.held;
  if (r.unbalanced_end >= 0.5 && !r.iterations_ran_out) {
    ++stuck_steps;
    worst_stuck = std::max(worst_stuck, r.unbalanced_end);
  }
  smallest_dt = smallest_dt > 0.0 ? std::min(smallest_dt, r.dt) : r.dt;
  self.proximity_pairs += r.self.proximity_pairs;
  self.repulsions += r.self.repulsions;
  self.ccd_collisions += r.self.ccd_collisions;
  self.ccd_passes += r.self.ccd_passes;
  self.zones += r.self.zones;
  self.zone_particles += r.self.zone_particles;
  self.tangled_particles = std::max(self.tangled_particles, r.self.tangled_particles);
  force_seconds += r.force_seconds;
  integrate_seconds += r.integrate_seconds;
  constraint_seconds += r.constraint_seconds;
  seam_seconds += r.seam_seconds;
  collision_seconds += r.collision_seconds;
  self_collision_seconds += r.self_collision_seconds;
}

void cloth_speeds(const ClothSimulator& sim, double& mean_speed, double& max_speed) {
  const double mass = sim.model().mass.sum();
  mean_speed = mass > 0.0 ? std::sqrt(2.0 * sim.kinetic_energy() / mass) : 0.0;
  max_speed = 0.0;
  const Eigen::MatrixX3d& v = sim.velocities();
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (!sim.pinned()[i]) max_speed = std::max(max_speed, v.row(i).norm());
}

RunResult run(ClothSimulator& sim, const RunOptions& o, const std::function<void(int)>& on_frame,
              const std::function<void(const StepResult&)>& on_step) {
  RunResult result;
  const double start = sim.time(), end = start + o.duration;
  // A tolerance of a millionth of a step, so that a frame time reached by summing steps counts.
  const double eps = 1e-6 * sim.options().dt;
  if (on_frame) on_frame(0);
  double calm_since = -1.0;
  int tiny_steps = 0;
  const double tiny = o.stall.factor * sim.options().dt_min;
  while (sim.time() < end - eps) {
    const StepResult r = sim.step();
    if (!r.ok) {
      result.ok = false;
      result.failure = r.failure;
      result.stopped_reason = "failed: " + r.failure;
      break;
    }
    tiny_steps = r.dt <= tiny ? tiny_steps + 1 : 0;
    if (o.stall.enabled && tiny_steps >= o.stall.steps) {
      result.ok = false;
      result.stalled = true;
      result.failure = std::to_string(tiny_steps) + " steps in a row of at most " + std::to_string(tiny) +
                       " s at " + std::to_string(sim.time() - start) +
                       " s simulated (contacts and length limits cannot all hold)";
      result.stopped_reason = "stalled: " + result.failure;
      result.totals.add(r);
      break;
    }
    result.totals.add(r);
    if (on_step) on_step(r);
    if (o.fail_if) {
      const std::string why = o.fail_if();
      if (!why.empty()) {
        result.ok = false;
        result.failure = why;
        result.stopped_reason = "failed: " + why;
        break;
      }
    }
    if (sim.time() >= start + (result.frames + 1) / o.fps - eps) {
      ++result.frames;
      if (on_frame) on_frame(result.frames);
    }
    if (o.rest.enabled) {
      double mean = 0.0, fastest = 0.0;
      cloth_speeds(sim, mean, fastest);
      const bool calm = mean < o.rest.mean_speed && fastest < o.rest.max_speed;
      if (!calm) calm_since = -1.0;
      else if (calm_since < 0.0) calm_since = sim.time();
      if (calm && sim.time() - start >= o.rest.earliest && sim.time() - calm_since >= o.rest.time - eps) {
        result.rest_at = calm_since - start;
        result.stopped_reason = "at rest";
        break;
      }
    }
    if (o.max_steps > 0 && result.totals.steps >= o.max_steps && sim.time() < end - eps) {
      result.stopped_reason = "step limit reached";
      char line[200];
      std::snprintf(line, sizeof line, "stopped at the step limit (%d steps) after %.3g of %.3g s simulated: not at rest",
                    o.max_steps, sim.time() - start, o.duration);
      result.warnings.emplace_back(line);
      break;
    }
  }
  if (result.stopped_reason.empty()) result.stopped_reason = "duration reached";
  const StepTotals& s = result.totals;
  if (s.stuck_steps > 0 && 4 * s.stuck_steps >= s.steps) {
    char line[320];
    std::snprintf(line, sizeof line,
                  "projective dynamics stopped moving with forces unbalanced in %d of %d steps (up to %.3g "
                  "times a particle's weight): the cloth is held by the solver, not by its forces; its "
                  "springs are too stiff for this step (use the implicit integrator with a smaller dt)",
                  s.stuck_steps, s.steps, s.worst_stuck);
    result.warnings.emplace_back(line);
  }
  cloth_speeds(sim, result.mean_speed, result.max_speed);
  return result;
}

}  // namespace dresskit::cloth
