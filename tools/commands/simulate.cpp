#include "commands/simulate.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>

#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/run.h"
#include "dresskit/cloth/scene.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "common/output_folder.h"
#include "common/pages.h"
#include "common/progress.h"

namespace dresskit::cli {

void SimulateCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("simulate", "run a cloth scene (JSON, see docs/scenes.md); writes "
                                           "result.obj, report.json, report.html and optional frames");
  command->add_option("SCENE", scene, "scene file (.json)")->required();
  command->add_option("-o,--output", dir, "output directory")->required();
  command->add_flag("--frames", frames, "also write frame_NNNNN.obj at the scene's fps");
}

namespace {
/// Particles inside a body collider (by its own distance grid) and the deepest of them [m].
int inside_count(const Collider& c, const Eigen::MatrixX3d& x, double* deepest) {
  int count = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    Eigen::Vector3d n;
    const double d = c.distance(x.row(i).transpose(), &n);
    if (d < 0.0) ++count;
    if (deepest) *deepest = std::max(*deepest, -d);
  }
  return count;
}
}  // namespace

int SimulateCommand::run() {
  const ClothScene s = load_cloth_scene(scene);
  // Outputs are result.obj, report.json and frame_NNNNN.obj in dir: none may be a file the run reads.
  std::vector<std::string> inputs = s.files;
  inputs.push_back(scene);
  for (const std::string& input : inputs) {
    std::error_code same;
    const fs::path p(input);
    const std::string name = p.filename().string();
    const bool output_name = name == "result.obj" || name == "report.json" || name == "report.html" ||
                             (name.rfind("frame_", 0) == 0 && p.extension() == ".obj");
    if (output_name && fs::equivalent(p.parent_path().empty() ? fs::path(".") : p.parent_path(), dir, same))
      throw InputError(input + ": the run would overwrite this input with its output; write to another folder");
  }
  // Everything is written into a fresh folder that replaces the outputs of an earlier run into dir
  // as a whole, so frames of two runs are never mixed.
  const OutputLock lock = check_output_folder(dir, inputs);
  int code = 0;
  write_folder(dir, [&](const fs::path& out) { code = simulate_into(s, out); }, inputs);
  return code;
}

int SimulateCommand::simulate_into(const ClothScene& s, const fs::path& out) const {
  using Clock = std::chrono::steady_clock;
  ClothSimulator sim(s.model, s.simulation);
  sim.set_pinned(s.pins);
  if (!s.pin_motion.particles.empty()) sim.set_pin_motion(s.pin_motion);
  const bool sewing = s.model.seams.size() > 0;
  // Output: the cloth, with closed seams welded into single vertices when asked.
  auto cloth_text = [&] {
    if (!sewing || !s.weld_seams) return cloth_obj_text(sim.positions(), s.faces, s.model.springs);
    Eigen::MatrixX3d V;
    Eigen::MatrixX3i F;
    std::vector<int> to;
    weld_seams(sim.positions(), s.faces, s.model.seams, s.simulation.seam_tolerance, V, F, to);
    return cloth_obj_text(V, F, s.model.springs);
  };
  // Layers: the gap of every double layer and the order of the layers, at every frame.
  const bool layered = s.model.layer_offset.size() > 1;
  LayerGap gap_range;
  gap_range.min = std::numeric_limits<double>::infinity();
  int worst_order = 0;
  // Body meshes: how each was read, and the cloth particles inside it at the start and at the end.
  json bodies = json::array();
  for (const Collider& c : s.simulation.colliders) {
    if (c.kind != Collider::Kind::mesh) continue;
    const MeshDistanceReport& b = c.body->report();
    bodies.push_back({{"closed", b.closed}, {"boundary_edges", b.boundary_edges},
                      {"non_manifold_edges", b.non_manifold_edges}, {"sign_method", b.sign_method},
                      {"sign_disagreements", b.sign_disagreements},
                      {"grid", {b.grid[0], b.grid[1], b.grid[2]}}, {"cell_m", b.cell}, {"band_m", b.band},
                      {"build_seconds", b.build_seconds},
                      {"particles_inside_at_start", inside_count(c, sim.positions(), nullptr)}});
    if (!b.closed) {
      std::cerr << "dress-a-mesh: " << scene << ": a body mesh is not watertight (" << b.boundary_edges
                << " boundary edges, " << b.non_manifold_edges
                << " edges with more than two faces): inside is the majority of three ray parities\n";
    }
  }
  // Cloth–cloth: edge–triangle crossings at the start, at every frame and at the end.
  const int crossings_at_start = sim.intersections();
  int worst_crossings = crossings_at_start;
  std::vector<double> energy;
  const Eigen::MatrixX3d start = sim.positions();
  Progress progress("simulate", s.run.duration, "s simulated");
  const auto t0 = Clock::now();
  const RunResult result = dresskit::cloth::run(
      sim, s.run,
      [&](int k) {
        energy.push_back(sim.elastic_energy());
        if (layered) {
          const LayerGap g = layer_gap(s.model, sim.positions());
          if (g.springs) {
            gap_range.min = std::min(gap_range.min, g.min);
            gap_range.max = std::max(gap_range.max, g.max);
          }
          worst_order = std::max(worst_order, layer_order(s.model, sim.positions(), s.simulation.colliders).violations);
        }
        if (k > 0 && s.simulation.self_collision) worst_crossings = std::max(worst_crossings, sim.intersections());
        if (frames) {
          char name[32];
          std::snprintf(name, sizeof name, "frame_%05d.obj", k);
          write_file_atomically((out / name).string(), cloth_text());
        }
      },
      [&](const StepResult&) { progress.update(sim.time()); });
  progress.finish();
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const StepTotals& tot = result.totals;
  write_file_atomically((out / "result.obj").string(), cloth_text());
  const int crossings_at_end = sim.intersections();
  double closest = std::numeric_limits<double>::infinity();
  for (const Collider& c : s.simulation.colliders) {
    Eigen::Vector3d n;
    for (int i = 0; i < sim.positions().rows(); ++i) closest = std::min(closest, c.distance(sim.positions().row(i).transpose(), &n));
  }
  json garments = json::array();
  for (const GarmentInfo& g : s.garments) {
    json entry = {{"fabric", g.fabric}, {"double_layer", g.double_layer}, {"first_vertex", g.first_vertex},
                  {"vertices", g.vertices}};
    if (g.double_layer) {
      entry["thickness_mm"] = g.thickness.thickness * 1e3;
      entry["thickness_min_mm"] = g.thickness.min * 1e3;
      entry["thickness_max_mm"] = g.thickness.max * 1e3;
    }
    garments.push_back(entry);
  }
  const SimulationOptions& o = s.simulation;
  const LayerGap gap = layer_gap(s.model, sim.positions());
  const LayerOrder order = layer_order(s.model, sim.positions(), o.colliders);
  json report = {
      {"scene", scene},
      {"integrator", to_string(o.integrator)},
      {"linear_solver", o.linear.solver == LinearSolver::ldlt ? "ldlt" : "cg"},
      {"fabric", s.fabric_name},
      {"vertices", sim.positions().rows()},
      {"springs", {{"structural", s.model.springs.count(SpringType::structural)},
                   {"shear", s.model.springs.count(SpringType::shear)},
                   {"bending", s.model.springs.count(SpringType::bending)},
                   {"layer_structural", s.model.springs.count(SpringType::layer_structural)},
                   {"layer_shear", s.model.springs.count(SpringType::layer_shear)}}},
      {"skipped", {{"zero_area_faces", s.model.skipped_zero_area_faces},
                   {"zero_length_springs", s.model.skipped_zero_length_springs}}},
      {"force_terms", {{"gravity", o.gravity.norm() > 0},
                       {"air_damping", o.air_damping > 0},
                       {"wind", o.wind.norm() > 0},
                       {"spring_damping", o.spring_damping > 0},
                       {"dynamic_stiffness", o.dynamic_stiffness},
                       {"strain_limiting", o.strain_limiting},
                       {"layer_limits", !s.model.springs.limited.empty()},
                       {"colliders", o.colliders.size()}}},
      {"dt", o.dt},
      {"adaptive", o.adaptive},
      {"smallest_dt", tot.steps ? tot.smallest_dt : o.dt},
      {"step_retries", tot.retries},
      {"simulated_seconds", sim.time()},
      {"steps", tot.steps},
      {"frames", result.frames},
      {"wall_seconds", wall},
      {"seconds_per_frame", result.frames ? wall / result.frames : 0.0},
      {"cg_iterations", tot.cg_iterations},
      {"max_strain", sim.max_strain()},
      {"mean_strain", sim.mean_strain()},
      {"energy_history", energy},
      {"final_residual", sim.static_residual()},
      {"closest_collider_distance_m", std::isfinite(closest) ? json(closest) : json(nullptr)},
      {"stopped_reason", result.stopped_reason},
      {"stuck_steps", tot.stuck_steps},
      {"warnings", result.warnings},
      {"rest", {{"stop_at_rest", s.run.rest.enabled},
                {"mean_speed_threshold", s.run.rest.mean_speed},
                {"max_speed_threshold", s.run.rest.max_speed},
                {"time", s.run.rest.time},
                {"at_rest_from_seconds", result.rest_at >= 0.0 ? json(result.rest_at) : json(nullptr)},
                {"mean_speed_at_end", result.mean_speed},
                {"max_speed_at_end", result.max_speed}}},
      {"collider_contacts", {{"pushes", tot.collisions}, {"tunnelling_caught", tot.tunnelling}}},
      {"nan_detected", !result.ok && result.failure.find("non-finite") != std::string::npos}};
  if (!bodies.empty()) {
    int k = 0;
    for (const Collider& c : o.colliders) {
      if (c.kind != Collider::Kind::mesh) continue;
      double deepest = 0.0;
      bodies[k]["particles_inside_at_end"] = inside_count(c, sim.positions(), &deepest);
      bodies[k++]["deepest_inside_at_end_m"] = deepest;
    }
    report["bodies"] = bodies;
    report["deep_pushes"] = tot.deep_pushes;
  }
  report["self_collision"] = o.self_collision;
  report["intersections"] = {{"at_start", crossings_at_start}, {"at_end", crossings_at_end},
                             {"max_over_frames", std::max(worst_crossings, crossings_at_end)}};
  if (o.self_collision) {
    report["cloth_collisions"] = {{"thickness_m", o.self_collision_options.thickness},
                                  {"proximity_pairs", tot.self.proximity_pairs},
                                  {"repulsions", tot.self.repulsions},
                                  {"ccd_collisions", tot.self.ccd_collisions},
                                  {"impact_zones", tot.self.zones},
                                  {"impact_zone_particles", tot.self.zone_particles},
                                  {"steps_held", tot.held_steps}};
  }
  report["phase_seconds"] = {{"forces_and_assembly", tot.force_seconds}, {"integrator", tot.integrate_seconds},
                             {"layer_guard_and_limits", tot.constraint_seconds}, {"seams", tot.seam_seconds},
                             {"colliders", tot.collision_seconds}, {"cloth_collisions", tot.self_collision_seconds}};
  if (sewing) {
    const SeamGaps g = seam_gaps(s.model.seams, sim.positions(), o.seam_tolerance);
    int sewn = 0;
    for (char c : sim.sewn()) sewn += c;
    report["seams"] = {{"stitches", g.stitches}, {"closed", g.closed}, {"sewn", sewn},
                       {"max_gap_mm", g.max * 1e3}, {"mean_gap_mm", g.mean * 1e3},
                       {"tolerance_mm", o.seam_tolerance * 1e3}, {"welded", s.weld_seams}};
  }
  report["layers"] = s.model.layer_offset.size();
  report["garments"] = garments;
  if (gap.springs) {
    report["layer_gap_mm"] = {{"min", gap.min * 1e3}, {"mean", gap.mean * 1e3}, {"max", gap.max * 1e3},
                              {"min_over_frames", gap_range.min * 1e3}, {"max_over_frames", gap_range.max * 1e3}};
  }
  if (layered) {
    report["layer_order"] = {{"checked", order.checked}, {"violations", order.violations},
                             {"max_violations_over_frames", std::max(worst_order, order.violations)}};
  }
  write_file_atomically((out / "report.json").string(), report.dump(2) + "\n");
  write_report_html((out / "report.html").string(),
                    simulate_page(scene, s, start, sim.positions(), result, report));
  std::cout << "simulated " << tot.steps << " steps (" << result.frames << " frames, " << sim.time() << " s) in "
            << wall << " s; max strain " << sim.max_strain() << "; " << result.stopped_reason << "\n";
  for (const std::string& w : result.warnings) std::cerr << "dress-a-mesh: " << scene << ": warning: " << w << "\n";
  if (!result.ok) {
    std::cerr << "dress-a-mesh: " << scene << ": simulation stopped after " << tot.steps
              << " steps: " << result.failure << " (last good state written)\n";
    return static_cast<int>(ExitCode::simulation_failed);
  }
  return 0;
}

}  // namespace dresskit::cli
