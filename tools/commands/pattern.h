#pragma once
// `dress-a-mesh pattern`: a sewing pattern read, checked and cut: its picture, its panels meshed
// flat and placed in 3D, and a summary (docs/pattern.md).
#include <string>

#include "commands/command.h"

namespace dresskit::cli {

struct PatternCommand : Command {
  std::string path, output;
  double edge = 0.02;          // target triangle edge length [m]
  double length_ratio = 1.05;  // stitched edges longer than this ratio warn
  bool as_json = false;

  void add_to(CLI::App& app) override;
  /// Writes DIR/pattern.svg, DIR/<name>.flat.obj, DIR/<name>.placed.obj and DIR/pattern.json, all
  /// or none; prints a summary or (--json) the summary as JSON. Warnings go to stderr.
  int run() override;
};

}  // namespace dresskit::cli
