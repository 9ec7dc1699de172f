#pragma once
// `dress-a-mesh segment`: spectral segmentation into named parts, with dumps to look at
// (docs/cli.md, docs/segmentation.md).
#include <string>

#include "commands/command.h"

#include "dresskit/segmentation/segment.h"

namespace dresskit::cli {

struct SegmentCommand : Command {
  std::string path, units = "m", up = "+y", forward, output, affinity = "dihedral",
                    laplacian = "normalized";
  int parts = -1;  // -1: not given (automatic)
  bool as_json = false;
  segmentation::SegmentationOptions options;

  void add_to(CLI::App& app) override;
  /// Writes DIR/labels.json, DIR/segments.ply and DIR/<part>.obj, prints a summary; returns the
  /// exit code. Throws InputError / OutputError like the other commands. Nothing is written unless
  /// the segmentation succeeded, and the files appear together (a temporary folder renamed into
  /// place).
  int run() override;
};

}  // namespace dresskit::cli
