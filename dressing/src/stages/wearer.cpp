// Wearer: for each garment mesh, the body fitted into it part by part — where the garment's own
// wearer stood, at what size and in what pose — and the garment carried from there onto the body
// (alignment/wearer.h). A garment mesh without part labels takes the body part each vertex lies
// over (body, sleeves, legs). Sewing patterns are sewn around the body and need no wearer.
#include <algorithm>

#include "../measures.h"
#include "../outfit.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/names.h"
#include "dresskit/mesh/topology.h"

namespace dresskit::dressing::detail::stages {

namespace {

std::vector<DressPart> parts_of(const mesh::TriangleMesh& m) {
  std::vector<DressPart> parts(m.label_names.size());
  for (std::size_t k = 0; k < parts.size(); ++k) parts[k].name = m.label_names[k];
  for (Eigen::Index i = 0; i < m.labels.size(); ++i)
    if (m.labels(i) >= 0) ++parts[static_cast<std::size_t>(m.labels(i))].vertices;
  return parts;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto at = v.begin() + static_cast<long>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), at, v.end());
  return *at;
}

/// A garment has an opening for a body to pass through: a mesh whose largest piece is closed and
/// of genus 0 (a ball, a body) is not one. (A garment modelled with thickness as a closed shell
/// has handles where the body passes.)
void refuse_what_is_no_garment(const DressedGarment& g) {
  std::vector<mesh::TriangleMesh> pieces = mesh::split_components(g.mesh);
  if (pieces.empty()) return;
  const auto largest = std::max_element(pieces.begin(), pieces.end(), [](const mesh::TriangleMesh& a, const mesh::TriangleMesh& b) {
    return a.num_faces() < b.num_faces();
  });
  const mesh::TopologyReport t = mesh::analyse_topology(*largest);
  if (t.closed && t.euler_characteristic == 2)
    throw InputError(g.file.path + ": its largest piece (" + counted(t.num_faces, "face", "faces") +
                     ") is closed, with no opening for a body to pass through: not a garment for a person");
}

}  // namespace

StageReport wearer(Outfit& outfit, const DressOptions& options) {
  std::vector<DressedGarment>& garments = outfit.result.garments;
  outfit.carried.assign(garments.size(), std::nullopt);
  if (std::all_of(garments.begin(), garments.end(), [](const DressedGarment& g) { return g.from_pattern; }))
    return left_out("every garment is a sewing pattern, sewn around the body");
  const alignment::BodyRig rig = alignment::rig_body(outfit.result.body, options.rig);
  std::string report;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    DressedGarment& g = garments[k];
    if (g.from_pattern) continue;
    refuse_what_is_no_garment(g);
    const alignment::WearerFit fit = [&] {
      try {
        return alignment::fit_wearer(rig, outfit.result.body, g.mesh.V, options.wearer);
      } catch (const InputError& e) {  // "garment: too few points …", named by its file
        const std::string what = e.what();
        throw InputError(g.file.path + what.substr(what.find(':')));
      }
    }();
    // A wearer at the bounds of the sizes tried: the garment is not for a person of this size.
    const alignment::WearerFitOptions& o = options.wearer;
    if (fit.scale <= 1.001 * o.smallest_scale || fit.scale >= 0.999 * o.largest_scale)
      throw InputError(g.file.path + ": the garment fits a wearer " +
                       std::string(fit.scale < 1.0 ? "at most " : "at least ") + number(fit.scale) +
                       " times this body's size (it fits " + number(o.smallest_scale) + "–" + number(o.largest_scale) +
                       "): it is not a garment for a person of this size");
    alignment::CarriedGarment carried = alignment::carry_garment(rig, fit, g.mesh, options.carry);
    // How far carrying moves each of the garment's parts (as the wearer's body parts name them):
    // the 95th percentile of its vertices' moves, the largest over the parts.
    std::vector<std::vector<double>> moves(carried.label_names.size());
    for (Eigen::Index v = 0; v < g.mesh.V.rows(); ++v)
      moves[static_cast<std::size_t>(carried.labels(v))].push_back((carried.V.row(v) - g.mesh.V.row(v)).norm());
    for (const std::vector<double>& part : moves) g.carry_move = std::max(g.carry_move, percentile(part, 0.95));
    if (g.parts.empty()) {
      g.mesh.labels = carried.labels;
      g.mesh.label_names = carried.label_names;
      g.parts = parts_of(g.mesh);
    }
    report += (report.empty() ? "" : "; ") + g.name + ": its wearer " + number(fit.scale) + " times the body's size, " +
              "limbs turned by up to " + number(alignment::largest_turn_degrees(fit), 2) + "°, the garment " +
              number(1e3 * alignment::rms_from_ease(fit), 2) +
              " mm RMS from an even ease (" + fit.start + ", " + counted(fit.iterations, "iteration", "iterations") +
              "); carrying it moves 95 % of the vertices of each of its parts by at most " + number(1e3 * g.carry_move) + " mm";
    g.wearer = fit;
    outfit.carried[k] = std::move(carried);
  }
  return ran(report);
}

}  // namespace dresskit::dressing::detail::stages
