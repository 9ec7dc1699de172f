#pragma once
// `dress-a-mesh align`: rigid registration of two meshes (--rigid) or the part-wise placement of a
// garment on a body (docs/cli.md, docs/alignment.md).
#include <string>

#include "commands/command.h"

#include "dresskit/alignment/placement.h"

namespace dresskit::cli {

struct AlignCommand : Command {
  std::string source, target, dir, units, source_units, target_units, up = "+y";
  std::string garment_labels, body_labels, garment_labels_key, body_labels_key, reference;
  bool rigid = false, with_scale = false, local = false, part_scale = false;
  double min_fitness = 0.5;
  alignment::GlobalOptions global;
  alignment::PlacementOptions placement;

  void add_to(CLI::App& app) override;
  /// Aligns and writes DIR/result.json with DIR/aligned.obj (--rigid) or DIR/posed.obj; returns the
  /// exit code. Throws InputError / OutputError like the other commands (nothing is written then).
  int run() override;
};

}  // namespace dresskit::cli
