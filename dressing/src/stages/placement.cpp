// Placement: each garment mesh not already on the body is carried from where its wearer stood
// (wearer) onto the body, then pushed out of the body with its edges' stretch limited; garments to
// place are pushed together, as one outfit whose pieces are worn in layer order, so that outer
// pieces are pushed out of inner ones. A placed garment that crosses itself more often than as
// authored is untangled; one stretched past what the settle can take is refused. A sewn pattern is
// on the body it was sewn around, or refused.
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

/// A garment is refused as too small when more than this share of its carried edges would have to
/// grow by more than kLargestLoosening to lie within the length limit (scale_to_fit).
constexpr double kStretchedShare = 0.02;
/// The most an edge of the rest shape grows to fit the body (loosened_rest).
constexpr double kLargestLoosening = 1.3;

/// The growth of the rest shape that all but kStretchedShare of the placed garment's edges need to
/// lie within (1 + strain_limit) of their rest lengths.
double scale_to_fit(const TriangleMesh& rest, const Eigen::MatrixX3d& placed, double strain_limit) {
  std::vector<double> ratio;
  for (int f = 0; f < rest.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = rest.F(f, k), b = rest.F(f, (k + 1) % 3);
      if (a > b) continue;  // each interior edge once (a boundary edge seen one way may be missed)
      const double length = (rest.V.row(a) - rest.V.row(b)).norm();
      if (length > 0.0) ratio.push_back((placed.row(a) - placed.row(b)).norm() / length);
    }
  if (ratio.empty()) return 0.0;
  const auto at = ratio.begin() + static_cast<long>((1.0 - kStretchedShare) * static_cast<double>(ratio.size() - 1));
  std::nth_element(ratio.begin(), at, ratio.end());
  return *at / (1.0 + strain_limit);
}

/// Pushes the garments `to_place`, carried from their wearers, out of the body together (as one
/// outfit, layers as ordered); throws InputError naming them when they are left off the body.
std::string place_together(Outfit& outfit, const std::vector<std::size_t>& to_place, const DressOptions& options) {
  std::vector<DressedGarment>& garments = outfit.result.garments;
  TriangleMesh together;  // their rest shapes at their wearers' sizes
  alignment::PlacementResult p;
  p.V.resize(0, 3);
  std::vector<Eigen::Index> first;
  std::vector<int> layer_of;
  std::string names;
  for (std::size_t k : to_place) {
    const DressedGarment& g = garments[k];
    first.push_back(together.V.rows());
    TriangleMesh rest = g.mesh;
    rest.V /= g.wearer->scale;
    append_mesh(together, rest, "");
    p.V.conservativeResize(p.V.rows() + rest.V.rows(), 3);
    p.V.bottomRows(rest.V.rows()) = outfit.carried[k]->V;
    layer_of.insert(layer_of.end(), static_cast<std::size_t>(g.mesh.num_vertices()), static_cast<int>(k));
    names += (names.empty() ? "" : ", ") + g.file.path;
  }
  first.push_back(together.V.rows());
  alignment::PlacementOptions o = options.placement;
  o.vertex_layers = Eigen::Map<const Eigen::VectorXi>(layer_of.data(), static_cast<Eigen::Index>(layer_of.size()));
  o.pieces_of_a_layer_apart = false;  // a garment's own pieces are carried as authored
  const TriangleMesh& body = outfit.result.body;
  alignment::push_out_of_body(together, body, vertex_normals(body.V, body.F), o, 1.0, 1.0, p);
  // The quality gate: garments left off the body are refused rather than passed on.
  const SurfaceFit after = surface_fit(p.V, outfit.inside());
  if (after.mean_distance > 0.1 * outfit.body_height)
    throw InputError(names + ": the placement does not fit the garment on the body (mean distance to the body " +
                     number(after.mean_distance) + " m): check its units and that it is a garment for a person");
  std::string report;
  for (std::size_t i = 0; i < to_place.size(); ++i) {
    DressedGarment& g = garments[to_place[i]];
    const alignment::WearerFit& fit = *g.wearer;
    g.placement = p;
    g.placement.V = p.V.middleRows(first[i], first[i + 1] - first[i]);
    g.placement.global = fit.global.inverse();
    g.placement.global_method = "carried from its wearer (" + fit.start + ")";
    g.placement.seconds = fit.seconds;
    g.placed_by_placement = true;
    g.placed = g.placement.V;
    // Its rest shape at its wearer's size, loosened where the body is larger than its wearer there
    // (a man's shirt on a woman's hips): a garment the body stretches beyond its length limit
    // cannot settle; one loosened there drapes in, and keeps its lengths elsewhere.
    const double strain_limit = cloth::SimulationOptions().strain_limit;
    const double loose = scale_to_fit(g.mesh, g.placed, strain_limit);
    if (loose > kLargestLoosening / fit.scale)
      throw InputError(g.file.path + ": the garment is too small for this body: carried onto it, " +
                       number(100.0 * kStretchedShare) + " % of its edges would have to grow by " +
                       number(loose * fit.scale, 3) + " times or more (at most " + number(kLargestLoosening) +
                       "): not a garment for a person of this size");
    g.placement.global_scale = 1.0 / fit.scale;
    int grown = 0;
    g.rest = loosened_rest(g.mesh.V * g.placement.global_scale, g.mesh.F, g.placed, strain_limit, kLargestLoosening, &grown);
    report += (report.empty() ? "" : ", ") + g.name + " at its wearer's scale " + number(g.placement.global_scale, 4) +
              (grown > 0 ? " (loosened where the body is larger: " + counted(grown, "edge", "edges") + " grown)" : "");
  }
  return std::string(to_place.size() > 1 ? "placed together: " : "placed: ") + report + ", " +
         counted(p.pushed_out, "vertex", "vertices") + " pushed out of the body";
}

/// A garment placed with springs stretched beyond the simulator's blow-up strain cannot be settled
/// (its first length-limit pass pulls particles through the body). Untangling can stretch it so:
/// its stretch is limited again, as pushing out ends, up to ten times as long; one still stretched
/// so is refused.
void limit_to_blow_up(Outfit& outfit, std::size_t k, const DressOptions& options) {
  DressedGarment& g = outfit.result.garments[k];
  const double blow_up = cloth::SimulationOptions().blow_up_strain;
  const cloth::ClothModel cloth = garment_cloth(g, outfit.fabrics[k]);
  double stretch = cloth::blow_up_stretch(cloth, g.placed);
  int round = 0;
  for (; round < 10 && stretch > blow_up; ++round) {
    alignment::limit_stretch(rest_shape(g), 1.0, options.placement, g.placed);
    stretch = cloth::blow_up_stretch(cloth, g.placed);
  }
  if (round > 0) g.crossings_placed = cloth::count_intersections(g.placed, g.mesh.F);
  if (stretch > blow_up)
    throw InputError(g.file.path + ": the placement stretches it by up to " + number(100.0 * stretch, 3) +
                     " % (more than " + number(100.0 * blow_up, 3) + " %): the garment does not fit this body as placed");
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
    if (g.from_pattern) {
      const SurfaceFit before = surface_fit(g.mesh.V, outfit.inside());
      const std::string as_given = " (mean distance " + number(100.0 * before.mean_distance / outfit.body_height, 2) +
                                   " % of its height, " + counted(before.inside, "vertex", "vertices") + " inside)";
      // A sewn pattern that did not end on this body is not a garment placement can rescue: its
      // panels' places are for another body.
      if (!on_body(before, g.mesh.num_vertices(), outfit.body_height, options))
        throw InputError(g.file.path + ": sewn around this body, the garment is not on it" + as_given +
                         ": the pattern is placed for another body");
      g.placed = g.mesh.V;
      say(g.name + " sewn on the body" + as_given);
      continue;
    }
    const alignment::WearerFit& fit = *g.wearer;
    const std::string moves = " (carrying it from its wearer would move 95 % of each part's vertices by at most " +
                              number(100.0 * g.carry_move / outfit.body_height, 2) +
                              " % of the body's height; it lies around the body as it is with " +
                              number(fit.cost_as_is / std::max(fit.cost, 1e-300), 3) + " times its wearer's cost)";
    if (g.carry_move <= options.fit_move * outfit.body_height || fit.cost_as_is <= options.fit_cost * fit.cost) {
      g.placed = g.mesh.V;
      say(g.name + " already on the body" + moves);
      continue;
    }
    say(g.name + " not on the body as given" + moves);
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
    if (g.placed_by_placement) limit_to_blow_up(outfit, k, options);
    g.inside_placed = surface_fit(g.placed, outfit.inside()).inside;
  }
  return {!to_place.empty(), report};
}

}  // namespace dresskit::dressing::detail::stages
