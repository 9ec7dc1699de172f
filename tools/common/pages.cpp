#include "common/pages.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "dresskit/cloth/mesh_distance.h"

using namespace dresskit::cloth;
using namespace dresskit::mesh;
using namespace dresskit::report;

namespace dresskit::cli {
using json = nlohmann::json;
namespace {

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

/// A number of the report, or NaN where it holds null (a non-finite value; plots leave it out).
double number(const json& j) {
  return j.is_number() ? j.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

std::string figure(const json& j) {
  if (j.is_number()) return report_number(j.get<double>());
  if (j.is_boolean()) return j.get<bool>() ? "yes" : "no";
  if (j.is_string()) return j.get<std::string>();
  if (j.is_null()) return "–";
  return j.dump();
}

/// Rows of (name, value) for the members of `j` that are numbers, strings, booleans or null.
std::vector<std::vector<std::string>> figures(const json& j, const std::vector<std::string>& keys) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& k : keys)
    if (j.contains(k)) rows.push_back({k, figure(j[k])});
  return rows;
}

// Colliders as meshes for the view: a sphere, a box or a cylinder as they are; a plane as a square
// under the cloth twice its size; a body mesh as read.
ReportMesh sphere_mesh(const Eigen::Vector3d& c, double r, int slices = 32, int stacks = 16) {
  ReportMesh m;
  m.V.resize((stacks + 1) * (slices + 1), 3);
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= slices; ++j) {
      const double t = M_PI * i / stacks, p = 2.0 * M_PI * j / slices;
      m.V.row(i * (slices + 1) + j) =
          c.transpose() +
          r * Eigen::RowVector3d(std::sin(t) * std::cos(p), std::cos(t), std::sin(t) * std::sin(p));
    }
  m.F.resize(2 * stacks * slices, 3);
  int f = 0;
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const int a = i * (slices + 1) + j, b = a + slices + 1;
      m.F.row(f++) << a, a + 1, b;
      m.F.row(f++) << a + 1, b + 1, b;
    }
  return m;
}

ReportMesh box_mesh(const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
  ReportMesh m;
  m.V.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    m.V.row(k) = (c + Eigen::Vector3d((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(),
                                      (k & 4 ? 1 : -1) * h.z()))
                     .transpose();
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6,
      1, 3, 5, 3, 7, 5;
  return m;
}

/// Two unit vectors across `axis`.
std::pair<Eigen::Vector3d, Eigen::Vector3d> across(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d n = axis.normalized();
  const Eigen::Vector3d u =
      (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY())
          .cross(n)
          .normalized();
  return {u, n.cross(u)};
}

ReportMesh cylinder_mesh(const Collider& c, int slices = 32) {
  const auto [u, v] = across(c.normal);
  const Eigen::Vector3d a = c.normal.normalized() * c.half_length;
  ReportMesh m;
  m.V.resize(2 * slices + 2, 3);
  for (int j = 0; j < slices; ++j) {
    const double p = 2.0 * M_PI * j / slices;
    const Eigen::Vector3d rim = c.radius * (std::cos(p) * u + std::sin(p) * v);
    m.V.row(j) = (c.point - a + rim).transpose();
    m.V.row(slices + j) = (c.point + a + rim).transpose();
  }
  m.V.row(2 * slices) = (c.point - a).transpose();
  m.V.row(2 * slices + 1) = (c.point + a).transpose();
  m.F.resize(4 * slices, 3);
  for (int j = 0, f = 0; j < slices; ++j) {
    const int k = (j + 1) % slices;
    m.F.row(f++) << j, k, slices + j;
    m.F.row(f++) << k, slices + k, slices + j;
    m.F.row(f++) << 2 * slices, k, j;
    m.F.row(f++) << 2 * slices + 1, slices + j, slices + k;
  }
  return m;
}

ReportMesh plane_mesh(const Collider& c, const Eigen::MatrixX3d& cloth) {
  const Eigen::Vector3d centre = cloth.colwise().mean().transpose();
  const double size =
      std::max(0.5, 2.0 * (cloth.colwise().maxCoeff() - cloth.colwise().minCoeff()).norm());
  const Eigen::Vector3d n = c.normal.normalized();
  const Eigen::Vector3d on = centre - n * n.dot(centre - c.point);
  const auto [u, v] = across(n);
  ReportMesh m;
  m.V.resize(4, 3);
  m.V << (on - size * (u + v) / 2).transpose(), (on + size * (u - v) / 2).transpose(),
      (on + size * (u + v) / 2).transpose(), (on - size * (u - v) / 2).transpose();
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  return m;
}

/// Each vertex's distance to the nearest collider [mm] (negative inside); exact for body meshes.
Eigen::VectorXd collider_distance_mm(const std::vector<Collider>& colliders,
                                     const Eigen::MatrixX3d& x) {
  Eigen::VectorXd d(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d n;
    for (const Collider& c : colliders) {
      const Eigen::Vector3d p = x.row(i).transpose();
      best = std::min(
          best, c.kind == Collider::Kind::mesh ? c.body->exact_distance(p, &n) : c.distance(p, &n));
    }
    d(i) = 1e3 * best;
  }
  return d;
}

}  // namespace

ReportPage segment_page(const std::string& path, const TriangleMesh& mesh, const json& summary) {
  ReportPage page;
  page.command = "segment";
  page.title = "segment: " + stem(path);
  page.summary = std::to_string(mesh.num_vertices()) + " vertices, " +
                 std::to_string(mesh.num_faces()) + " faces, " +
                 figure(summary.value("parts", json())) + " parts (" +
                 figure(summary.value("parts_chosen_by", json())) + ")";
  ReportMesh m;
  m.name = stem(path);
  m.role = "body";
  m.V = mesh.V;
  m.F = mesh.F;
  m.labels = mesh.labels;
  m.label_names = mesh.label_names;
  page.meshes.push_back(m);
  page.notes.push_back(
      "Choose 'parts' under Colour to see the parts; the mesh as read, in metres, +Y up.");

  std::vector<std::vector<std::string>> rows;
  for (const json& p : summary.value("part_details", json::array()))
    rows.push_back({figure(p["label"]), figure(p["name"]), figure(p["vertices"]),
                    figure(p["area_m2"]), figure(p["confidence"])});
  page.sections.push_back(
      ReportSection::table_of("Parts", {"label", "name", "vertices", "area m²", "confidence"}, rows,
                              "Colours in the view follow the labels' order."));
  const json seconds = summary.value("seconds", json::object());
  std::vector<std::string> labels;
  std::vector<double> values;
  for (const char* k : {"graph", "eigen", "clustering", "naming"})
    if (seconds.contains(k)) labels.push_back(k), values.push_back(number(seconds[k]));
  page.sections.push_back(
      ReportSection::bars_of("Time per step", labels, values, "s",
                             "Total " + figure(seconds.value("total", json())) + " s."));
  std::vector<double> index, spectrum;
  for (const json& v : summary.value("spectrum", json::array())) {
    index.push_back(static_cast<double>(index.size() + 1));
    spectrum.push_back(number(v));
  }
  page.sections.push_back(
      ReportSection::line_of("Spectrum", index, spectrum, "", "eigenvalue",
                             "The smallest eigenvalues of the Laplacian, in order; the number of "
                             "parts is chosen at the largest gap "
                             "(eigengap " +
                                 figure(summary.value("eigengap", json())) + ")."));
  page.sections.push_back(ReportSection::table_of(
      "Figures", {"figure", "value"},
      figures(summary, {"vertices", "faces", "components", "parts", "parts_chosen_by",
                        "limbs_added_after_eigengap", "eigen_residual", "eigen_iterations",
                        "isolated_vertices", "relabelled_by_cleanup",
                        "moved_by_boundary_refinement", "normalized_cut"})));
  page.report_json = summary.dump(2) + "\n";
  return page;
}

ReportPage simulate_page(const std::string& scene_path, const ClothScene& s,
                         const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& end,
                         const RunResult& result, const json& report) {
  ReportPage page;
  page.command = "simulate";
  page.title = "simulate: " + stem(scene_path);
  if (!result.ok) page.failure = result.failure;
  const std::string last = result.ok ? "end" : "last good state";
  page.summary = figure(report.value("steps", json())) + " steps, " +
                 figure(report.value("simulated_seconds", json())) + " s simulated in " +
                 figure(report.value("wall_seconds", json())) + " s; " + result.stopped_reason;
  const std::vector<Collider>& colliders = s.simulation.colliders;
  if (s.faces.rows() > 0) {
    ReportMesh cloth;
    cloth.name = "cloth";
    cloth.role = "cloth";
    cloth.F = s.faces;
    for (const auto& [name, x] :
         {std::make_pair(std::string("start"), &start), std::make_pair(last, &end)}) {
      if (!x->allFinite()) continue;
      cloth.shapes.push_back({name, *x});
      cloth.fields.push_back({"strain", name, "",
                              vertex_strain(*x, s.model.rest_positions, s.faces), 0.0, 0.1, false});
      if (!colliders.empty())
        cloth.fields.push_back({"distance to the colliders", name, "mm",
                                collider_distance_mm(colliders, *x), -5.0, 20.0, true});
    }
    if (!cloth.shapes.empty()) page.meshes.push_back(cloth);
  } else {
    page.notes.push_back("The cloth is a chain (no faces): nothing to show in 3D.");
  }
  int k = 0;
  for (const Collider& c : colliders) {
    ReportMesh m;
    switch (c.kind) {
      case Collider::Kind::sphere:
        m = sphere_mesh(c.point, c.radius);
        break;
      case Collider::Kind::box:
        m = box_mesh(c.point, c.half_size);
        break;
      case Collider::Kind::cylinder:
        m = cylinder_mesh(c);
        break;
      case Collider::Kind::plane:
        m = plane_mesh(c, end.allFinite() ? end : start);
        break;
      case Collider::Kind::mesh:
        m.V = c.body->mesh().V;
        m.F = c.body->mesh().F;
        break;
    }
    m.name = "collider " + std::to_string(k++);
    m.role = c.kind == Collider::Kind::mesh ? "body" : "collider";
    if (!page.meshes.empty()) page.meshes.push_back(m);
  }
  page.default_shape = last;
  if (!page.meshes.empty()) {
    page.notes.push_back(
        "Shapes: the cloth at the start and at the " +
        std::string(result.ok ? "end of the run." : "last good state before the failed step."));
    page.notes.push_back(
        "Colour maps of the cloth: strain, each vertex's largest edge stretch against the rest "
        "shape "
        "(0 to 10 %), and distance to the nearest collider in mm (red inside it, blue 2 cm or more "
        "off it).");
  }

  std::vector<double> time, energy;
  const double fps = s.run.fps > 0.0 ? s.run.fps : 1.0;
  for (const json& e : report.value("energy_history", json::array())) {
    time.push_back(static_cast<double>(time.size()) / fps);
    energy.push_back(number(e));
  }
  page.sections.push_back(
      ReportSection::line_of("Elastic energy over time", time, energy, "s", "J",
                             "At every frame (" + report_number(fps) + " per simulated second)."));
  std::vector<std::string> labels;
  std::vector<double> values;
  const json phases = report.value("phase_seconds", json::object());
  for (const auto& [name, v] : phases.items()) labels.push_back(name), values.push_back(number(v));
  page.sections.push_back(ReportSection::bars_of("Time per phase of a step", labels, values, "s",
                                                 "CPU seconds summed over the steps."));
  page.sections.push_back(ReportSection::table_of(
      "Figures", {"figure", "value"},
      figures(report, {"integrator", "fabric", "vertices", "dt", "adaptive", "smallest_dt", "steps",
                       "step_retries", "frames", "simulated_seconds", "wall_seconds", "max_strain",
                       "mean_strain", "final_residual", "closest_collider_distance_m",
                       "stopped_reason", "nan_detected", "layers"})));
  if (report.contains("intersections")) {
    const json& i = report["intersections"];
    page.sections.push_back(ReportSection::table_of(
        "Cloth crossings", {"at start", "at end", "most over the frames"},
        {{figure(i["at_start"]), figure(i["at_end"]), figure(i["max_over_frames"])}},
        "Edge–triangle crossings of the cloth with itself."));
  }
  if (report.contains("layer_gap_mm")) {
    const json& g = report["layer_gap_mm"];
    page.sections.push_back(ReportSection::table_of(
        "Layer gap", {"min mm", "mean mm", "max mm", "min over frames mm", "max over frames mm"},
        {{figure(g["min"]), figure(g["mean"]), figure(g["max"]), figure(g["min_over_frames"]),
          figure(g["max_over_frames"])}}));
  }
  page.report_json = report.dump(2) + "\n";
  return page;
}

}  // namespace dresskit::cli
