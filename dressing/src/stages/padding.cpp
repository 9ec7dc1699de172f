// Padding: padded garments become double layers over the settled outfit, their padding grown to
// the thickness heat conduction gives (../padding.h).
#include <algorithm>

#include "../measures.h"
#include "../outfit.h"
#include "../padding.h"
#include "dresskit/mesh/names.h"

namespace dresskit::dressing::detail::stages {

StageReport padding(Outfit& outfit, const DressOptions& options) {
  DressResult& result = outfit.result;
  std::vector<DressedGarment>& garments = result.garments;
  if (std::none_of(garments.begin(), garments.end(), [](const DressedGarment& g) { return g.padded; }))
    return left_out("no padded garment");
  if (!result.settled || !result.settle.ok) return left_out("padding grows over the settled garments: not settled");
  cloth::SimulationOptions o = outfit.settled_with;
  // As the settle began, whichever settle was kept.
  o.rise_skips_held_springs =
      std::any_of(garments.begin(), garments.end(), [](const DressedGarment& g) { return g.from_pattern; });
  // A padding that stalls (its growth pressed between body and cloth) grows again from the settled
  // sheets allowing twice, then four times the rise in strain a step, as the settle does.
  const std::vector<DressedGarment> settled = garments;
  const double allowed = o.max_strain_change;
  PaddingRun p;
  std::string retried;
  for (const double factor : {1.0, 2.0, 4.0}) {
    if (factor > 1.0) {
      garments = settled;
      retried += "; padding " + p.run.stopped_reason + ", grown again allowing a rise in strain of " +
                 number(factor * allowed) + " a step";
    }
    o.max_strain_change = factor * allowed;
    p = pad_garments(garments, outfit.fabrics, *outfit.body_distance(), o, outfit.separation, outfit.settle_duration,
                     outfit.settle_max_steps, outfit.waistbands, options.on_settle);
    if (!p.run.stalled) break;
  }
  result.padding_ran = true;
  result.padding_settle = p.run;
  std::string report;
  for (const DressedGarment& g : garments)
    if (g.padded)
      report += (report.empty() ? "" : "; ") + g.name + " " + number(1e3 * g.padding.thickness) + " mm asked, shells " +
                number(1e3 * g.padding.gap_min) + "–" + number(1e3 * g.padding.gap_max) + " mm apart (median " +
                number(1e3 * g.padding.gap_median) + "), " + std::to_string(g.padding.start_at_full) + " of " +
                counted(g.dressed.rows(), "vertex", "vertices") + " started at the full thickness";
  return ran(report + "; " + counted(p.run.totals.steps, "step", "steps") + ", " + number(p.simulated) + " s simulated, " +
             p.run.stopped_reason + retried);
}

}  // namespace dresskit::dressing::detail::stages
