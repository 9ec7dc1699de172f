#pragma once
// `dress-a-mesh segment`: spectral segmentation into named parts, with dumps to look at
// (docs/cli.md, docs/segmentation.md).
#include <CLI/CLI.hpp>
#include <string>

#include "dresskit/segmentation/segment.h"

namespace dresskit::cli {

struct SegmentCommand {
  std::string path, units = "m", up = "+y", forward, output, affinity = "dihedral",
                    laplacian = "normalized";
  int parts = -1;  // -1: not given (automatic)
  bool as_json = false;
  SegmentationOptions options;
  CLI::App* command = nullptr;

  void add_to(CLI::App& app);
  /// Writes DIR/labels.json, DIR/segments.ply and DIR/<part>.obj, prints a summary; returns the
  /// exit code. Throws InputError / OutputError like the other commands. Nothing is written unless
  /// the segmentation succeeded, and the files appear together (a temporary folder renamed into
  /// place).
  int run();
};

}  // namespace dresskit::cli
