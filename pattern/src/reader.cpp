// GarmentCode pattern JSON: {"pattern": {"panels": {NAME: {"vertices", "edges", "translation",
// "rotation"}}, "stitches": [[{"panel", "edge"}, {"panel", "edge"}(, "right_wrong")], ...],
// "panel_order"}, "properties": {"curvature_coords", "units_in_meter"}}.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <map>
#include <sstream>

#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/curves.h"
#include "dresskit/pattern/pattern.h"

namespace dresskit::pattern {
namespace {
using json = nlohmann::ordered_json;  // panels keep the file's order

std::string quoted(const std::string& s) { return "'" + s + "'"; }

struct Context {
  std::string file;
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(file + ": " + where + ": " + what);
  }
};

double number(const Context& c, const json& v, const std::string& where) {
  if (!v.is_number()) c.fail(where, "must be a number, not " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) c.fail(where, "must be finite");
  return x;
}

Eigen::Vector2d pair(const Context& c, const json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 2) c.fail(where, "must be [x, y], not " + v.dump());
  return {number(c, v[0], where), number(c, v[1], where)};
}

Eigen::Vector3d triple(const Context& c, const json& panel, const char* key,
                       const std::string& where) {
  if (!panel.contains(key)) return Eigen::Vector3d::Zero();
  const json& v = panel.at(key);
  if (!v.is_array() || v.size() != 3)
    c.fail(where + " " + key, "must be [x, y, z], not " + v.dump());
  return {number(c, v[0], where + " " + key), number(c, v[1], where + " " + key),
          number(c, v[2], where + " " + key)};
}

/// A curve's control point lies at most this many chord lengths from its chord's midpoint.
constexpr double kFarthestControl = 10.0;
/// A panel's translation is at most this many times the pattern's largest panel from the origin.
constexpr double kFarthestPanel = 100.0;

/// The curvature of an edge: relative coordinates are (along the chord, along the chord turned a
/// quarter counter-clockwise) as fractions of the chord; absolute ones are panel coordinates.
void read_curvature(const Context& c, const json& curvature, bool relative, double scale,
                    const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, Edge& e,
                    const std::string& where) {
  auto control = [&](const json& v) -> Eigen::Vector2d {
    const Eigen::Vector2d q = pair(c, v, where + " curvature");
    const Eigen::Vector2d chord = p1 - p0;
    const Eigen::Vector2d at = relative ? Eigen::Vector2d(p0 + q.x() * chord + q.y() * Eigen::Vector2d(-chord.y(), chord.x()))
                                        : Eigen::Vector2d(q / scale);
    // A curve bulging out many times its chord is no garment's edge (and would be sampled into
    // thousands of points): refused before any work.
    if ((at - 0.5 * (p0 + p1)).norm() > kFarthestControl * std::max(chord.norm(), 1e-12))
      c.fail(where, "curvature control point " + v.dump() + " lies more than " + std::to_string(int(kFarthestControl)) +
                        " chord lengths from its edge");
    return at;
  };
  if (curvature.is_array()) {  // older files: one relative quadratic control point
    e.kind = CurveKind::quadratic;
    e.controls = {control(curvature)};
    return;
  }
  if (!curvature.is_object() || !curvature.contains("type") || !curvature.contains("params"))
    c.fail(where, "curvature must be {\"type\", \"params\"}, not " + curvature.dump());
  const std::string type =
      curvature.at("type").is_string() ? curvature.at("type").get<std::string>() : "";
  const json& params = curvature.at("params");
  if (!params.is_array()) c.fail(where, "curvature params must be an array");
  if (type == "quadratic" || type == "cubic") {
    const std::size_t n = type == "quadratic" ? 1 : 2;
    if (params.size() != n)
      c.fail(where, "a " + type + " curve needs " + std::to_string(n) + " control point(s)");
    e.kind = type == "quadratic" ? CurveKind::quadratic : CurveKind::cubic;
    for (const json& q : params) e.controls.push_back(control(q));
  } else if (type == "circle") {
    if (params.size() != 3) c.fail(where, "a circle needs [radius, large_arc, right]");
    e.kind = CurveKind::arc;
    e.radius = number(c, params[0], where + " circle radius") / scale;
    e.large_arc = number(c, params[1], where + " circle large_arc") != 0.0;
    e.counter_clockwise = number(c, params[2], where + " circle right") != 0.0;
    if (!(e.radius > 0.0)) c.fail(where, "circle radius must be positive");
  } else {
    c.fail(where, "curvature type " + quoted(type) + " is not quadratic, cubic or circle");
  }
}

Panel read_panel(const Context& c, const std::string& name, const json& j, bool relative,
                 double scale) {
  const std::string where = "panel " + quoted(name);
  if (!j.is_object()) c.fail(where, "must be an object");
  Panel p;
  p.name = name;
  if (!j.contains("vertices") || !j.at("vertices").is_array() || j.at("vertices").size() < 2)
    c.fail(where, "needs \"vertices\": at least two [x, y]");
  const json& vs = j.at("vertices");
  p.vertices.resize(vs.size(), 2);
  for (std::size_t i = 0; i < vs.size(); ++i)
    p.vertices.row(i) = pair(c, vs[i], where + " vertex " + std::to_string(i)).transpose() / scale;
  p.translation = triple(c, j, "translation", where) / scale;
  p.euler_degrees = triple(c, j, "rotation", where);
  if (p.euler_degrees.cwiseAbs().maxCoeff() > 360.0)
    c.fail(where + " rotation", "an angle beyond a whole turn (" + std::to_string(p.euler_degrees.cwiseAbs().maxCoeff()) +
                                    "°): rotations are degrees within ±360");
  if (!j.contains("edges") || !j.at("edges").is_array() || j.at("edges").empty())
    c.fail(where, "needs \"edges\"");
  const json& es = j.at("edges");
  for (std::size_t k = 0; k < es.size(); ++k) {
    const std::string ew = where + " edge " + std::to_string(k);
    const json& ej = es[k];
    if (!ej.is_object() || !ej.contains("endpoints")) c.fail(ew, "needs \"endpoints\"");
    const json& ends = ej.at("endpoints");
    if (!ends.is_array() || ends.size() != 2 || !ends[0].is_number_integer() ||
        !ends[1].is_number_integer())
      c.fail(ew, "endpoints must be two vertex numbers, not " + ends.dump());
    Edge e;
    e.start = ends[0].get<int>();
    e.end = ends[1].get<int>();
    for (int v : {e.start, e.end})
      if (v < 0 || v >= p.vertices.rows())
        c.fail(ew, "vertex " + std::to_string(v) + " does not exist (the panel has " +
                       std::to_string(p.vertices.rows()) + ")");
    if (ej.contains("curvature"))
      read_curvature(c, ej.at("curvature"), relative, scale, p.vertices.row(e.start).transpose(),
                     p.vertices.row(e.end).transpose(), e, ew);
    if (ej.contains("label") && ej.at("label").is_string())
      e.label = ej.at("label").get<std::string>();
    p.edges.push_back(e);
  }
  return p;
}

/// Whether segments ab and cd cross or touch (exactly, by orientation signs).
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  auto orient = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    const double v = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
    return (v > 0) - (v < 0);
  };
  auto on = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q,
               const Eigen::Vector2d& r) {  // r within box pq
    return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  // Boxes first: pieces of one straight edge, nearly but not exactly collinear in floating point,
  // must not count as meeting.
  if (std::max(a.x(), b.x()) < std::min(c.x(), d.x()) ||
      std::max(c.x(), d.x()) < std::min(a.x(), b.x()) ||
      std::max(a.y(), b.y()) < std::min(c.y(), d.y()) ||
      std::max(c.y(), d.y()) < std::min(a.y(), b.y()))
    return false;
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) ||
         (o4 == 0 && on(c, d, b));
}

void check_panel(const Context& c, const Panel& p, const ReadOptions& options) {
  const std::string where = "panel " + quoted(p.name);
  const int n = int(p.edges.size());
  for (int k = 0; k < n; ++k) {
    const Edge& e = p.edges[k];
    const Edge& next = p.edges[(k + 1) % n];
    if (e.end != next.start)
      c.fail(where + " edge " + std::to_string(k),
             "ends at vertex " + std::to_string(e.end) + " but edge " +
                 std::to_string((k + 1) % n) + " starts at vertex " + std::to_string(next.start) +
                 ": the outline is not a closed loop");
    const double length = edge_length(p, k);
    if (!(length >= options.min_edge_length))
      c.fail(where + " edge " + std::to_string(k),
             "has zero length (" + std::to_string(length) + " m)");
  }
  // Self-intersection: the outline sampled finely, segments of edges compared pairwise (neighbours
  // along the outline share a point and are skipped).
  double perimeter = 0.0;
  for (int k = 0; k < n; ++k) perimeter += edge_length(p, k);
  Eigen::VectorXi owner;
  const Eigen::MatrixX2d s = sample_outline(p, std::max(perimeter / 2000.0, 1e-4), &owner);
  const int m = int(s.rows());
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d a = s.row(i).transpose(), b = s.row((i + 1) % m).transpose();
    for (int j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;
      const Eigen::Vector2d q0 = s.row(j).transpose(), q1 = s.row((j + 1) % m).transpose();
      if (segments_meet(a, b, q0, q1))
        c.fail(where, "the outline crosses itself: edge " + std::to_string(owner[i]) +
                          " meets edge " + std::to_string(owner[j]));
    }
  }
}

StitchSide read_side(const Context& c, const Pattern& pattern, const json& j,
                     const std::string& where) {
  if (!j.is_object() || !j.contains("panel") || !j.contains("edge") || !j.at("panel").is_string() ||
      !j.at("edge").is_number_integer())
    c.fail(where, "each side must be {\"panel\": NAME, \"edge\": NUMBER}, not " + j.dump());
  const std::string name = j.at("panel").get<std::string>();
  StitchSide s;
  s.panel = pattern.panel_index(name);
  if (s.panel < 0) c.fail(where, "panel " + quoted(name) + " does not exist");
  s.edge = j.at("edge").get<int>();
  const int edges = int(pattern.panels[s.panel].edges.size());
  if (s.edge < 0 || s.edge >= edges)
    c.fail(where, "panel " + quoted(name) + " has no edge " + std::to_string(s.edge) + " (it has " +
                      std::to_string(edges) + ")");
  return s;
}

}  // namespace

Eigen::Matrix3d Panel::rotation() const {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  // Fixed-axis x, y, z rotations (GarmentCode: scipy's from_euler('xyz', degrees=True)).
  return (Eigen::AngleAxisd(euler_degrees.z() * deg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(euler_degrees.y() * deg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(euler_degrees.x() * deg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d Panel::place(const Eigen::Vector2d& p) const {
  return rotation() * Eigen::Vector3d(p.x(), p.y(), 0.0) + translation;
}

int Pattern::panel_index(const std::string& n) const {
  for (std::size_t i = 0; i < panels.size(); ++i)
    if (panels[i].name == n) return int(i);
  return -1;
}

std::string Pattern::edge_name(int panel, int edge) const {
  return "panel " + quoted(panels[panel].name) + " edge " + std::to_string(edge);
}

std::string pattern_name(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0)
    name.resize(name.size() - 5);
  return name;
}

bool is_pattern_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return ext == ".json";
}

Pattern parse_pattern(const std::string& text, const std::string& file,
                      const ReadOptions& options) {
  const Context c{file};
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // a syntax error, or a number beyond a double (1e999)
    throw InputError(file + ": not valid JSON: " + e.what());
  }
  if (!root.is_object() || !root.contains("pattern") || !root.at("pattern").is_object())
    c.fail("pattern", "missing: not a GarmentCode pattern file");
  const json& pj = root.at("pattern");
  if (!root.contains("properties") || !root.at("properties").is_object() ||
      !root.at("properties").contains("units_in_meter"))
    c.fail("properties.units_in_meter", "missing: the file does not say its units");
  const json& props = root.at("properties");
  Pattern pattern;
  pattern.file = file;
  pattern.name = pattern_name(file);
  pattern.units_in_meter = number(c, props.at("units_in_meter"), "properties.units_in_meter");
  if (!(pattern.units_in_meter > 0.0)) c.fail("properties.units_in_meter", "must be positive");
  bool relative = true;
  if (props.contains("curvature_coords")) {
    const json& cc = props.at("curvature_coords");
    if (!cc.is_string() ||
        (cc.get<std::string>() != "relative" && cc.get<std::string>() != "absolute"))
      c.fail("properties.curvature_coords",
             "must be \"relative\" or \"absolute\", not " + cc.dump());
    relative = cc.get<std::string>() == "relative";
  }
  if (!pj.contains("panels") || !pj.at("panels").is_object() || pj.at("panels").empty())
    c.fail("pattern.panels", "missing or empty");
  const json& panels = pj.at("panels");
  std::vector<std::string> order;
  if (pj.contains("panel_order") && pj.at("panel_order").is_array()) {
    for (const json& n : pj.at("panel_order")) {
      if (!n.is_string() || !panels.contains(n.get<std::string>()))
        c.fail("pattern.panel_order", "names panel " + n.dump() + ", which does not exist");
      order.push_back(n.get<std::string>());
    }
  }
  for (auto it = panels.begin(); it != panels.end(); ++it)
    if (std::find(order.begin(), order.end(), it.key()) == order.end()) order.push_back(it.key());
  for (const std::string& name : order) {
    pattern.panels.push_back(
        read_panel(c, name, panels.at(name), relative, pattern.units_in_meter));
    check_panel(c, pattern.panels.back(), options);
  }
  // Panels are placed around one body: one thousands of panel sizes away is a typing error, and
  // sewing it to the others would run for ever.
  double largest = 0.0;
  for (const Panel& panel : pattern.panels)
    largest = std::max(largest, (panel.vertices.colwise().maxCoeff() - panel.vertices.colwise().minCoeff()).norm());
  for (const Panel& panel : pattern.panels)
    if (panel.translation.norm() > kFarthestPanel * largest)
      c.fail("panel " + quoted(panel.name) + " translation",
             "lies " + std::to_string(panel.translation.norm()) + " m from the origin, more than " +
                 std::to_string(int(kFarthestPanel)) + " times the largest panel's size (" + std::to_string(largest) + " m)");
  if (pj.contains("stitches")) {
    const json& ss = pj.at("stitches");
    if (!ss.is_array()) c.fail("pattern.stitches", "must be an array");
    // The stitch that first sews each edge (panel, edge), by index in the file.
    std::map<std::pair<int, int>, std::size_t> sewn_by;
    for (std::size_t i = 0; i < ss.size(); ++i) {
      const std::string where = "stitch " + std::to_string(i);
      const json& s = ss[i];
      if (!s.is_array() || s.size() < 2 || s.size() > 3)
        c.fail(where, "must be [SIDE, SIDE], not " + s.dump());
      Stitch st;
      st.a = read_side(c, pattern, s[0], where);
      st.b = read_side(c, pattern, s[1], where);
      if (s.size() == 3) {
        if (!s[2].is_string() || s[2].get<std::string>() != "right_wrong")
          c.fail(where, "third member must be \"right_wrong\", not " + s[2].dump());
        st.same_direction = true;
      }
      if (st.a.panel == st.b.panel && st.a.edge == st.b.edge)
        c.fail(where, "sews an edge to itself");
      // A stitch listed twice, or an edge sewn by two stitches (a seam of three layers), is sewn
      // as given (stitches keep the file's numbers), and said.
      const auto first_a = sewn_by.find({st.a.panel, st.a.edge}), first_b = sewn_by.find({st.b.panel, st.b.edge});
      if (first_a != sewn_by.end() && first_b != sewn_by.end() && first_a->second == first_b->second) {
        pattern.warnings.push_back(file + ": " + where + " repeats stitch " + std::to_string(first_a->second) +
                                   " (" + pattern.edge_name(st.a.panel, st.a.edge) + " to " +
                                   pattern.edge_name(st.b.panel, st.b.edge) + ")");
      } else {
        for (const auto& [side, first] : {std::pair{st.a, first_a}, std::pair{st.b, first_b}})
          if (first != sewn_by.end())
            pattern.warnings.push_back(file + ": " + where + ": " + pattern.edge_name(side.panel, side.edge) +
                                       " is also sewn by stitch " + std::to_string(first->second) +
                                       " (a seam of three layers)");
      }
      sewn_by.emplace(std::pair{st.a.panel, st.a.edge}, i);
      sewn_by.emplace(std::pair{st.b.panel, st.b.edge}, i);
      const double la = edge_length(pattern.panels[st.a.panel], st.a.edge);
      const double lb = edge_length(pattern.panels[st.b.panel], st.b.edge);
      if (std::max(la, lb) > options.max_length_ratio * std::min(la, lb)) {
        std::ostringstream w;
        w.precision(4);
        w << file << ": " << where << ": " << pattern.edge_name(st.a.panel, st.a.edge) << " ("
          << la * 100.0 << " cm) and " << pattern.edge_name(st.b.panel, st.b.edge) << " ("
          << lb * 100.0 << " cm) differ in length by more than " << options.max_length_ratio
          << " times";
        pattern.warnings.push_back(w.str());
      }
      pattern.stitches.push_back(st);
    }
  }
  return pattern;
}

Pattern read_pattern(const std::string& path, const ReadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot be read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_pattern(buffer.str(), path, options);
}

}  // namespace dresskit::pattern
