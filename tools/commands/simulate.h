#pragma once
// `dress-a-mesh simulate`: runs a cloth scene (docs/scenes.md) and writes the cloth, optional
// frames and report.json (docs/cli.md).
#include <filesystem>
#include <string>

#include "commands/command.h"
#include "dresskit/cloth/scene.h"

namespace dresskit::cli {

struct SimulateCommand : Command {
  std::string scene, dir;
  bool frames = false;

  void add_to(CLI::App& app) override;
  /// Runs the scene for its duration or until the cloth is at rest; a failed step (NaN, blow-up)
  /// stops the run: the last good state is written and the exit code is 4. The outputs of an
  /// earlier run into the folder are replaced as a whole (no stale frames stay).
  int run() override;

 private:
  /// The run, its outputs written into `out`; returns the exit code.
  int simulate_into(const cloth::ClothScene& s, const std::filesystem::path& out) const;
};

}  // namespace dresskit::cli
