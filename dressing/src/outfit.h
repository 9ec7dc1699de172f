#pragma once
// The dressing pipeline's state and its stages (docs/dressing.md). dress() runs a table of stages
// over one Outfit; each stage is a file under stages/ with one function `StageReport run(Outfit&,
// const DressOptions&)` that reads what earlier stages left in the outfit and adds its own.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dresskit/alignment/wearer.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/inside.h"

namespace dresskit::dressing::detail {

/// What dress() was given and what its stages have made of it so far. It refers to the files it is
/// made with, which must outlive it.
struct Outfit {
  Outfit(const MeshFile& body_file, const std::vector<GarmentFile>& garment_files);

  const MeshFile& body_file;
  const std::vector<GarmentFile>& garment_files;
  /// The result as built: body and garments (from load; garments in layer order from layers),
  /// stages, settle. Moved out when the stages end.
  DressResult result;
  std::vector<cloth::Fabric> fabrics;  ///< per garment, in result.garments' order
  /// Per garment (result.garments' order), the garment carried from its wearer onto the body
  /// (wearer); empty for a sewing pattern, which is sewn around the body.
  std::vector<std::optional<alignment::CarriedGarment>> carried;

  /// The body's distance (for sewing, untangling, grading and settling) and inside test, each
  /// built when first asked for (a stage that changes the body calls forget_body()).
  const std::shared_ptr<const cloth::MeshDistance>& body_distance();
  const mesh::InsideTest& inside();
  void forget_body();
  double body_height = 0.0;  ///< [m] (units)

  /// Patterns carried part by part (GarmentFile::pattern_body): their bodies with part labels, each
  /// read once, and this body's parts found at load (kept for segmentation unless cleaning changes
  /// the body).
  std::map<std::string, mesh::TriangleMesh> pattern_bodies;
  std::optional<mesh::TriangleMesh> labelled_body;
  std::vector<DressPart> labelled_body_parts;
  bool labelled_body_from_file = false;

  /// The distance layers are kept apart by: the thickest cloth's own thickness [m] (thickness).
  double separation = 0.0;
  /// Per garment, the vertices held as its waistband while settling (settle; padding holds them too).
  std::vector<std::vector<int>> waistbands;
  /// The simulator's options of the settle that was kept and the simulated time it had (settle;
  /// padding runs as long, with the same options).
  cloth::SimulationOptions settled_with;
  double settle_duration = 0.0;
  /// Steps at most for that time (DressOptions::settle_step_budget × settle_duration / dt; 0: no bound).
  int settle_max_steps = 0;

 private:
  std::shared_ptr<const cloth::MeshDistance> body_distance_;
  std::optional<mesh::InsideTest> inside_;
};

/// What a stage did, or why it was left out.
struct StageReport {
  bool ran = false;
  std::string reason;
};
inline StageReport ran(std::string reason) { return {true, std::move(reason)}; }
inline StageReport left_out(std::string reason) { return {false, std::move(reason)}; }

/// The stages, in the order dress() runs them (stages/*.cpp).
namespace stages {
StageReport load(Outfit& outfit, const DressOptions& options);
StageReport clean(Outfit& outfit, const DressOptions& options);
StageReport units(Outfit& outfit, const DressOptions& options);
StageReport segmentation(Outfit& outfit, const DressOptions& options);
StageReport wearer(Outfit& outfit, const DressOptions& options);
StageReport layers(Outfit& outfit, const DressOptions& options);
StageReport placement(Outfit& outfit, const DressOptions& options);
StageReport thickness(Outfit& outfit, const DressOptions& options);
StageReport grading(Outfit& outfit, const DressOptions& options);
StageReport settle(Outfit& outfit, const DressOptions& options);
StageReport padding(Outfit& outfit, const DressOptions& options);
}  // namespace stages

/// Measures the dressed outfit into its result (crossings, inside, strain, layer gaps, warnings).
void measure_dressed(Outfit& outfit);

}  // namespace dresskit::dressing::detail
