// Thickness: each cloth's own thickness from its fabric keeps the layers apart; a padded garment's
// thickness and its limits come from heat conduction through its fabric (docs/thickness.md).
#include <algorithm>

#include "../measures.h"
#include "../outfit.h"
#include "dresskit/thickness/thickness.h"

namespace dresskit::dressing::detail::stages {

StageReport thickness(Outfit& outfit, const DressOptions& options) {
  std::vector<DressedGarment>& garments = outfit.result.garments;
  std::string report;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    DressedGarment& g = garments[k];
    const cloth::Fabric& f = outfit.fabrics[k];
    g.thickness = thickness::sheet_thickness(f.composition, f.areal_density);
    outfit.separation = std::max(outfit.separation, g.thickness);
    report += (report.empty() ? "" : ", ") + g.name + " " + number(1e3 * g.thickness, 2) + " mm";
  }
  report += " (mass per area over fibre density × solidity 0.25)";
  for (std::size_t k = 0; k < garments.size(); ++k) {
    DressedGarment& g = garments[k];
    if (!g.padded) continue;
    const thickness::ThicknessResult t = thickness::compute_thickness(outfit.fabrics[k].composition, options.padding);
    g.padding.thickness = t.thickness, g.padding.min = t.thickness_min, g.padding.max = t.thickness_max;
    report += "; " + g.name + " padded " + number(1e3 * t.thickness) + " mm (limits " + number(1e3 * t.thickness_min) +
              "–" + number(1e3 * t.thickness_max) + " mm) by heat conduction";
  }
  return ran(report);
}

}  // namespace dresskit::dressing::detail::stages
