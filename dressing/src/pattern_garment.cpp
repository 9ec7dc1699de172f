#include "pattern_garment.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/cut.h"
#include "dresskit/pattern/pattern.h"
#include "dresskit/pattern/sew.h"

using namespace dresskit::mesh;
using namespace dresskit::pattern;

namespace dresskit::dressing::detail {

bool is_pattern_garment(const GarmentFile& g) {
  return !g.file.mesh && pattern::is_pattern_file(g.file.path);
}

void sew_pattern_garment(const GarmentFile& g, const TriangleMesh& body,
                         const std::shared_ptr<const cloth::MeshDistance>& body_distance,
                         const DressOptions& options, DressedGarment& d) {
  const pattern::Pattern p = pattern::read_pattern(g.file.path);
  pattern::CutOptions cut_options;
  cut_options.edge_length = options.pattern_edge_length;
  const pattern::CutPattern cut = pattern::cut_pattern(p, cut_options);
  pattern::SewOptions sew_options;
  sew_options.fabric = d.fabric;
  sew_options.tolerance = options.seam_tolerance;
  const pattern::SewResult sewn = [&] {
    try {
      return pattern::sew_pattern(p, cut, body, sew_options, body_distance);
    } catch (const InputError& e) {
      throw InputError(g.file.path + ": " + e.what());
    }
  }();
  SewnPattern& s = d.pattern;
  d.from_pattern = true;
  d.mesh = sewn.garment;
  d.mesh.labels.resize(0);  // panels are not body parts: the garment is segmented like a mesh
  d.mesh.label_names.clear();
  d.file.load = LoadOptions{};  // the garment is made in metres, +Y up; its outputs are too
  s.panels.clear();
  for (const pattern::Panel& panel : p.panels) s.panels.push_back(panel.name);
  s.panel_area.assign(cut.triangle_area.data(),
                      cut.triangle_area.data() + cut.triangle_area.size());
  s.panel_faces.resize(cut.faces.rows(), 3);
  for (Eigen::Index f = 0; f < cut.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) s.panel_faces(f, k) = sewn.welded_vertex[cut.faces(f, k)];
  s.panel_of_face = cut.panel_of_face;
  // Flat lengths of the triangles' edges, keyed by their welded ends.
  std::map<std::array<int, 2>, std::pair<double, int>> flat;
  for (Eigen::Index f = 0; f < cut.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = cut.faces(f, c), b = cut.faces(f, (c + 1) % 3);
      const int u = sewn.welded_vertex[a], v = sewn.welded_vertex[b];
      if (u == v) continue;
      auto& [sum, count] = flat[{std::min(u, v), std::max(u, v)}];
      sum += (cut.flat.row(a) - cut.flat.row(b)).norm();
      ++count;
    }
  s.flat_edges.clear();
  s.flat_edge_length.clear();
  for (const auto& [edge, length] : flat) {
    s.flat_edges.push_back(edge);
    s.flat_edge_length.push_back(length.first / length.second);
  }
  s.stitches = static_cast<int>(p.stitches.size());
  s.stitch_pairs = sewn.stitch_pairs;
  s.sewn_pairs = sewn.closed_pairs;
  s.sew_method = sewn.method;
  s.max_gap = sewn.max_gap;
  s.closed = sewn.closed;
  s.unwelded = sewn.unwelded;
  s.moved_by = sewn.moved_by;
  s.panels_moved_out = sewn.panels_moved_out;
  s.triangles = static_cast<int>(sewn.garment.F.rows());
  s.cut_seconds = cut.seconds;
  s.sew_seconds = sewn.seconds;
  s.sew_simulated = sewn.simulated_seconds;
  s.warnings = p.warnings;
  if (!sewn.closed) {
    // The stitch furthest from closed, named: its pairs that were sewn are welded, the rest stay
    // open.
    const auto widest =
        std::max_element(sewn.stitch_gap.begin(), sewn.stitch_gap.end()) - sewn.stitch_gap.begin();
    const pattern::Stitch& st = p.stitches[static_cast<std::size_t>(widest)];
    const double gap = sewn.stitch_gap[static_cast<std::size_t>(widest)];
    if (gap > options.max_open_seam)
      throw InputError(g.file.path + ": stitch " + std::to_string(widest) + " (" +
                       p.edge_name(st.a.panel, st.a.edge) + " to " + p.edge_name(st.b.panel, st.b.edge) +
                       ") is still " + std::to_string(int(std::lround(1e3 * gap))) + " mm open after sewing (" +
                       sewn.stopped + "): the pattern does not sew on this body" +
                       (sewn.moved_by.isZero() ? std::string("; is it placed for another?")
                                               : std::string(" (carried from the body it is placed for)")));
    s.warnings.push_back(
        g.file.path + ": stitch " + std::to_string(widest) + " (" +
        p.edge_name(st.a.panel, st.a.edge) + " to " + p.edge_name(st.b.panel, st.b.edge) +
        ") is still " + std::to_string(1e3 * sewn.stitch_gap[static_cast<std::size_t>(widest)]) +
        " mm open after " + std::to_string(sewn.simulated_seconds) + " s of sewing; " +
        std::to_string(sewn.stitch_pairs - sewn.closed_pairs) + " of " +
        std::to_string(sewn.stitch_pairs) + " stitch pairs stay unwelded");
  }
}

void measure_dressed_panels(DressedGarment& d) {
  SewnPattern& s = d.pattern;
  s.panel_area_dressed.clear();
  if (!d.from_pattern || d.dressed.rows() != d.mesh.num_vertices() ||
      (s.panel_faces.size() > 0 && s.panel_faces.maxCoeff() >= d.dressed.rows()))
    return;
  s.panel_area_dressed.assign(s.panels.size(), 0.0);
  for (Eigen::Index f = 0; f < s.panel_faces.rows(); ++f) {
    const Eigen::Vector3d a = d.dressed.row(s.panel_faces(f, 0)),
                          b = d.dressed.row(s.panel_faces(f, 1)),
                          c = d.dressed.row(s.panel_faces(f, 2));
    s.panel_area_dressed[static_cast<std::size_t>(s.panel_of_face[f])] +=
        0.5 * (b - a).cross(c - a).norm();
  }
}

}  // namespace dresskit::dressing::detail
