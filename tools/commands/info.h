#pragma once
// `dress-a-mesh info`: a mesh's vertices, faces, bounding box, components, boundary loops,
// manifoldness and closedness (docs/cli.md).
#include "commands/command.h"
#include "common/mesh.h"

namespace dresskit::cli {

struct InfoCommand : Command {
  MeshArgument mesh;
  bool as_json = false;

  void add_to(CLI::App& app) override;
  int run() override;
};

}  // namespace dresskit::cli
