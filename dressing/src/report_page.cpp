#include "report_page.h"

#include <algorithm>
#include <filesystem>

#include "dresskit/mesh/inside.h"
#include "garments.h"

using namespace dresskit::cloth;
using namespace dresskit::report;

using namespace dresskit::alignment;
using namespace dresskit::mesh;

namespace dresskit::dressing::detail {
namespace {

/// Colour map ranges: distance to the body from 5 mm inside (red) to 2 cm off it (blue); strain
/// from none to 10 %, the simulator's default strain limit (beyond it the top colour).
constexpr double kInsideMm = -5.0, kOffMm = 20.0, kStrainTop = 0.1;

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

/// Each vertex's signed distance to the body [mm], negative inside.
Eigen::VectorXd distance_mm(const Eigen::MatrixX3d& V, const InsideTest& body) {
  Eigen::VectorXd d(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    d(i) = 1e3 * body.signed_distance(V.row(i).transpose());
  return d;
}

std::string yes(bool ran) { return ran ? "yes" : "left out"; }

std::string garment_list(const DressResult& r) {
  std::string names;
  for (const DressedGarment& g : r.garments) names += (names.empty() ? "" : ", ") + g.name;
  return names;
}

void add_tables(const DressResult& r, ReportPage& page) {
  std::vector<std::vector<std::string>> rows;
  // First what went wrong, where it cannot be missed.
  for (const std::string& w : r.warnings) rows.push_back({"outfit", w});
  for (const std::string& w : r.settle.warnings) rows.push_back({"settle", w});
  for (const DressedGarment& g : r.garments)
    for (const std::string& w : g.warnings) rows.push_back({g.name, w});
  if (!rows.empty())
    page.sections.push_back(ReportSection::table_of("Warnings", {"about", "warning"}, rows));
  rows.clear();
  std::vector<std::string> labels;
  std::vector<double> seconds;
  for (const DressStage& s : r.stages) {
    rows.push_back({s.name, yes(s.ran), report_number(s.seconds), s.reason});
    labels.push_back(s.name);
    seconds.push_back(s.seconds);
  }
  page.sections.push_back(
      ReportSection::bars_of("Time per stage", labels, seconds, "s",
                             "Wall-clock; writing the files is in the table of report.json."));
  page.sections.push_back(ReportSection::table_of(
      "Stages", {"stage", "ran", "seconds", "what it did, or why not"}, rows));

  rows.clear();
  for (const DressedGarment& g : r.garments) {
    rows.push_back({g.name, g.fabric, std::to_string(g.layer),
                    g.placed_by_placement ? "placed" : "already on the body",
                    report_number(1e3 * g.thickness), std::to_string(g.crossings_authored),
                    std::to_string(g.crossings_fitted), std::to_string(g.crossings_placed),
                    std::to_string(g.crossings_dressed), std::to_string(g.inside_placed),
                    std::to_string(g.inside_dressed), report_number(g.max_strain_dressed),
                    std::to_string(g.waistband_vertices)});
  }
  page.sections.push_back(ReportSection::table_of(
      "Garments",
      {"garment", "fabric", "layer", "placement", "thickness mm", "crossings authored", "fitted",
       "placed", "dressed", "inside placed", "inside dressed", "largest strain",
       "waistband vertices"},
      rows,
      "Crossings: edge–triangle crossings of the garment with itself. Inside: vertices deeper than "
      "2 mm in the "
      "body. Strain: the largest structural strain against the rest shape."));

  rows.clear();
  for (std::size_t k = 0; k < r.layer_gap_median.size(); ++k) {
    const bool overlap = r.layer_gap_vertices[k] > 0;
    rows.push_back({r.garments[k].name, r.garments[k + 1].name,
                    std::to_string(r.layer_gap_vertices[k]),
                    overlap ? report_number(1e3 * r.layer_gap_p5[k]) : "–",
                    overlap ? report_number(1e3 * r.layer_gap_median[k]) : "–",
                    report_number(1e3 * r.layer_gap_asked[k])});
  }
  if (!rows.empty()) {
    page.sections.push_back(ReportSection::table_of(
        "Layer gaps",
        {"inner", "outer", "overlapping vertices", "5th percentile mm", "median mm", "asked mm"},
        rows,
        "Of the outer garment's vertices within 2 cm of the inner one, their distance to it. "
        "Crossings between the "
        "garments at the end: " +
            std::to_string(r.layer_crossings) + "."));
  }

  if (r.settled) {
    const StepTotals& t = r.settle.totals;
    page.sections.push_back(
        ReportSection::table_of("Settling",
                                {"stopped", "steps", "step retries", "smallest step s",
                                 "at rest from s", "mean speed at end m/s"},
                                {{r.settle.stopped_reason, std::to_string(t.steps),
                                  std::to_string(t.retries), report_number(t.smallest_dt),
                                  r.settle.rest_at >= 0.0 ? report_number(r.settle.rest_at) : "–",
                                  report_number(r.settle.mean_speed)}}));
    page.sections.push_back(ReportSection::line_of("Elastic energy over the settle", r.settle_time,
                                                   r.settle_energy, "s", "J"));
    page.sections.push_back(ReportSection::line_of(
        "Largest strain over the settle", r.settle_time, r.settle_strain, "s", "",
        "The largest structural spring strain (length over rest length − 1) after each step."));
  }

  rows.clear();
  for (const DressedGarment& g : r.garments) {
    if (!g.wearer) continue;
    const alignment::WearerFit& w = *g.wearer;
    rows.push_back({g.name, report_number(w.scale), report_number(alignment::largest_turn_degrees(w)),
                    report_number(1e3 * alignment::rms_from_ease(w)), report_number(1e3 * g.carry_move),
                    g.placed_by_placement ? "carried onto the body" : "left as given: already on the body"});
  }
  if (!rows.empty()) {
    page.sections.push_back(ReportSection::table_of(
        "Wearers",
        {"garment", "wearer's size", "largest limb turn °", "RMS from an even ease mm", "carry moves (p95) mm", "placement"},
        rows,
        "The body fitted into each garment mesh where the garment's own wearer stood: its size against "
        "the body's, how far its limbs turned, and how far carrying the garment from there moves it."));
  }

  rows.clear();
  for (const DressPart& p : r.body_parts)
    rows.push_back({"body", p.name, std::to_string(p.vertices), report_number(p.confidence)});
  for (const DressedGarment& g : r.garments)
    for (const DressPart& p : g.parts)
      rows.push_back({g.name, p.name, std::to_string(p.vertices), report_number(p.confidence)});
  page.sections.push_back(
      ReportSection::table_of("Parts", {"mesh", "part", "vertices", "confidence"}, rows,
                              "The colours of the view's 'parts' follow this order per mesh."));
}

}  // namespace

ReportPage dress_page(const DressResult& r, const std::string& command,
                      const std::string& failure) {
  ReportPage page;
  page.command = command;
  page.failure = failure;
  const std::string body_name = r.body_file.mesh ? r.body_file.path : stem(r.body_file.path);
  page.title = command + ": " + body_name + " in " + garment_list(r);
  const bool settled = r.settled;
  const std::string last = failure.empty() ? "dressed" : "last good state";
  page.summary = std::to_string(r.garments.size()) + " garment" +
                 (r.garments.size() == 1 ? "" : "s") + ", quality " + to_string(r.quality) + ", " +
                 report_number(r.seconds) + " s" +
                 (settled ? "" : "; not settled (dressed = placed)");

  ReportMesh body;
  // Named as given unless a garment has that name.
  body.name = std::any_of(r.garments.begin(), r.garments.end(),
                          [&](const DressedGarment& g) { return g.name == body_name; })
                  ? "body " + body_name
                  : body_name;
  body.role = "body";
  body.V = r.body.V;
  body.F = r.body.F;
  if (r.body.labels.size() == r.body.V.rows()) {
    body.labels = r.body.labels;
    body.label_names = r.body.label_names;
  }
  page.meshes.push_back(body);

  const InsideTest inside(r.body);
  for (const DressedGarment& g : r.garments) {
    ReportMesh m;
    m.name = g.name;
    m.role = "garment";
    m.F = g.mesh.F;
    if (g.mesh.labels.size() == g.mesh.V.rows()) {
      m.labels = g.mesh.labels;
      m.label_names = g.mesh.label_names;
    }
    const Eigen::MatrixX3d rest = rest_shape(g).V;
    std::vector<std::pair<std::string, const Eigen::MatrixX3d*>> shapes = {{"placed", &g.placed}};
    if (settled) shapes.emplace_back(last, &g.dressed);
    for (const auto& [name, V] : shapes) {
      if (V->rows() != g.mesh.V.rows() || !V->allFinite()) continue;
      m.shapes.push_back({name, *V});
      ReportField distance{
          "distance to the body", name, "mm", distance_mm(*V, inside), kInsideMm, kOffMm, true};
      ReportField strain{"strain", name,       "",   vertex_strain(*V, rest, g.mesh.F),
                         0.0,      kStrainTop, false};
      m.fields.push_back(distance);
      m.fields.push_back(strain);
    }
    if (m.shapes.empty()) continue;  // nothing finite to show
    page.meshes.push_back(m);
  }
  page.default_shape = settled ? last : "placed";
  page.notes.push_back(
      settled ? "Shapes: placed (as handed to settling) and " + last +
                    (failure.empty() ? " (after settling)." : " (where settling stopped).")
              : "Shape: placed (settling was not asked for).");
  page.notes.push_back(
      "Colour maps of the garments: distance to the body in mm (red inside it, white on it, blue "
      "2 cm or more off it) and strain, each vertex's largest edge stretch against the rest shape "
      "settled from (0 to 10 %, the default strain limit, and beyond in the top colour).");
  add_tables(r, page);
  return page;
}

}  // namespace dresskit::dressing::detail
