// Settle: the placed garments, stacked as layers, settle on the body in the cloth simulator with
// the body as a collider, trousers and skirts held by their waistbands. What is tried when a settle
// fails, jams or leaves a garment crossing itself is a policy written as data (kRetries below): each
// retry says when it is tried and what it changes; a retry after a failure is kept when it settles,
// any other when it settles and leaves fewer crossings of the garments' own than the run kept.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "../garments.h"
#include "../measures.h"
#include "../outfit.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/run.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/mesh/names.h"

namespace dresskit::dressing::detail::stages {

using namespace dresskit::cloth;

namespace {

/// The simulator's options for a quality and how long it settles [s].
SimulationOptions simulation_options(DressQuality q, double& duration) {
  SimulationOptions o;
  o.self_collision = true;
  switch (q) {
    // Fast keeps the simulator's steps and iterations and settles for less time: a stiff fabric
    // held against the body needs the default projective iterations, or its adaptive step falls
    // to the minimum.
    case DressQuality::fast: duration = 0.5; break;
    case DressQuality::balanced: duration = 1.0; break;
    case DressQuality::accurate:
      o.dt = 1.0 / 240.0;
      o.projective.iterations = 20;
      duration = 2.0;
      break;
  }
  return o;
}

/// How one settle is set up: the simulator's options and, per garment, the vertices held where
/// placed besides the waistbands.
struct SettleSetup {
  SimulationOptions simulation;
  std::vector<std::vector<int>> hold;
};

/// A settle of the outfit from its placed positions, and what it left.
struct SettleRun {
  SettleSetup setup;
  std::optional<ClothSimulator> sim;
  RunResult run;
  /// Samples over the run: simulated time [s], elastic energy [J], largest structural strain.
  std::vector<double> time, energy, strain;
  std::vector<int> own;  ///< per garment, its crossings of its own at the end
  std::string said;      ///< the jams it settled through, for the stage's report ("; …" each)
  int own_total() const { return std::accumulate(own.begin(), own.end(), 0); }
};

/// Settles the outfit's garments, stacked as one cloth, from their placed positions.
class Settler {
 public:
  Settler(const Outfit& outfit, const std::vector<ClothModel>& models, double duration,
          const std::function<void(double, double)>& on_settle)
      : outfit_(outfit),
        model_(models.size() == 1 ? models[0] : stack_layers(models, outfit.separation)),
        first_(garment_offsets(models)),
        duration_(duration),
        on_settle_(on_settle) {}

  /// One settle with `setup`.
  SettleRun run(const SettleSetup& setup) const {
    SettleRun r;
    r.setup = setup;
    r.sim.emplace(model_, setup.simulation);
    ClothSimulator& sim = *r.sim;
    Eigen::MatrixX3d x(model_.rest_positions.rows(), 3);
    std::vector<int> held;
    const std::vector<DressedGarment>& garments = outfit_.result.garments;
    for (std::size_t k = 0; k < garments.size(); ++k) {
      x.middleRows(first_[k], first_[k + 1] - first_[k]) = garments[k].placed;
      for (int v : outfit_.waistbands[k]) held.push_back(first_[k] + v);
      for (int v : setup.hold[k]) held.push_back(first_[k] + v);
    }
    sim.set_state(x, Eigen::MatrixX3d::Zero(x.rows(), 3));
    if (!held.empty()) sim.set_pinned(held);
    // Sampled at most kSettleSamples times (the elastic energy costs about 5 % of a step) and after
    // the last step.
    auto sample = [&](double strain) {
      r.time.push_back(sim.time());
      r.energy.push_back(sim.elastic_energy());
      r.strain.push_back(strain);
    };
    RunOptions run_options;
    run_options.duration = duration_;
    // The step budget is counted in the nominal steps of the first settle's dt: a safer retry's
    // shorter steps spend it faster, as they should (the limit is on work, not on simulated time).
    run_options.max_steps = outfit_.settle_max_steps;
    double next_sample = 0.0;
    r.run = cloth::run(sim, run_options, {}, [&](const StepResult& step) {
      if (step.ok && sim.time() >= next_sample) {
        sample(step.strain);
        next_sample = sim.time() + duration_ / kSettleSamples;
      }
      if (on_settle_) on_settle_(sim.time(), duration_);
    });
    if (r.time.empty() || r.time.back() < sim.time()) sample(sim.max_strain());
    for (std::size_t k = 0; k < garments.size(); ++k) r.own.push_back(count_intersections(positions(r, k), garments[k].mesh.F));
    return r;
  }

  /// A settle with `setup` that, where it stalls, settles again allowing a larger rise in strain
  /// a step (kJamFactors). A garment untangled by holding its parts apart may be pressed between
  /// them and the body tighter than its length limits allow: the contacts then raise its strain at
  /// every step by more than the adaptive step allows, however short. The least rise that gets past
  /// the jam is used: the larger steps it allows crumple cloth pressed between body and cloth.
  SettleRun run_through_jams(SettleSetup setup) const {
    static constexpr double kJamFactors[] = {2.0, 4.0};
    const double allowed = setup.simulation.max_strain_change;
    SettleRun r = run(setup);
    std::vector<std::string> retries;
    for (const double factor : kJamFactors) {
      if (!r.run.stalled) break;
      retries.push_back("settling " + r.run.stopped_reason + ", settled again allowing a rise in strain of " +
                        number(factor * allowed) + " a step");
      setup.simulation.max_strain_change = factor * allowed;
      r = run(setup);
    }
    for (const std::string& s : retries) r.said += "; " + s;
    r.run.warnings.insert(r.run.warnings.begin(), retries.begin(), retries.end());
    return r;
  }

  /// Garment k's positions at the end of a run.
  Eigen::MatrixX3d positions(const SettleRun& r, std::size_t k) const {
    return r.sim->positions().middleRows(first_[k], first_[k + 1] - first_[k]);
  }

 private:
  const Outfit& outfit_;
  ClothModel model_;
  std::vector<int> first_;
  double duration_;
  const std::function<void(double, double)>& on_settle_;
};

/// A settle tried again after the one kept so far. `prepare` says whether it applies to `kept`
/// and, where it does, changes the setup (a copy of kept's) and returns what it changed. A retry
/// after a failed settle is kept when it settles; any other when it settles with fewer crossings of
/// the garments' own.
struct SettleRetry {
  std::optional<std::string> (*prepare)(const Outfit& outfit, const SettleRun& kept, SettleSetup& setup,
                                        double allowed);
  bool through_jams;   ///< settles through jams as the first settle does
  bool after_failure;  ///< tried only when the settle kept so far failed (otherwise only when it did not)
};

/// A settle that blew up starts again from the placed garments with steps a quarter as long, half
/// the contact travel a step and four times the length limit's sweeps: what the first steps did to
/// cloth pressed against the body is then taken back before it tears a spring.
std::optional<std::string> safer(const Outfit&, const SettleRun& kept, SettleSetup& setup, double) {
  setup.simulation.dt /= 4.0;
  setup.simulation.contact_travel *= 0.5;
  setup.simulation.strain_limit_iterations *= 4;
  return "from the start with safer settings after it failed (" + kept.run.failure + "): steps of at most " +
         number(setup.simulation.dt, 3) + " s, half the contact travel, four times the length limit's sweeps";
}

/// With a garment sewn from a pattern the adaptive step leaves the springs held at their length
/// limit out of the rise it judges. The longer steps that allows can let cloth pressed between
/// body and cloth pass through itself: a settle that leaves a pattern's garment crossing itself
/// more often than sewn runs again judging them.
std::optional<std::string> judge_held_springs(const Outfit& outfit, const SettleRun& kept, SettleSetup& setup,
                                              double allowed) {
  const std::vector<DressedGarment>& garments = outfit.result.garments;
  bool more = false;
  for (std::size_t k = 0; k < garments.size(); ++k)
    more = more || (garments[k].from_pattern && kept.own[k] > garments[k].crossings_authored);
  if (!setup.simulation.rise_skips_held_springs || !more) return std::nullopt;
  setup.simulation.rise_skips_held_springs = false;
  setup.simulation.max_strain_change = allowed;
  return "judging the springs held at their length limit";
}

/// Cloth–cloth collisions leave out pairs whose sides both lie in a crossing at a step's start, so
/// that a garment can drape out of the crossings placement left; but where a garment crosses itself
/// as authored (layered details: folded hems, lapels through a jacket), its tangled parts may pass
/// further through each other instead. A settle that leaves a garment crossing itself more often
/// than as authored runs again with the particles of the crossings it has both as authored and as
/// placed held where they were placed.
std::optional<std::string> hold_authored_crossings(const Outfit& outfit, const SettleRun& kept, SettleSetup& setup,
                                                   double) {
  const std::vector<DressedGarment>& garments = outfit.result.garments;
  int tangled = 0;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    const DressedGarment& g = garments[k];
    if (kept.own[k] <= g.crossings_authored) continue;
    const std::vector<int> authored = crossing_vertices(g.mesh.V, g.mesh.F), placed = crossing_vertices(g.placed, g.mesh.F);
    std::set_intersection(authored.begin(), authored.end(), placed.begin(), placed.end(), std::back_inserter(setup.hold[k]));
    tangled += static_cast<int>(setup.hold[k].size());
  }
  if (tangled == 0) return std::nullopt;
  return "holding " + std::to_string(tangled) + " particles of the garments' own crossings as authored";
}

/// The retries, in the order tried after the first settle.
const SettleRetry kRetries[] = {
    {safer, true, true},
    {judge_held_springs, true, false},
    {hold_authored_crossings, false, false},
};

}  // namespace

StageReport settle(Outfit& outfit, const DressOptions& options) {
  DressResult& result = outfit.result;
  std::vector<DressedGarment>& garments = result.garments;
  for (DressedGarment& g : garments) g.dressed = g.placed;
  double duration = 1.0;
  SettleSetup setup{simulation_options(options.quality, duration), std::vector<std::vector<int>>(garments.size())};
  if (options.settle_seconds > 0.0) duration = options.settle_seconds;
  setup.simulation.colliders.push_back(Collider::mesh(outfit.body_distance()));
  // A garment sewn from a pattern holds springs at their length limit for good where its seams join
  // edges of unequal length: the adaptive step leaves them out of the strain rise it judges.
  setup.simulation.rise_skips_held_springs =
      std::any_of(garments.begin(), garments.end(), [](const DressedGarment& g) { return g.from_pattern; });
  outfit.settled_with = setup.simulation;
  outfit.settle_duration = duration;
  if (options.settle_step_budget > 0.0)
    outfit.settle_max_steps = static_cast<int>(std::ceil(options.settle_step_budget * duration / setup.simulation.dt));
  if (!options.settle) return left_out("not asked for");

  std::vector<ClothModel> models;
  for (std::size_t k = 0; k < garments.size(); ++k) models.push_back(garment_cloth(garments[k], outfit.fabrics[k]));
  // Trousers and skirts stay up by their waistband, held as by a belt; a garment reaching above
  // three quarters of the body's height hangs from its shoulders.
  const double shoulders = result.body.V.col(1).minCoeff() + 0.75 * outfit.body_height;
  std::string report;
  for (DressedGarment& g : garments) {
    outfit.waistbands.push_back(
        waistband(g, rest_shape(g).V, options.waistband, setup.simulation.strain_limit, outfit.inside(), shoulders));
    g.waistband_vertices = static_cast<int>(outfit.waistbands.back().size());
    if (g.waistband_vertices > 0)
      report += "; waistband of " + g.name + " held (" + counted(g.waistband_vertices, "vertex", "vertices") + ")";
  }

  const Settler settler(outfit, models, duration, options.on_settle);
  const double allowed = setup.simulation.max_strain_change;
  SettleRun kept = settler.run_through_jams(setup);
  report += kept.said;
  for (const SettleRetry& retry : kRetries) {
    if (retry.after_failure == kept.run.ok) continue;
    SettleSetup changed = kept.setup;
    const std::optional<std::string> how = retry.prepare(outfit, kept, changed, allowed);
    if (!how) continue;
    SettleRun again = retry.through_jams ? settler.run_through_jams(changed) : settler.run(changed);
    const int before = kept.own_total(), after = again.own_total();
    report += "; settled again " + *how;
    if (again.run.ok && (retry.after_failure || after < before)) {
      report += " (" + std::to_string(before) + " → " + counted(after, "crossing", "crossings") + ")" + again.said;
      kept = std::move(again);
    } else {
      report += ", not kept (" +
                (again.run.ok ? counted(after, "crossing", "crossings") + " against " + std::to_string(before)
                              : again.run.stopped_reason) +
                ")";
    }
  }

  result.settled = true;
  result.settle = kept.run;
  result.settle_time = kept.time, result.settle_energy = kept.energy, result.settle_strain = kept.strain;
  outfit.settled_with = kept.setup.simulation;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    garments[k].dressed = settler.positions(kept, k);
    garments[k].tangle_held_vertices = static_cast<int>(kept.setup.hold[k].size());
  }
  return ran(counted(kept.run.totals.steps, "step", "steps") + ", " + number(kept.sim->time()) + " s simulated, " +
             kept.run.stopped_reason + report);
}

}  // namespace dresskit::dressing::detail::stages
