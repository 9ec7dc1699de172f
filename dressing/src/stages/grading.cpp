// Grading: each garment worn over another moved out over it by the separation, so that the settle
// starts with the layers in order (its cloth–cloth collisions keep them so, but cannot undo a
// crossing they start with).
#include "../garments.h"
#include "../measures.h"
#include "../outfit.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/mesh/names.h"

namespace dresskit::dressing::detail::stages {

StageReport grading(Outfit& outfit, const DressOptions&) {
  std::vector<DressedGarment>& garments = outfit.result.garments;
  if (garments.size() < 2) return left_out("one garment: no layers to grade");
  const int before = crossings_between(garments, &DressedGarment::placed);
  const std::vector<Grading> graded = grade_layers(garments, outfit.body_distance(), outfit.separation);
  std::string report;
  for (std::size_t k = 0; k < graded.size(); ++k) {
    if (graded[k].vertices == 0) continue;
    DressedGarment& g = garments[k];
    g.crossings_placed = cloth::count_intersections(g.placed, g.mesh.F);
    report += (report.empty() ? "" : "; ") + g.name + " moved out over " + garments[k - 1].name + ": " +
              counted(graded[k].vertices, "vertex", "vertices") + ", by up to " + number(1e3 * graded[k].largest, 3) +
              " mm";
    // Moved out at an armpit or the crotch, where the body's normals of two parts face each other,
    // a placed garment's sleeve and side (or two legs) cross: it is moved onto its graded positions
    // from an uncrossed shape, its parts held apart on the way (as after placement). A garment worn
    // as authored settles its few new crossings out better from where grading left it.
    if (g.placed_by_placement && g.crossings_placed > g.crossings_authored) {
      const int graded_crossings = g.crossings_placed;
      untangle_along_path(garments, k);
      report += ", crossing itself " + counted(graded_crossings, "time", "times") + ", " +
                std::to_string(g.crossings_placed) + " after untangling (" + std::to_string(g.crossings_authored) +
                " as authored)";
    }
    g.inside_placed = surface_fit(g.placed, outfit.inside()).inside;
  }
  if (report.empty()) return left_out("every garment already lies over the one beneath it");
  const int after = crossings_between(garments, &DressedGarment::placed);
  return ran(report + "; the garments cross each other " + counted(after, "time", "times") + " (" +
             std::to_string(before) + " before)");
}

}  // namespace dresskit::dressing::detail::stages
