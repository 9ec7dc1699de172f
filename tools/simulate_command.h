#pragma once
// `dress-a-mesh simulate`: runs a cloth scene (docs/scenes.md) and writes the cloth, optional
// frames and report.json (docs/cli.md).
#include <CLI/CLI.hpp>
#include <string>

namespace dresskit::cli {

struct SimulateCommand {
  std::string scene, dir;
  bool frames = false;
  CLI::App* command = nullptr;

  void add_to(CLI::App& app);
  /// Runs the scene for its duration or until the cloth is at rest; a failed step (NaN, blow-up)
  /// stops the run: the last good state is written and the exit code is 4.
  int run();
};

}  // namespace dresskit::cli
