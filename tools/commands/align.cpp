#include "commands/align.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "dresskit/alignment/part_labels.h"
#include "dresskit/mesh/errors.h"
#include "common/output_folder.h"
#include "dresskit/mesh/io.h"

namespace dresskit::cli {
namespace {

json matrix_json(const Eigen::Matrix4d& T) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return rows;
}

json icp_json(const IcpResult& r) {
  return {{"transform", matrix_json(r.transform)},
          {"scale", r.scale},
          {"fitness", r.fitness},
          {"rmse", r.rmse},
          {"iterations", r.iterations},
          {"converged", r.converged},
          {"seconds", r.seconds}};
}

std::string text(double value) {
  std::ostringstream s;
  s.precision(3);
  s << value;
  return s.str();
}

TriangleMesh load(const std::string& path, const std::string& units, const std::string& up) {
  LoadOptions options;
  options.units = Units::parse(units);
  options.up = parse_up_axis(up);
  return load_mesh(path, options);
}

// Writes the mesh and the report into dir together, never over one of the inputs.
void write_outputs(const std::string& dir, const std::string& mesh_name, const TriangleMesh& mesh,
                   const json& report, const std::vector<std::string>& inputs) {
  write_folder(
      dir,
      [&](const fs::path& folder) {
        save_mesh(mesh, (folder / mesh_name).string());
        write_file_atomically((folder / "result.json").string(), report.dump(2) + "\n");
      },
      inputs);
}

}  // namespace

void AlignCommand::add_to(CLI::App& app) {
  command =
      app.add_subcommand("align",
                         "register SOURCE onto TARGET (--rigid), or place GARMENT on BODY part "
                         "by part (docs/alignment.md)");
  command->add_option("SOURCE", source, "source mesh, or the garment")->required();
  command->add_option("TARGET", target, "target mesh, or the body")->required();
  command->add_option("-o,--output", dir, "output directory")->required();
  command->add_flag("--rigid", rigid, "plain registration: result.json and aligned.obj");
  command->add_option("--units", units,
                      "length unit of both inputs: m, dm, cm, mm or metres per unit");
  command->add_option("--source-units,--garment-units", source_units,
                      "length unit of SOURCE (overrides --units)");
  command->add_option("--target-units,--body-units", target_units,
                      "length unit of TARGET (overrides --units)");
  option_with_default(command, "--up", up, "up axis of both inputs: +x, -x, +y, -y, +z, -z");
  command->add_flag("--scale", with_scale,
                    "--rigid: also estimate a uniform scale (similarity transform)");
  command->add_flag("--local", local,
                    "--rigid: start ICP from the inputs' placement (no candidate orientations)");
  command->add_option("--max-iterations", global.icp.max_iterations, "ICP iterations per stage")
      ->capture_default_str()
      ->check(positive_number());
  option_with_default(command, "--min-fitness", min_fitness,
                      "--rigid: fail below this fraction of matched points");
  command->add_option("--garment-labels", garment_labels,
                      "part labels of the garment (labels JSON)");
  command->add_option("--body-labels", body_labels, "part labels of the body (labels JSON)");
  command->add_option("--garment-labels-key", garment_labels_key,
                      "entry of --garment-labels (default: file stem)");
  command->add_option("--body-labels-key", body_labels_key,
                      "entry of --body-labels (default: file stem)");
  option_with_default(command, "--clearance", placement.clearance,
                      "distance kept outside the body [m]");
  option_with_default(command, "--blend-radius", placement.blend_radius,
                      "part transforms blend within this distance [m]");
  option_with_default(command, "--max-stretch", placement.max_edge_stretch,
                      "edges longer than (1 + this) x rest length are shortened");
  option_with_default(
      command, "--layer-gap", placement.layer_gap,
      "pieces of an outfit kept this far apart, outer outside inner [m]; < 0 = off");
  command->add_flag("--part-scale", part_scale, "per-part similarity ICP (default: rigid parts)");
  command->add_flag("--keep-ease", placement.keep_ease,
                    "per-part ICP onto the body raised by the part's ease, not onto the skin");
  command->add_option("--reference", reference,
                      "placement: a reference placement of the garment (same vertex "
                      "order) to compare with; adds `quality` to result.json");
}

int AlignCommand::run() {
  const OutputLock lock = check_output_folder(dir, {source, target, garment_labels, body_labels, reference},
                                              {"aligned.obj", "posed.obj", "result.json", "report.html"});
  const std::string su = !source_units.empty() ? source_units : (!units.empty() ? units : "m");
  const std::string tu = !target_units.empty() ? target_units : (!units.empty() ? units : "m");
  const TriangleMesh src = load(source, su, up), dst = load(target, tu, up);
  const double ds = bbox_diagonal(src.V), dt = bbox_diagonal(dst.V);
  const double ratio = std::max(ds, dt) / std::max(1e-300, std::min(ds, dt));
  if (units.empty() && source_units.empty() && target_units.empty() && ratio > 5.0) {
    throw InputError(source + " and " + target + ": sizes differ by a factor of " + text(ratio) +
                     " (bounding-box diagonals " + text(ds) + " and " + text(dt) +
                     " in file units); give their units with --source-units / --target-units");
  }

  json report = {{"source", source},
                 {"target", target},
                 {"source_units", su},
                 {"target_units", tu},
                 {"units_out", "m"}};
  if (rigid) {
    global.with_scale = with_scale;
    global.candidates = local ? 0 : global.candidates;
    const PointSet s{src.V, {}}, t{dst.V, vertex_normals(dst.V, dst.F)};
    check_point_set(s, source);
    check_point_set(t, target);
    const GlobalResult g = global_align(s, t, global);
    const IcpResult& r = g.result;
    if (!(r.fitness >= min_fitness)) {
      throw InputError(source + ": registration onto " + target + " failed: only " +
                       text(100 * r.fitness) + "% of points within " +
                       text(global.icp.inlier_distance * dt) + " m of the target (--min-fitness " +
                       text(min_fitness) + ")");
    }
    report.update(icp_json(r));
    report["seconds"] = g.seconds;
    report["candidates"] = g.candidates.size();
    report["best_candidate"] = g.best_candidate;
    TriangleMesh aligned = src;
    aligned.V = transform_points(r.transform, src.V);
    if (aligned.N.rows()) aligned.N = transform_normals(r.transform, src.N);
    write_outputs(dir, "aligned.obj", aligned, report, {source, target});
    std::cout << "aligned " << source << " onto " << target << ": fitness " << text(r.fitness)
              << ", rmse " << text(r.rmse) << " m, " << r.iterations << " iterations, "
              << text(g.seconds) << " s\n";
    return 0;
  }

  TriangleMesh garment = src, body = dst;
  if (!garment_labels.empty())
    apply_part_labels(garment, garment_labels, garment_labels_key, source);
  if (!body_labels.empty()) apply_part_labels(body, body_labels, body_labels_key, target);
  if (!garment.has_labels()) throw InputError(source + ": no part labels (give --garment-labels)");
  if (!body.has_labels()) throw InputError(target + ": no part labels (give --body-labels)");
  placement.part_scale = part_scale;
  const PlacementResult p = place_garment(garment, body, placement);

  json matches = json::array(), parts = json::array();
  for (const auto& m : p.matching.matches)
    matches.push_back({{"garment_part", m.garment_part},
                       {"body_part", m.body_part},
                       {"confidence", m.confidence},
                       {"by", m.by}});
  for (const auto& part : p.parts) {
    json j = {{"garment_part", part.garment_part},
              {"body_part", part.body_part},
              {"vertices", part.vertices},
              {"used_icp", part.used_icp}};
    j.update(icp_json(part.icp));
    if (!part.note.empty()) j["note"] = part.note;
    parts.push_back(j);
  }
  report["global"] = {{"transform", matrix_json(p.global)},
                      {"scale", p.global_scale},
                      {"method", p.global_method},
                      {"junctions", p.junctions}};
  report["matches"] = matches;
  report["unmatched_garment_parts"] = p.matching.unmatched_garment_parts;
  report["unmatched_body_parts"] = p.matching.unmatched_body_parts;
  report["parts"] = parts;
  report["pushed_out_vertices"] = p.pushed_out;
  report["stretch_limited_edges"] = p.stretch_limited_edges;
  report["layer_pieces"] = p.layer_pieces;
  report["layer_pushed_vertices"] = p.layer_pushed;
  report["max_edge_stretch_limit"] = placement.max_edge_stretch;
  report["clearance_m"] = placement.clearance;
  report["blend_radius_m"] = placement.blend_radius;
  report["seconds"] = p.seconds;
  if (!reference.empty()) {
    const TriangleMesh ref = load(reference, su, up);
    if (ref.num_vertices() != garment.num_vertices())
      throw InputError(reference + ": " + std::to_string(ref.num_vertices()) +
                       " vertices, the garment has " + std::to_string(garment.num_vertices()));
    const PlacementQuality q = placement_quality(p.V, garment, ref.V, body);
    const PlacementQuality q_ref = placement_quality(ref.V, garment, ref.V, body);
    report["quality"] = {{"reference", reference},
                         {"body_height_m", q.body_height},
                         {"mean_distance_percent_of_height", 100 * q.mean_distance},
                         {"p95_distance_percent_of_height", 100 * q.p95_distance},
                         {"inside_fraction", q.inside_fraction},
                         {"max_edge_stretch", q.max_edge_stretch},
                         {"reference_inside_fraction", q_ref.inside_fraction},
                         {"reference_max_edge_stretch", q_ref.max_edge_stretch}};
  }
  TriangleMesh posed = garment;
  posed.V = p.V;
  posed.N.resize(0, 3);
  write_outputs(dir, "posed.obj", posed, report, {source, target, garment_labels, body_labels, reference});
  std::cout << "placed " << source << " on " << target << ": " << p.matching.matches.size()
            << " parts matched, " << p.global_method << ", scale " << text(p.global_scale) << ", "
            << p.pushed_out << " vertices pushed out, " << text(p.seconds) << " s\n";
  return 0;
}

}  // namespace dresskit::cli
