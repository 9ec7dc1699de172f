#pragma once
// The dressing pipeline's output stage: the dressed result as files and a report (docs/dressing.md,
// docs/formats.md).
//
//   const dresskit::dressing::DressResult r = dresskit::dressing::dress(body, garments);
//   const std::string report = dresskit::dressing::write_dress_outputs("out", r);
#include <string>

#include "dresskit/dressing/dress.h"

namespace dresskit::dressing {

struct DressOutputOptions {
  bool segments = false;  ///< also segments.ply: every mesh coloured by part
  /// Members added to report.json (the text of a JSON object, "" = none): what a caller knows
  /// about the run beyond the pipeline, such as how its meshes were made.
  std::string report_extra;
  /// Also report.html: the body and garments in 3D with the report's figures (docs/formats.md).
  bool page = true;
  std::string command = "dress";  ///< the command named on report.html ("dress", "demo")
};

/// Writes into `folder` (which must exist): report.json; report.html (with `page`); dressed.glb (the
/// body and each garment as named nodes); for every garment <name>.placed.obj and <name>.dressed.obj, in its file's own
/// vertex order, units and axes (a garment given in memory: in its own order, in m). report.json's
/// stages end with `write`, and its `seconds` is the whole run's. Returns report.json's text.
/// Throws OutputError naming the file that cannot be written, InputError for a bad report_extra.
std::string write_dress_outputs(const std::string& folder, const DressResult& result,
                                const DressOutputOptions& options = {});

/// For a run whose settling or padding failed (result.settle.ok or padding_settle.ok false, the
/// padding not merely stalled), or that a stage refused (`refused`: its line; DressRefused):
/// writes report.html alone into `folder` (which must exist), saying what failed and showing what
/// the stages made (the garments placed and at the last good state settling reached), with the
/// report's figures (its JSON included, not written). Throws OutputError naming the file that
/// cannot be written.
void write_dress_failure_page(const std::string& folder, const DressResult& result,
                              const DressOutputOptions& options = {}, const std::string& refused = "");

}  // namespace dresskit::dressing
