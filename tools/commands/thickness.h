#pragma once
// `dress-a-mesh thickness`: a fabric's thickness from heat conduction (docs/cli.md, docs/thickness.md).

#include <string>

#include "commands/command.h"

#include "dresskit/thickness/thickness.h"

namespace dresskit::cli {

struct ThicknessCommand : Command {
  std::string fabric, fabric_file, composition, plot_dir, scheme = "crank-nicolson", panel_areas;
  bool all_fabrics = false, as_json = false;
  thickness::ThicknessOptions options;

  void add_to(CLI::App& app) override;
  /// Prints the thickness (or the ten fabrics' table) and writes the plot; returns the exit code.
  /// Throws InputError / OutputError like the other commands; CLI::ValidationError for usage.
  int run() override;
};

}  // namespace dresskit::cli
