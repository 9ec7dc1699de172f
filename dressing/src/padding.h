#pragma once
// Padded garments (dress.cpp's padding stage, docs/dressing.md): once the outfit has settled as
// sheets, each padded garment becomes a double layer over its settled sheet. Its outer shell starts
// as far out as it can without crossing anything, and the padding grows from there to the
// thickness heat conduction gives.
#include <functional>
#include <string>
#include <vector>

#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/run.h"
#include "dresskit/dressing/dress.h"

namespace dresskit::dressing::detail {

struct PaddingRun {
  cloth::RunResult run;
  double simulated = 0.0;  ///< [s]
};

/// Pads the padded garments of an outfit settled as sheets (their `dressed` positions; `padding`
/// set): sets dressed (inner shell), dressed_outer and the padding figures. Garments are stacked
/// `separation` apart [m] as when they settled; belt: their held vertices (mesh indices, per
/// garment). A padded garment's inner shell stays where it settled but where it lies over padding
/// (which pushes it out); the run lasts at most `seconds` and `max_steps` steps (0: no bound) and
/// stops at rest. A run that stalls keeps its last state (crossing nothing; the padding not grown
/// everywhere).
PaddingRun pad_garments(std::vector<DressedGarment>& garments, const std::vector<cloth::Fabric>& fabrics,
                        const cloth::MeshDistance& body, const cloth::SimulationOptions& options,
                        double separation, double seconds, int max_steps, const std::vector<std::vector<int>>& belt,
                        const std::function<void(double, double)>& on_settle);

}  // namespace dresskit::dressing::detail
