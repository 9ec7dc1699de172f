// Placement: each garment not already on the body is fitted onto it part by part. Garments to
// place are placed together, as one outfit whose pieces are worn in layer order, so that their
// parts share one global fit and outer pieces are pushed out of inner ones. A placed garment that
// crosses itself more often than as authored is untangled; one stretched past what the settle can
// take is refused.
#include <algorithm>

#include "../garments.h"
#include "../measures.h"
#include "../outfit.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/names.h"

namespace dresskit::dressing::detail::stages {

using namespace dresskit::mesh;

namespace {

/// Parts of the same name from several garments keep apart as name_2, name_3, ... (each garment's
/// body is placed on its own), as segmentation names the pieces of one garment.
void distinct_label_names(TriangleMesh& m) {
  for (std::size_t l = 1; l < m.label_names.size(); ++l) {
    const std::string name = m.label_names[l];
    for (int n = 2; std::count(m.label_names.begin(), m.label_names.begin() + static_cast<long>(l), m.label_names[l]); ++n)
      m.label_names[l] = name + "_" + std::to_string(n);
  }
}

/// Places the garments `to_place` together (as one outfit, layers as ordered); throws InputError
/// naming them when the fit shrank or blew them up, or left them off the body.
std::string place_together(Outfit& outfit, const std::vector<std::size_t>& to_place, const DressOptions& options) {
  std::vector<DressedGarment>& garments = outfit.result.garments;
  TriangleMesh together;
  std::vector<Eigen::Index> first;
  std::vector<int> layer_of;
  std::string names;
  for (std::size_t k : to_place) {
    const DressedGarment& g = garments[k];
    first.push_back(together.V.rows());
    append_mesh(together, g.mesh, "");
    layer_of.insert(layer_of.end(), static_cast<std::size_t>(g.mesh.num_vertices()), static_cast<int>(k));
    names += (names.empty() ? "" : ", ") + g.file.path;
  }
  first.push_back(together.V.rows());
  distinct_label_names(together);
  alignment::PlacementOptions o = options.placement;
  o.vertex_layers = Eigen::Map<const Eigen::VectorXi>(layer_of.data(), static_cast<Eigen::Index>(layer_of.size()));
  const alignment::PlacementResult p = alignment::place_garment(together, outfit.result.body, o);
  // The quality gate: a placement that shrank or blew the garments up, or left them off the body,
  // is refused rather than passed on.
  const double scale = p.global_scale;
  const SurfaceFit after = surface_fit(p.V, outfit.inside());
  if (!(scale >= 0.4 && scale <= 2.5) || after.mean_distance > 0.1 * outfit.body_height)
    throw InputError(names + ": the placement does not fit the garment on the body (scale " + number(scale) +
                     ", mean distance to the body " + number(after.mean_distance) +
                     " m): check its units and that it is a garment for a person");
  for (std::size_t i = 0; i < to_place.size(); ++i) {
    DressedGarment& g = garments[to_place[i]];
    g.placement = p;
    g.placed_by_placement = true;
    g.placed = p.V.middleRows(first[i], first[i + 1] - first[i]);
  }
  return std::string(to_place.size() > 1 ? "placed together" : "placed") + " (scale " + number(scale) + ", " +
         std::to_string(p.matching.matches.size()) + " parts matched, " + p.global_method + ")";
}

}  // namespace

StageReport placement(Outfit& outfit, const DressOptions& options) {
  std::vector<DressedGarment>& garments = outfit.result.garments;
  std::string report;
  const auto say = [&](const std::string& text) { report += (report.empty() ? "" : "; ") + text; };
  std::vector<std::size_t> to_place;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    DressedGarment& g = garments[k];
    g.crossings_authored = cloth::count_intersections(g.mesh.V, g.mesh.F);
    const SurfaceFit before = surface_fit(g.mesh.V, outfit.inside());
    const std::string as_given = " (mean distance " + number(100.0 * before.mean_distance / outfit.body_height, 2) +
                                 " % of its height, " + counted(before.inside, "vertex", "vertices") + " inside)";
    if (on_body(before, g.mesh.num_vertices(), outfit.body_height, options)) {
      g.placed = g.mesh.V;
      say(g.name + " already on the body" + as_given);
      continue;
    }
    // A sewn pattern that did not end on this body is not a garment placement can rescue: its
    // panels' places are for another body.
    if (g.from_pattern)
      throw InputError(g.file.path + ": sewn around this body, the garment is not on it" + as_given +
                       ": the pattern is placed for another body");
    say(g.name + " not on the body as given" + as_given);
    to_place.push_back(k);
  }
  if (!to_place.empty()) say(place_together(outfit, to_place, options));
  for (std::size_t k = 0; k < garments.size(); ++k) {
    DressedGarment& g = garments[k];
    g.crossings_placed = g.crossings_fitted = cloth::count_intersections(g.placed, g.mesh.F);
    if (g.placed_by_placement && g.crossings_placed > g.crossings_authored) {
      untangle(garments, k, *outfit.body_distance(), options.placement.clearance);
      untangle_along_path(garments, k);
      say(g.name + ": crossing itself " + counted(g.crossings_fitted, "time", "times") + " as fitted, " +
          std::to_string(g.crossings_placed) + " after untangling (" + std::to_string(g.crossings_authored) +
          " as authored)");
    }
    g.inside_placed = surface_fit(g.placed, outfit.inside()).inside;
    // A garment placed with springs stretched beyond the simulator's blow-up strain cannot be
    // settled (its first length-limit pass pulls particles through the body): refused.
    if (!g.placed_by_placement) continue;
    const std::vector<double> strain = structural_strains(garment_cloth(g, outfit.fabrics[k]), g.placed);
    const double blow_up = cloth::SimulationOptions().blow_up_strain;
    if (!strain.empty() && strain.back() > blow_up)
      throw InputError(g.file.path + ": the placement stretches it by up to " + number(100.0 * strain.back(), 3) +
                       " % (more than " + number(100.0 * blow_up, 3) + " %): the garment does not fit this body as placed");
  }
  return {!to_place.empty(), report};
}

}  // namespace dresskit::dressing::detail::stages
