#include "dresskit/dressing/outputs.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/report/page.h"
#include "report_page.h"

using namespace dresskit::alignment;
using namespace dresskit::mesh;
using namespace dresskit::report;

namespace dresskit::dressing {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

/// Positions in the file's own vertex order, units and axes (a mesh given in memory: its order, in
/// metres): the mesh's rows mapped back through source_vertex (a vertex the toolkit dropped keeps
/// the given position), faces likewise.
TriangleMesh in_file_order(const DressedGarment& g, const Eigen::MatrixX3d& V) {
  TriangleMesh result;
  const TriangleMesh& mesh = g.mesh;
  const TriangleMesh original = g.in_memory ? *g.file.mesh : g.from_pattern ? g.mesh : load_mesh(g.file.path, g.file.load);
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
  result.V = g.in_memory ? out : to_file_frame(out, g.file.load);
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
  // The file's texture coordinates and quads, in its vertex order (the writer keeps a quad whose
  // two triangles are both among the faces).
  const auto file_vertex = [&](int i) { return original.source_vertex.size() ? original.source_vertex(i) : i; };
  if (original.UV.rows() == original.num_vertices() && original.num_vertices() > 0) {
    result.UV = Eigen::MatrixX2d::Zero(count, 2);
    for (int i = 0; i < original.num_vertices(); ++i)
      if (file_vertex(i) >= 0 && file_vertex(i) < count) result.UV.row(file_vertex(i)) = original.UV.row(i);
  }
  result.quads.resize(original.quads.rows(), 4);
  int quads = 0;
  for (Eigen::Index q = 0; q < original.quads.rows(); ++q) {
    bool ok = true;
    for (int k = 0; k < 4; ++k) {
      result.quads(quads, k) = file_vertex(original.quads(q, k));
      ok = ok && result.quads(quads, k) >= 0 && result.quads(quads, k) < count;
    }
    quads += ok;
  }
  result.quads.conservativeResize(quads, 4);
  // Per face: corner texture coordinates (a file's UV seams, a pattern's flat panels) and groups
  // (a pattern's panels), where every face was written.
  if (kept == mesh.num_faces()) {
    if (mesh.FTC.rows() == mesh.num_faces()) result.TC = mesh.TC, result.FTC = mesh.FTC;
    if (mesh.face_groups.size() == mesh.num_faces())
      result.face_groups = mesh.face_groups, result.group_names = mesh.group_names;
  }
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
  out["pushed_out_vertices"] = p.pushed_out;
  out["seconds"] = p.seconds;
  return out;
}

/// A garment mesh's wearer: where the body stood in it, and how far carrying it moves it.
json wearer_json(const DressedGarment& g) {
  if (!g.wearer) return nullptr;
  const alignment::WearerFit& w = *g.wearer;
  return {{"scale", w.scale},
          {"largest_turn_deg", alignment::largest_turn_degrees(w)},
          {"rms_mm", 1e3 * alignment::rms_from_ease(w)},
          {"cost_as_is_ratio", w.cost > 0.0 ? json(w.cost_as_is / w.cost) : json(nullptr)},
          {"start", w.start},
          {"iterations", w.iterations},
          {"carry_move_p95_mm", 1e3 * g.carry_move},
          {"seconds", w.seconds}};
}

const char* labels_source(bool given, const MeshFile& file) {
  return !given ? "segmentation" : file.labels.empty() ? "given with the mesh" : "file";
}

/// A garment sewn from a pattern: its seams when sewing stopped, its panels' areas flat and
/// dressed, and how long cutting and sewing took.
json pattern_json(const SewnPattern& p) {
  json panels = json::array();
  for (std::size_t k = 0; k < p.panels.size(); ++k) {
    const bool dressed = k < p.panel_area_dressed.size();
    panels.push_back({{"name", p.panels[k]},
                      {"part", k < p.panel_parts.size() ? json(p.panel_parts[k]) : json(nullptr)},
                      {"area_m2", p.panel_area[k]},
                      {"area_dressed_m2", dressed ? json(p.panel_area_dressed[k]) : json(nullptr)},
                      {"area_change", dressed ? json(p.panel_area_dressed[k] / p.panel_area[k] - 1.0) : json(nullptr)}});
  }
  return {{"seams",
           {{"count", p.stitches},
            {"pairs", p.stitch_pairs},
            {"sewn_pairs", p.sewn_pairs},
            {"welded_open_pairs", p.welded_open_pairs},
            {"unwelded_pairs", p.unwelded.size()},
            {"max_gap_m", p.max_gap},
            {"closed", p.closed},
            {"method", p.sew_method},
            {"stopped", p.sew_stopped},
            {"steps", p.sew_steps},
            {"contacts", p.sew_contacts}}},
          {"panels", panels},
          {"pattern",
           {{"triangles", p.triangles},
            {"carried_by", p.carried_by},
            {"moved_to_body_m", {p.moved_by.x(), p.moved_by.y(), p.moved_by.z()}},
            {"panels_moved_out", p.panels_moved_out},
            {"cut_seconds", p.cut_seconds},
            {"sew_seconds", p.sew_seconds},
            {"sew_simulated_seconds", p.sew_simulated},
            {"warnings", p.warnings}}}};
}

/// A padded garment: its thickness asked and the shells' distance dressed.
json padding_json(const DressedGarment& g) {
  const PaddingFigures& p = g.padding;
  json out = {{"thickness_mm", 1e3 * p.thickness}, {"min_mm", 1e3 * p.min}, {"max_mm", 1e3 * p.max},
              {"by", "heat conduction"}, {"start_at_full_thickness", p.start_at_full},
              {"crossings", {{"start", p.crossings_start}, {"dressed", p.crossings}}}};
  if (g.dressed_outer.rows() > 0)
    out["gap_mm"] = {{"min", 1e3 * p.gap_min}, {"p5", 1e3 * p.gap_p5}, {"median", 1e3 * p.gap_median},
                     {"max", 1e3 * p.gap_max}, {"vertices_below_min", p.below_min}};
  return out;
}

json report_json(const DressResult& r) {
  json garments = json::array();
  for (const DressedGarment& g : r.garments) {
    garments.push_back(
        {{"name", g.name},
         {"path", g.in_memory ? json(nullptr) : json(g.file.path)},
         {"units", g.in_memory ? "m" : g.file.load.units.name},
         {"fabric", g.fabric},
         {"vertices", g.mesh.num_vertices()},
         {"labels", !g.labels_from_file && g.wearer ? "wearer" : labels_source(g.labels_from_file, g.file)},
         {"parts", parts_json(g.parts)},
         {"wearer", wearer_json(g)},
         {"placement", placement_json(g)},
         {"layer", g.layer},
         {"thickness_mm", 1e3 * g.thickness},
         {"crossings", {{"authored", g.crossings_authored}, {"fitted", g.crossings_fitted}, {"placed", g.crossings_placed},
                        {"dressed", g.crossings_dressed}}},
         {"vertices_inside_body_2mm", {{"placed", g.inside_placed}, {"dressed", g.inside_dressed}}},
         {"max_strain", g.max_strain_dressed},
         {"strain_p99", g.strain_p99_dressed},
         {"springs_over_limit", g.springs_over_limit},
         {"waistband_vertices", g.waistband_vertices},
         {"tangle_held_vertices", g.tangle_held_vertices},
         {"warnings", g.warnings},
         {"outputs", {{"placed", g.name + ".placed.obj"}, {"dressed", g.name + ".dressed.obj"}}}});
    if (g.from_pattern) garments.back().update(pattern_json(g.pattern));
    if (g.padded) garments.back()["padding"] = padding_json(g);
    if (g.dressed_outer.rows() > 0) garments.back()["outputs"]["dressed_outer"] = g.name + ".outer.obj";
  }
  json gaps = json::array();
  for (std::size_t k = 0; k < r.layer_gap_median.size(); ++k)
    gaps.push_back({{"inner", r.garments[k].name}, {"outer", r.garments[k + 1].name},
                    {"overlapping_vertices", r.layer_gap_vertices[k]},
                    {"p5_mm", r.layer_gap_vertices[k] > 0 ? json(1e3 * r.layer_gap_p5[k]) : json(nullptr)},
                    {"median_mm", r.layer_gap_vertices[k] > 0 ? json(1e3 * r.layer_gap_median[k]) : json(nullptr)},
                    {"asked_mm", 1e3 * r.layer_gap_asked[k]}});
  json report = {
      {"body", {{"path", r.body_file.path}, {"units", r.body_file.load.units.name},
                {"vertices", r.body.num_vertices()},
                {"height_m", r.body.V.col(1).maxCoeff() - r.body.V.col(1).minCoeff()},
                {"labels", labels_source(r.body_labels_from_file, r.body_file)},
                {"parts", parts_json(r.body_parts)}}},
      {"garments", garments},
      {"quality", to_string(r.quality)},
      {"layers", {{"count", r.garments.size()}, {"crossings_between", r.layer_crossings}, {"gaps", gaps}}},
      {"warnings", r.warnings}};
  if (r.settled) {
    report["settle"] = {{"stopped_reason", r.settle.stopped_reason},
                        {"steps", r.settle.totals.steps},
                        {"step_retries", r.settle.totals.retries},
                        {"smallest_dt", r.settle.totals.smallest_dt},
                        {"at_rest_from_seconds", r.settle.rest_at >= 0.0 ? json(r.settle.rest_at) : json(nullptr)},
                        {"mean_speed_at_end", r.settle.mean_speed},
                        {"stuck_steps", r.settle.totals.stuck_steps},
                        {"warnings", r.settle.warnings}};
  }
  if (r.padding_ran)
    report["padding"] = {{"stopped_reason", r.padding_settle.stopped_reason},
                         {"stalled", r.padding_settle.stalled},
                         {"steps", r.padding_settle.totals.steps},
                         {"at_rest_from_seconds", r.padding_settle.rest_at >= 0.0 ? json(r.padding_settle.rest_at) : json(nullptr)}};
  return report;
}

json report_with_extra(const DressResult& r, const DressOutputOptions& options) {
  json report = report_json(r);
  if (!options.report_extra.empty()) {
    const json extra = json::parse(options.report_extra, nullptr, false);
    if (!extra.is_object()) throw InputError("report extra: not the text of a JSON object");
    report.update(extra);
  }
  return report;
}

json stages_json(const DressResult& r) {
  json stages = json::array();
  for (const DressStage& s : r.stages)
    stages.push_back({{"name", s.name}, {"ran", s.ran}, {"seconds", s.seconds}, {"reason", s.reason}});
  return stages;
}

}  // namespace

std::string write_dress_outputs(const std::string& folder, const DressResult& r, const DressOutputOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  json report = report_with_extra(r, options);
  const fs::path dir(folder);
  for (const DressedGarment& g : r.garments) {
    save_mesh(in_file_order(g, g.placed), (dir / (g.name + ".placed.obj")).string());
    save_mesh(in_file_order(g, g.dressed), (dir / (g.name + ".dressed.obj")).string());
    if (g.dressed_outer.rows() > 0) save_mesh(in_file_order(g, g.dressed_outer), (dir / (g.name + ".outer.obj")).string());
  }
  std::vector<NamedMesh> scene;
  scene.push_back({"body", r.body});
  for (const DressedGarment& g : r.garments) {
    TriangleMesh dressed = g.mesh;
    dressed.V = g.dressed;
    dressed.N.resize(0, 3);  // the file's normals are of its rest shape: the writer takes the dressed shape's
    scene.push_back({g.name, dressed});
    if (g.dressed_outer.rows() == 0) continue;
    dressed.V = g.dressed_outer;
    scene.push_back({g.name + ".outer", dressed});
  }
  save_scene(scene, (dir / "dressed.glb").string());
  if (options.segments) {
    TriangleMesh all = empty_mesh();
    append_mesh(all, r.body, "body_");
    for (const DressedGarment& g : r.garments) append_mesh(all, g.mesh, g.name + "_");
    save_mesh(all, (dir / "segments.ply").string());
  }
  // The page's meshes and colour maps are made before the write stage's time is taken; its text,
  // which holds report.json's, after.
  ReportPage page;
  if (options.page) page = detail::dress_page(r, options.command, "");
  json stages = stages_json(r);
  const auto padded = std::count_if(r.garments.begin(), r.garments.end(), [](const DressedGarment& g) { return g.dressed_outer.rows() > 0; });
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  stages.push_back({{"name", "write"}, {"ran", true}, {"seconds", seconds},
                    {"reason", std::to_string(2 * r.garments.size() + padded + 1 + options.segments) + " files and the report" +
                                   (options.page ? " and its page" : "")}});
  report["stages"] = stages;
  report["seconds"] = r.seconds + seconds;
  const std::string text = report.dump(2) + "\n";
  write_file_atomically((dir / "report.json").string(), text);
  if (options.page) {
    page.report_json = text;
    write_report_html((dir / "report.html").string(), page);
  }
  return text;
}

void write_dress_failure_page(const std::string& folder, const DressResult& r, const DressOutputOptions& options,
                              const std::string& refused) {
  const bool padding = r.settle.ok && r.padding_ran && !r.padding_settle.ok;  // the padding's run failed
  const cloth::RunResult& run = padding ? r.padding_settle : r.settle;
  const std::string failure = !refused.empty() ? "refused at " + r.stages.back().name + ": " + refused
                              : std::string(padding ? "padding" : "settling") + " stopped after " +
                                    std::to_string(run.totals.steps) + " steps: " +
                                    (run.failure.empty() ? run.stopped_reason : run.failure);
  ReportPage page = detail::dress_page(r, options.command, failure);
  json report = report_with_extra(r, options);
  report["stages"] = stages_json(r);
  report["seconds"] = r.seconds;
  report["failure"] = failure;
  page.report_json = report.dump(2) + "\n";
  write_report_html((fs::path(folder) / "report.html").string(), page);
}

}  // namespace dresskit::dressing
