#pragma once
// `dress-a-mesh simulate`: runs a cloth scene (docs/scenes.md) and writes the cloth, optional
// frames and report.json (docs/cli.md).
#include <string>

#include "commands/command.h"

namespace dresskit::cli {

struct SimulateCommand : Command {
  std::string scene, dir;
  bool frames = false;

  void add_to(CLI::App& app) override;
  /// Runs the scene for its duration or until the cloth is at rest; a failed step (NaN, blow-up)
  /// stops the run: the last good state is written and the exit code is 4.
  int run() override;
};

}  // namespace dresskit::cli
