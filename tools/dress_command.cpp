#include "dress_command.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "output_folder.h"
#include "progress.h"

namespace dresskit::cli {
namespace fs = std::filesystem;
using json = nlohmann::json;

void DressCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("dress", "dress BODY in GARMENT(s), given inside to outside: segment, place, "
                                        "settle; writes report.json, dressed.glb and each garment placed "
                                        "and dressed (docs/dressing.md)");
  command->add_option("BODY", body, "body mesh")->required();
  command->add_option("GARMENT", garments, "garment meshes, inside to outside")->required();
  command->add_option("-o,--output", dir, "output directory")->required();
  command->add_option("--units", units, "length unit of every input: m, dm, cm, mm or metres per unit");
  command->add_option("--body-units", body_units, "length unit of BODY (overrides --units)");
  command->add_option("--garment-units", garment_units, "length unit of the garments (overrides --units)");
  command->add_option("--up", up, "up axis of every input: +x, -x, +y, -y, +z, -z")->capture_default_str();
  command->add_option("--fabric", fabrics,
                      "fabric of each garment in order (one: all of them); default gray-interlock");
  command->add_option("--body-labels", body_labels, "part labels of the body (labels JSON): no segmentation");
  command->add_option("--garment-labels", garment_labels,
                      "part labels of each garment in order (one file: all of them, keyed by file stem)");
  command->add_option("--quality", quality, "fast, balanced or accurate")->capture_default_str();
  command->add_option("--layers", layers,
                      "given: worn inside to outside in the order given; inferred: from the garments' kinds "
                      "(bottoms under tops, the larger outside)")
      ->capture_default_str();
  command->add_flag("--no-settle", no_settle, "stop after placement (dressed = placed)");
  command->add_flag("--json", as_json, "print the report as JSON on stdout (nothing else)");
  command->add_flag("--segments", segments, "also write segments.ply: every mesh coloured by part");
}

namespace {
LoadOptions load_options(const std::string& specific, const std::string& common, const std::string& up) {
  LoadOptions o;
  o.units = Units::parse(!specific.empty() ? specific : !common.empty() ? common : "m");
  o.up = parse_up_axis(up);
  return o;
}

/// Picks the i-th of a per-garment option: one value serves every garment.
std::string per_garment(const std::vector<std::string>& values, std::size_t i, const char* option,
                        std::size_t garments) {
  if (values.empty()) return "";
  if (values.size() == 1) return values[0];
  if (values.size() != garments)
    throw InputError(std::string(option) + ": give one value, or one per garment (" + std::to_string(garments) +
                     "), not " + std::to_string(values.size()));
  return values[i];
}

/// Positions in the file's own vertex order, units and axes: the mesh's rows mapped back through
/// source_vertex (a vertex the toolkit dropped keeps the file's position), faces likewise.
TriangleMesh in_file_order(const TriangleMesh& mesh, const Eigen::MatrixX3d& V, const MeshFile& file) {
  const TriangleMesh original = load_mesh(file.path, file.load);
  int count = original.num_vertices();
  for (Eigen::Index i = 0; i < mesh.source_vertex.size(); ++i) count = std::max(count, mesh.source_vertex(i) + 1);
  Eigen::MatrixX3d out = Eigen::MatrixX3d::Zero(count, 3);
  std::vector<int> to_file(static_cast<std::size_t>(mesh.num_vertices()));
  for (int i = 0; i < original.num_vertices(); ++i) {
    const int s = original.source_vertex.size() ? original.source_vertex(i) : i;
    if (s >= 0 && s < count) out.row(s) = original.V.row(i);
  }
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const int s = mesh.source_vertex.size() ? mesh.source_vertex(i) : i;
    to_file[static_cast<std::size_t>(i)] = s;
    if (s >= 0 && s < count) out.row(s) = V.row(i);
  }
  TriangleMesh result;
  result.V = to_file_frame(out, file.load);
  result.F.resize(mesh.num_faces(), 3);
  int kept = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Eigen::Vector3i face;
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      face(k) = to_file[static_cast<std::size_t>(mesh.F(f, k))];
      ok = ok && face(k) >= 0;
    }
    if (ok) result.F.row(kept++) = face.transpose();
  }
  result.F.conservativeResize(kept, 3);
  return result;
}

json parts_json(const std::vector<DressPart>& parts) {
  json out = json::array();
  for (const DressPart& p : parts) out.push_back({{"name", p.name}, {"confidence", p.confidence}, {"vertices", p.vertices}});
  return out;
}

json placement_json(const DressedGarment& g) {
  json out = {{"ran", g.placed_by_placement}};
  if (!g.placed_by_placement) return out;
  const PlacementResult& p = g.placement;
  out["global_scale"] = p.global_scale;
  out["global_method"] = p.global_method;
  json matches = json::array();
  for (const PartMatch& m : p.matching.matches)
    matches.push_back({{"garment_part", m.garment_part}, {"body_part", m.body_part}, {"confidence", m.confidence}, {"by", m.by}});
  out["matches"] = matches;
  out["unmatched_garment_parts"] = p.matching.unmatched_garment_parts;
  json parts = json::array();
  for (const PartPlacement& q : p.parts) {
    json e = {{"garment_part", q.garment_part}, {"body_part", q.body_part}, {"vertices", q.vertices},
              {"used_icp", q.used_icp}, {"fitness", q.icp.fitness}, {"rmse_m", q.icp.rmse}};
    if (!q.note.empty()) e["note"] = q.note;
    parts.push_back(e);
  }
  out["parts"] = parts;
  out["pushed_out_vertices"] = p.pushed_out;
  out["seconds"] = p.seconds;
  return out;
}

}  // namespace

int DressCommand::run() {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  MeshFile body_file{body, load_options(body_units, units, up), body_labels, ""};
  std::vector<GarmentFile> garment_files;
  std::set<std::string> stems;
  for (std::size_t i = 0; i < garments.size(); ++i) {
    GarmentFile g;
    g.file = {garments[i], load_options(garment_units, units, up),
              per_garment(garment_labels, i, "--garment-labels", garments.size()), ""};
    g.fabric = per_garment(fabrics, i, "--fabric", garments.size());
    if (!stems.insert(fs::path(garments[i]).stem().string()).second)
      throw InputError(garments[i] + ": another garment has the same file name; outputs are named by it");
    garment_files.push_back(g);
  }
  DressOptions options;
  options.quality = parse_quality(quality);
  options.settle = !no_settle;
  if (layers != "given" && layers != "inferred")
    throw InputError("--layers: '" + layers + "' is not given or inferred");
  options.infer_layers = layers == "inferred";
  options.on_stage = [&](const DressStage& s) {
    char line[64];
    std::snprintf(line, sizeof line, "%7.2f s", s.seconds);
    std::cerr << "dress: " << s.name << (s.ran ? "" : " (left out)") << " " << line << "  " << s.reason << "\n";
  };
  Progress progress("settle", 1.0, "s simulated");
  options.on_settle = [&](double done, double total) {
    if (!progress.terminal()) return;
    progress.set_total(total);
    progress.update(done);
  };
  DressResult r = dress(body_file, garment_files, options);
  progress.finish();
  if (r.settled && !r.settle.ok) {
    std::cerr << "dress-a-mesh: " << body << ": settling stopped: " << r.settle.failure
              << " (nothing written)\n";
    return static_cast<int>(ExitCode::simulation_failed);
  }

  // The report.
  json garments_json = json::array();
  for (const DressedGarment& g : r.garments) {
    garments_json.push_back(
        {{"name", g.name},
         {"path", g.file.path},
         {"units", g.file.load.units.name},
         {"fabric", g.fabric},
         {"vertices", g.mesh.num_vertices()},
         {"labels", g.labels_from_file ? "file" : "segmentation"},
         {"parts", parts_json(g.parts)},
         {"placement", placement_json(g)},
         {"layer", g.layer},
         {"thickness_mm", 1e3 * g.thickness},
         {"crossings", {{"authored", g.crossings_authored}, {"placed", g.crossings_placed}, {"dressed", g.crossings_dressed}}},
         {"vertices_inside_body_2mm", {{"placed", g.inside_placed}, {"dressed", g.inside_dressed}}},
         {"max_strain", g.max_strain_dressed},
         {"waistband_vertices", g.waistband_vertices},
         {"outputs", {{"placed", g.name + ".placed.obj"}, {"dressed", g.name + ".dressed.obj"}}}});
  }
  json gaps = json::array();
  for (std::size_t k = 0; k < r.layer_gap_median.size(); ++k)
    gaps.push_back({{"inner", r.garments[k].name}, {"outer", r.garments[k + 1].name},
                    {"p5_mm", 1e3 * r.layer_gap_p5[k]}, {"median_mm", 1e3 * r.layer_gap_median[k]},
                    {"asked_mm", 1e3 * r.layer_gap_asked[k]}});
  json report = {
      {"body", {{"path", body}, {"units", body_file.load.units.name}, {"vertices", r.body.num_vertices()},
                {"height_m", r.body.V.col(1).maxCoeff() - r.body.V.col(1).minCoeff()},
                {"labels", r.body_labels_from_file ? "file" : "segmentation"}, {"parts", parts_json(r.body_parts)}}},
      {"garments", garments_json},
      {"quality", quality},
      {"layers", {{"count", r.garments.size()}, {"crossings_between", r.layer_crossings}, {"gaps", gaps}}}};
  if (r.settled) {
    report["settle"] = {{"stopped_reason", r.settle.stopped_reason},
                        {"steps", r.settle.totals.steps},
                        {"step_retries", r.settle.totals.retries},
                        {"smallest_dt", r.settle.totals.smallest_dt},
                        {"at_rest_from_seconds", r.settle.rest_at >= 0.0 ? json(r.settle.rest_at) : json(nullptr)},
                        {"mean_speed_at_end", r.settle.mean_speed}};
  }

  // The files, together.
  const auto write_start = Clock::now();
  std::vector<NamedMesh> scene;
  TriangleMesh body_mesh = r.body;
  scene.push_back({"body", body_mesh});
  for (const DressedGarment& g : r.garments) {
    TriangleMesh dressed = g.mesh;
    dressed.V = g.dressed;
    scene.push_back({g.name, dressed});
  }
  json stages = json::array();
  auto write = [&](const fs::path& folder) {
    for (const DressedGarment& g : r.garments) {
      save_mesh(in_file_order(g.mesh, g.placed, g.file), (folder / (g.name + ".placed.obj")).string());
      save_mesh(in_file_order(g.mesh, g.dressed, g.file), (folder / (g.name + ".dressed.obj")).string());
    }
    save_scene(scene, (folder / "dressed.glb").string());
    if (segments) {
      TriangleMesh all = empty_mesh();
      append_mesh(all, r.body, "body_");
      for (const DressedGarment& g : r.garments) append_mesh(all, g.mesh, g.name + "_");
      save_mesh(all, (folder / "segments.ply").string());
    }
    for (const DressStage& s : r.stages)
      stages.push_back({{"name", s.name}, {"ran", s.ran}, {"seconds", s.seconds}, {"reason", s.reason}});
    const double write_seconds = std::chrono::duration<double>(Clock::now() - write_start).count();
    stages.push_back({{"name", "write"}, {"ran", true}, {"seconds", write_seconds},
                      {"reason", std::to_string(2 * r.garments.size() + 1 + segments) + " files and the report"}});
    report["stages"] = stages;
    report["seconds"] = std::chrono::duration<double>(Clock::now() - start).count();
    write_file_atomically((folder / "report.json").string(), report.dump(2) + "\n");
  };
  write_folder(dir, write);
  if (as_json) {
    std::cout << report.dump(2) << "\n";
  } else {
    for (const DressedGarment& g : r.garments) {
      std::cout << g.name << ": " << (g.placed_by_placement ? "placed" : "already on the body") << ", "
                << g.crossings_dressed << " crossings, " << g.inside_dressed << " vertices inside, largest strain "
                << g.max_strain_dressed << "\n";
    }
    std::cout << "wrote " << dir << " in " << report["seconds"].get<double>() << " s\n";
  }
  return 0;
}

}  // namespace dresskit::cli
