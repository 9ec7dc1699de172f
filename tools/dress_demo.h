#pragma once
// The demo's dressing stage: the default scene's trousers and t-shirt settled on the mannequin by
// the cloth simulator (body collider, cloth–cloth collisions, the t-shirt worn over the trousers).
#include <nlohmann/json.hpp>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/scene/garments.h"
#include "dresskit/scene/mannequin.h"

namespace dresskit::cli {

struct DressDemoOptions {
  double seconds = 1.0;      ///< simulated time [s]; > 0
  double dt = 1.0 / 240.0;   ///< time step [s]
  double over_ease = 0.008;  ///< the t-shirt's extra ease over the trousers' [m]
  double waistband = 0.015;  ///< the trousers' top band held as by a belt [m]
};

struct DressDemoResult {
  TriangleMesh outfit;   ///< the settled garments (labels: their parts)
  TriangleMesh dressed;  ///< the mannequin and the outfit in one mesh (labels: the body's, then the
                         ///< outfit's)
  nlohmann::json report;  ///< what ran and how it ended (docs/cli.md, demo)
  bool ok = true;         ///< false: a step failed; the outfit is the last good state
};

/// Dresses `body` (the mannequin made from `shape`) in `trousers` (made on it with `garments`) and
/// a t-shirt made with over_ease more ease. Throws InputError for options out of range.
DressDemoResult dress_demo(const TriangleMesh& body, const BodyShape& shape,
                           const TriangleMesh& trousers, const GarmentOptions& garments,
                           const DressDemoOptions& options = {});

}  // namespace dresskit::cli
