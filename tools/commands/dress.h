#pragma once
// `dress-a-mesh dress`: dresses a body in garments from files (docs/cli.md, docs/dressing.md).
#include <string>
#include <vector>

#include "commands/command.h"
#include "common/progress.h"
#include "dresskit/dressing/dress.h"

namespace dresskit::cli {

struct DressCommand : Command {
  std::string body;
  std::vector<std::string> garments, fabrics, paddings, garment_labels;
  std::string dir, units, body_units, garment_units, up = "+y", body_up, garment_up, body_labels, quality = "fast",
              layers = "given", pattern_body, pattern_body_units, pattern_body_labels;
  bool no_settle = false, as_json = false, segments = false;

  void add_to(CLI::App& app) override;
  /// Writes DIR/report.json, DIR/report.html, DIR/dressed.glb and per garment DIR/<stem>.placed.obj
  /// and DIR/<stem>.dressed.obj (with --segments also DIR/segments.ply), all together once the run
  /// succeeded; prints one line per stage on stderr. Returns the exit code (4 when settling blew
  /// up: DIR/report.html alone is written); throws InputError / OutputError like the other commands.
  int run() override;
};

/// Prints one line per stage on stderr ("COMMAND: stage  seconds  what it did"), and draws the
/// progress bar while settling (only on a terminal).
void show_progress(const std::string& command, dressing::DressOptions& options, Progress& progress);

/// For a run whose settling failed, or that a stage refused (`refused`: its line): writes
/// DIR/report.html alone (what failed, what the stages made) as the run's outputs (write_folder).
/// Returns what was written, for the error line; a page that cannot be written is said there, not
/// thrown.
std::string write_failure_page(const std::string& dir, const dressing::DressResult& result, const std::string& command,
                               const std::vector<std::string>& inputs = {}, const std::string& refused = "");

}  // namespace dresskit::cli
