#pragma once
// Cloth scenes as JSON (docs/scenes.md): a cloth (grid, mesh or chain) with a fabric and pins,
// analytic colliders, and simulation settings. Unknown keys are errors that name the key.
#include <string>
#include <vector>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/run.h"
#include "dresskit/cloth/simulator.h"

namespace dresskit::cloth {

/// One garment of a scene: its fabric, whether it is a double layer and with which thickness, and
/// where its particles are in the scene's model.
struct GarmentInfo {
  std::string fabric;
  bool double_layer = false;
  LayerThickness thickness;  ///< double layers only [m]
  int first_vertex = 0, vertices = 0;
};

struct ClothScene {
  ClothModel model;
  std::vector<int> pins;           ///< vertex indices
  PinMotion pin_motion;            ///< driven pins (none when its particles are empty)
  bool weld_seams = true;          ///< output: closed particle-to-particle stitches as one vertex
  SimulationOptions simulation;
  RunOptions run;                  ///< duration, frames per second, stopping at rest
  std::string fabric_name;         ///< the first garment's
  std::vector<GarmentInfo> garments;  ///< from the body outwards
  Eigen::MatrixX3i faces;          ///< for output; empty for a chain (written as a polyline)
  std::vector<std::string> files;  ///< the files the scene reads besides itself (meshes, fabric files)
};

/// Reads and checks a scene file; mesh and fabric paths are relative to the scene's folder. Throws
/// InputError "<file>: <key>: <problem>" for a malformed, unknown or out-of-range entry.
ClothScene load_cloth_scene(const std::string& path);

/// OBJ text of the cloth at positions x: faces, or a polyline when there are none.
std::string cloth_obj_text(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces,
                           const SpringSet& springs);

}  // namespace dresskit::cloth
