#pragma once
// The demo's dressing stage: the default scene's trousers and t-shirt settled on the mannequin by
// the cloth simulator (body collider, cloth–cloth collisions, the t-shirt worn over the trousers).
#include <nlohmann/json.hpp>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/scene/garments.h"
#include "dresskit/scene/mannequin.h"

namespace dresskit::cli {

/// The dressing runs projective dynamics with adaptive stepping: a step whose largest strain jumps
/// (or that fails) is retried at half the step. On the demo's mannequin and five variants of it
/// (coarser mesh, girth 0.7 and 1.4, T-pose, 1.5 m) this is 3–4.4 times faster than implicit Euler
/// at 1/240 s with no crossing, no particle inside and a largest strain at the end of 10.4–11.3 %
/// (implicit 10.0–15.9 %); at 1/60 s × 10 iterations the strain ended at up to 21 % (docs/results.md).
struct DressDemoOptions {
  double seconds = 1.0;      ///< simulated time [s]; > 0
  double dt = 1.0 / 120.0;   ///< the largest time step [s]
  int iterations = 4;        ///< projective dynamics' iterations per step; > 0
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
