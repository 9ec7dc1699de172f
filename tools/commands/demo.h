#pragma once
// `dress-a-mesh demo`: the embedded default scene, a procedural mannequin and garments made on it,
// dressed by the dressing pipeline like any user's meshes (docs/cli.md).
#include <string>

#include "commands/command.h"

#include "dresskit/mannequin/garments.h"
#include "dresskit/mannequin/mannequin.h"

namespace dresskit::cli {

struct DemoCommand : Command {
  std::string dir, pose = "a-pose", quality = "fast";
  mannequin::MannequinOptions body;
  mannequin::GarmentOptions garments;
  double seconds = 0.0;      ///< simulated settling at most [s]; 0: the quality's
  bool no_settle = false;
  double over_ease = 0.008;  ///< the t-shirt's ease beyond the trousers', so that they start apart [m]

  void add_to(CLI::App& app) override;
  /// Writes into DIR the mannequin and the garments made on it (obj, ply, glb), and the dressing
  /// pipeline's outputs for the mannequin in trousers (11oz-black-denim) under a t-shirt
  /// (gray-interlock): report.json, dressed.glb, <garment>.placed.obj, <garment>.dressed.obj, all
  /// together once the run succeeded. Returns the exit code (4: settling blew up, nothing written).
  int run() override;
};

}  // namespace dresskit::cli
