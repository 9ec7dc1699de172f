#pragma once
// A run's result as one self-contained HTML page (docs/formats.md, report.html): an orbitable 3D
// view of its meshes (WebGL, three.js inlined at build time) with toggles per mesh, part colours
// and per-vertex colour maps, then tables and plots of the run's figures, then the report's JSON.
// Everything is in the file: it opens offline, from file://, in any browser.
//
//   dresskit::report::ReportPage page;
//   page.title = "dress: body in shirt";
//   dresskit::report::ReportMesh body{"body", "body", V, F};
//   page.meshes.push_back(body);
//   page.sections.push_back(dresskit::report::ReportSection::table_of("Stages", {"stage", "s"}, rows));
//   dresskit::report::write_report_html("out/report.html", page);
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace dresskit::report {

/// One value per vertex of a mesh in one of its shapes, drawn as a colour map.
struct ReportField {
  std::string name;        ///< the colour map's name in the page ("distance to the body", "strain")
  std::string shape;       ///< the shape (ReportMesh::shapes) it belongs to
  std::string unit;        ///< shown in the legend ("mm", "" for none)
  Eigen::VectorXd values;  ///< #V, finite (a non-finite value is drawn as the lowest colour)
  /// The legend's range: values at or beyond it take the end colours. With `diverging`, below 0
  /// runs from white to red at `low` (< 0) and above 0 from white to blue at `high`; otherwise a
  /// sequential map (dark blue at `low` to yellow at `high`).
  double low = 0.0, high = 1.0;
  bool diverging = false;
};

/// One named set of positions of a mesh: "placed", "dressed", "start", "end" [m, +Y up].
struct ReportShape {
  std::string name;
  Eigen::MatrixX3d V;  ///< #V×3
};

/// A mesh of the 3D view. Shapes that a page's other meshes have and this one lacks show its first.
struct ReportMesh {
  std::string name;    ///< its toggle's label; unique within a page
  std::string role;    ///< "body", "garment", "cloth" or "collider": its plain colour and legend
  Eigen::MatrixX3d V;  ///< the first shape's positions (#V×3 [m], +Y up) when `shapes` is empty
  Eigen::MatrixX3i F;  ///< #F×3 triangles
  Eigen::VectorXi labels;                ///< #V part per vertex (−1: none), or empty
  std::vector<std::string> label_names;  ///< the parts' names
  std::vector<ReportShape> shapes;       ///< other than V: every shape, in the page's order
  std::vector<ReportField> fields;
};

/// A part of the page below the 3D view: a table, a bar chart, a line plot or a paragraph.
struct ReportSection {
  enum class Kind { table, bars, line, text };
  Kind kind = Kind::text;
  std::string title;
  std::string text;  ///< text: the paragraph; other kinds: a note under it ("" = none)
  /// table: the header and rows of cells (text, shown as given).
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  /// bars: one bar per label; line: y over x. `unit` names the value axis, `x_unit` the line's x.
  std::vector<std::string> labels;
  std::vector<double> x, values;
  std::string unit, x_unit;

  static ReportSection table_of(std::string title, std::vector<std::string> columns,
                                std::vector<std::vector<std::string>> rows, std::string note = "");
  static ReportSection bars_of(std::string title, std::vector<std::string> labels,
                               std::vector<double> values, std::string unit, std::string note = "");
  static ReportSection line_of(std::string title, std::vector<double> x, std::vector<double> y,
                               std::string x_unit, std::string unit, std::string note = "");
  static ReportSection text_of(std::string title, std::string text);
};

struct ReportPage {
  std::string title;    ///< the page's heading ("dress: mannequin in trousers, tshirt")
  std::string command;  ///< the command that wrote it ("dress", "demo", "segment", "simulate")
  /// "" for a run that succeeded; otherwise what failed, shown at the top of the page.
  std::string failure;
  std::string summary;  ///< one line under the heading ("" = none)
  std::vector<ReportMesh> meshes;
  std::string default_shape;  ///< the shape shown first ("" = the first mesh's first)
  /// Said under the 3D view: what the shapes are, which colour maps are missing and why.
  std::vector<std::string> notes;
  std::vector<ReportSection> sections;
  std::string report_json;  ///< the run's report.json text, shown folded at the end ("" = none)
};

/// The page's text: one HTML file with three.js, the meshes (base64 float32 and uint32 arrays) and
/// the figures inside. Throws InputError for a mesh whose arrays disagree in size, a face index out
/// of range, a non-finite position, or two meshes of one name.
std::string report_html(const ReportPage& page);

/// Writes report_html(page) to `path` (written beside it and moved into place); throws OutputError
/// naming the path when it cannot be written.
void write_report_html(const std::string& path, const ReportPage& page);

/// Each vertex's largest stretch over its edges against the rest shape (length / rest length − 1;
/// 0 where no edge of it is longer than at rest): the page's strain colour map.
Eigen::VectorXd vertex_strain(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& rest,
                              const Eigen::MatrixX3i& F);

/// A number as the page's tables show it: `digits` significant digits, no exponent for ordinary
/// sizes; "–" for a non-finite value.
std::string report_number(double value, int digits = 3);

}  // namespace dresskit::report
