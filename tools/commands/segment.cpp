#include "commands/segment.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "common/output_folder.h"
#include "common/pages.h"

namespace dresskit::cli {
namespace {

Eigen::Vector3d axis_vector(UpAxis axis) {
  switch (axis) {
    case UpAxis::pos_x:
      return Eigen::Vector3d::UnitX();
    case UpAxis::neg_x:
      return -Eigen::Vector3d::UnitX();
    case UpAxis::pos_y:
      return Eigen::Vector3d::UnitY();
    case UpAxis::neg_y:
      return -Eigen::Vector3d::UnitY();
    case UpAxis::pos_z:
      return Eigen::Vector3d::UnitZ();
    case UpAxis::neg_z:
      return -Eigen::Vector3d::UnitZ();
  }
  return Eigen::Vector3d::Zero();
}

bool is_obj(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".obj";
}

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// Labels in the input file's vertex order (source_vertex); file vertices the loader merged into
// another one (duplicate positions) take that vertex's label.
std::vector<int> labels_in_file_order(const TriangleMesh& mesh, const Eigen::VectorXi& labels) {
  int count = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i)
    count = std::max(count, mesh.source_vertex.size() ? mesh.source_vertex(i) + 1 : i + 1);
  std::vector<int> out(count, -1);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const int s = mesh.source_vertex.size() ? mesh.source_vertex(i) : i;
    if (s >= 0) out[s] = labels(i);
  }
  return out;
}

// Vertices without a face that sit exactly on a vertex with a face (a duplicate that the loader's
// joining left unused) take its label; the others stay −1.
int label_duplicates(const TriangleMesh& mesh, Eigen::VectorXi& labels) {
  std::map<std::array<double, 3>, int> labelled;
  for (int i = 0; i < mesh.num_vertices(); ++i)
    if (labels(i) >= 0)
      labelled.emplace(std::array<double, 3>{mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)}, labels(i));
  int filled = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (labels(i) >= 0) continue;
    const auto it = labelled.find({mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)});
    if (it != labelled.end()) labels(i) = it->second, ++filled;
  }
  return filled;
}

// The faces of one part as a mesh of their own (vertices renumbered in order of first use).
TriangleMesh part_mesh(const TriangleMesh& mesh, const Eigen::VectorXi& face_labels, int part) {
  std::vector<int> index(mesh.num_vertices(), -1), vertices;
  std::vector<Eigen::Vector3i> faces;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (face_labels(f) != part) continue;
    Eigen::Vector3i t;
    for (int c = 0; c < 3; ++c) {
      int& k = index[mesh.F(f, c)];
      if (k < 0) k = static_cast<int>(vertices.size()), vertices.push_back(mesh.F(f, c));
      t(c) = k;
    }
    faces.push_back(t);
  }
  TriangleMesh out;
  out.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (size_t k = 0; k < vertices.size(); ++k)
    out.V.row(static_cast<Eigen::Index>(k)) = mesh.V.row(vertices[k]);
  out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f)
    out.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return out;
}

json result_json(const std::string& path, const TriangleMesh& mesh, const SegmentationResult& r,
                 const std::vector<int>& file_labels, int duplicates,
                 const SegmentationOptions& o) {
  json parts = json::array();
  for (size_t p = 0; p < r.parts.size(); ++p)
    parts.push_back({{"label", p},
                     {"name", r.parts[p].name},
                     {"confidence", r.parts[p].confidence},
                     {"component", r.parts[p].component},
                     {"vertices", r.parts[p].vertices},
                     {"area_m2", r.parts[p].area}});
  return {
      {"input", path},
      {"vertices", file_labels.size()},
      {"faces", mesh.num_faces()},
      {"components", r.components},
      {"parts", r.parts_chosen},
      {"parts_chosen_by", r.parts_automatic ? "eigengap" : "given"},
      {"limbs_added_after_eigengap", r.limbs_added},
      {"parts_per_component", r.parts_per_component},
      {"part_names", r.part_names()},
      {"part_details", parts},
      {"eigengap", r.eigengap},
      {"spectrum", std::vector<double>(r.spectrum.data(), r.spectrum.data() + r.spectrum.size())},
      {"eigen_residual", r.eigen_residual},
      {"eigen_iterations", r.eigen_iterations},
      {"isolated_vertices", r.isolated_vertices},
      {"bridged_edges", r.bridged_edges},
      {"duplicate_vertices_labelled", duplicates},
      {"relabelled_by_cleanup", r.relabelled_vertices},
      {"moved_by_boundary_refinement", r.refined_vertices},
      {"normalized_cut", r.normalized_cut},
      {"clusters_before_merge", r.clusters_before_merge},
      {"skirt_components", r.skirt_components},
      {"skirt_band_fraction", r.skirt_band_fraction},
      {"axes",
       {{"up", vec(r.axes.up)},
        {"up_source", r.axes.up_source},
        {"forward", vec(r.axes.forward)},
        {"forward_source", r.axes.forward_source},
        {"left", vec(r.axes.left)}}},
      {"options",
       {{"affinity", to_string(o.affinity.kind)},
        {"convex_weight", o.affinity.convex_weight},
        {"laplacian", to_string(o.laplacian)},
        {"tolerance", o.eigen.tolerance},
        {"ncv", o.eigen.ncv},
        {"kmeans_restarts", o.kmeans.restarts},
        {"over_segmentation", o.over_segmentation},
        {"bridge_gaps", o.bridge_gaps},
        {"boundary_band", o.boundary_band},
        {"limb_tip_fraction", o.limb_tip_fraction},
        {"symmetry", o.symmetry_tolerance},
        {"split_skirts", o.split_skirts},
        {"grow_limbs", o.grow_limbs},
        {"seed", o.kmeans.seed},
        {"cleanup", o.cleanup}}},
      {"seconds",
       {{"graph", r.seconds.graph},
        {"eigen", r.seconds.eigen},
        {"clustering", r.seconds.clustering},
        {"naming", r.seconds.naming},
        {"total", r.seconds.total}}},
      {"vertex_labels_order",
       is_obj(path) ? "the OBJ file's v lines"
                    : "the loader's vertex order (assimp, identical positions joined)"},
      {"vertex_labels", file_labels},
      {"face_labels_order", "triangles of the loaded mesh (a quad a-b-c-d is a-b-c, a-c-d)"},
      {"face_labels",
       std::vector<int>(r.face_labels.data(), r.face_labels.data() + r.face_labels.size())}};
}

// Writes the texts and meshes into DIR, all of them or none, never over the input.
void write_outputs(const std::string& dir,
                   const std::vector<std::pair<std::string, std::string>>& texts,
                   const std::vector<std::pair<std::string, TriangleMesh>>& meshes, const std::string& input) {
  write_folder(
      dir,
      [&](const fs::path& temp) {
        for (const auto& [name, text] : texts) write_file_atomically((temp / name).string(), text);
        for (const auto& [name, mesh] : meshes) save_mesh(mesh, (temp / name).string());
      },
      {input});
}

}  // namespace

void SegmentCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("segment",
                               "cut a body or garment mesh into named parts by spectral "
                               "clustering; writes labels.json, segments.ply and one OBJ "
                               "per part (docs/segmentation.md)");
  command->add_option("MESH", path, "input mesh (obj, ply, off, stl, gltf, glb, fbx)")->required();
  command->add_option("--parts", parts, "number of parts (default: chosen by the eigengap)");
  option_with_default(command, "--max-parts", options.max_parts,
                      "largest automatic number of parts");
  option_with_default(command, "--units", units,
                      "source length unit: m, dm, cm, mm or metres per unit");
  command->add_option("--up", up,
                      "source up axis: +x, -x, +y, -y, +z, -z (default: estimated by PCA, "
                      "the mesh read as +y)");
  command->add_option("--forward", forward,
                      "the character's facing axis after --up "
                      "(default: estimated from the feet, else +z)");
  command->add_option("-o,--output", output, "output directory")->required();
  option_with_default(command, "--affinity", affinity, "dihedral, edge-length or cotangent");
  option_with_default(command, "--laplacian", laplacian, "normalized or plain");
  option_with_default(command, "--tolerance", options.eigen.tolerance, "eigen-solver tolerance");
  option_with_default(command, "--ncv", options.eigen.ncv,
                      "eigen-solver subspace size (0: automatic)");
  option_with_default(command, "--bridge-gaps", options.bridge_gaps,
                      "join boundary vertices closer than this many mean edge lengths (0: off)");
  option_with_default(
      command, "--over-segmentation", options.over_segmentation,
      "also try k+1 .. k+N clusters merged back to k by structure (0: plain k-means)");
  option_with_default(command, "--boundary-band", options.boundary_band,
                      "random-walker band around each cut, in radii of the junction (0: off)");
  option_with_default(command, "--limb-tip", options.limb_tip_fraction,
                      "limb cuts follow the harmonic field from tips beyond this fraction of the "
                      "limb's depth (0: off)");
  option_with_default(command, "--symmetry", options.symmetry_tolerance,
                      "limb cuts made mirror-symmetric when the mesh is symmetric within this many "
                      "mean edge lengths (0: off)");
  option_with_default(command, "--grow-limbs", options.grow_limbs,
                      "automatic parts: a closed mesh takes more parts while each new one is a "
                      "limb (1) or keeps the eigengap's choice (0)");
  option_with_default(command, "--split-skirts", options.split_skirts,
                      "cut a two-opening tube (a skirt) into waist band and left and right halves "
                      "(1) or leave it to the spectrum (0)");
  command->add_flag("--json", as_json, "print labels.json's summary fields as JSON");
}

int SegmentCommand::run() {
  LoadOptions load;
  load.units = Units::parse(units);
  load.up = parse_up_axis(up);
  if (parts != -1 && parts < 1)
    throw InputError("--parts: " + std::to_string(parts) + " (must be at least 1)");
  options.parts = parts == -1 ? 0 : parts;
  if (options.max_parts < 1)
    throw InputError("--max-parts: " + std::to_string(options.max_parts) + " (must be at least 1)");
  options.affinity.kind = parse_affinity(affinity);
  options.laplacian = parse_laplacian(laplacian);
  if (command->count("--up")) options.up = Eigen::Vector3d::UnitY();  // the loader turned it to +Y
  if (!forward.empty()) {
    // Given in the file's axes, like --up; the loader turns the file so that its up is +Y.
    options.forward = up_rotation(load.up) * axis_vector(parse_up_axis(forward));
    if (std::abs(options.forward.y()) > 0.5)
      throw InputError("--forward " + forward + ": along the up axis (--up " + up + "); the character faces across it");
  }
  if (!(options.eigen.tolerance > 0)) throw InputError("--tolerance: must be positive");
  if (!(options.bridge_gaps >= 0)) throw InputError("--bridge-gaps: must be 0 or more");
  if (!(options.boundary_band >= 0)) throw InputError("--boundary-band: must be 0 or more");
  if (!(options.limb_tip_fraction >= 0 && options.limb_tip_fraction < 1))
    throw InputError("--limb-tip: must be at least 0 and less than 1");

  const OutputLock lock = check_output_folder(output, {path}, {"labels.json", "report.html", "segments.ply"});
  const TriangleMesh mesh = load_mesh(path, load);
  SegmentationResult r;
  try {
    r = segment_mesh(mesh, options);
  } catch (const EigenSolverError& e) {
    throw InputError(path + ": " + e.what());
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
  Eigen::VectorXi labels = r.vertex_labels;
  const int duplicates = label_duplicates(mesh, labels);
  const std::vector<int> file_labels = labels_in_file_order(mesh, labels);
  const json report = result_json(path, mesh, r, file_labels, duplicates, options);

  TriangleMesh coloured = mesh;
  coloured.labels = labels;
  coloured.label_names = r.part_names();
  std::vector<std::pair<std::string, TriangleMesh>> meshes = {{"segments.ply", coloured}};
  for (size_t p = 0; p < r.parts.size(); ++p)
    meshes.emplace_back(r.parts[p].name + ".obj",
                        part_mesh(mesh, r.face_labels, static_cast<int>(p)));
  json summary = report;
  summary.erase("vertex_labels");
  summary.erase("face_labels");
  write_outputs(output,
                {{"labels.json", report.dump(1) + "\n"},
                 {"report.html", report_html(segment_page(path, coloured, summary))}},
                meshes, path);

  if (as_json) {
    std::cout << summary.dump(2) << "\n";
    return 0;
  }
  std::printf("%s: %d vertices, %d faces, %d component(s); %d parts (%s", path.c_str(),
              mesh.num_vertices(), mesh.num_faces(), r.components, r.parts_chosen,
              r.parts_automatic ? "eigengap" : "given");
  if (r.eigengap > 0) std::printf(", eigengap %.2f", r.eigengap);
  if (r.limbs_added > 0)
    std::printf(", then %d more limb%s", r.limbs_added, r.limbs_added > 1 ? "s" : "");
  std::printf(")\n");
  for (const auto& p : r.parts)
    std::printf("  %-14s %6d vertices  %7.4f m²  confidence %.2f\n", p.name.c_str(), p.vertices,
                p.area, p.confidence);
  std::printf("up (%.2f %.2f %.2f) %s, forward (%.2f %.2f %.2f) %s; eigen residual %.1e; %.0f ms\n",
              r.axes.up.x(), r.axes.up.y(), r.axes.up.z(), r.axes.up_source.c_str(),
              r.axes.forward.x(), r.axes.forward.y(), r.axes.forward.z(),
              r.axes.forward_source.c_str(), r.eigen_residual, r.seconds.total * 1e3);
  for (size_t k = 0; k < r.skirt_components.size(); ++k)
    std::printf("component %d is a skirt: waist band down to %.0f %% of its length, then halves\n",
                r.skirt_components[k], 100 * r.skirt_band_fraction[k]);
  if (r.isolated_vertices)
    std::printf("%d vertices without a face (%d duplicates labelled, the rest -1)\n",
                r.isolated_vertices, duplicates);
  std::printf("wrote labels.json, segments.ply, report.html and %zu part OBJs to %s\n", r.parts.size(),
              output.c_str());
  return 0;
}

}  // namespace dresskit::cli
