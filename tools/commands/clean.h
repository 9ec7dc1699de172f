#pragma once
// `dress-a-mesh clean`: repairs a mesh (CGAL) and writes it, printing what it fixed (docs/cli.md).
#include <string>

#include "commands/command.h"
#include "common/mesh.h"
#include "dresskit/mesh/cleanup.h"

namespace dresskit::cli {

struct CleanCommand : Command {
  MeshArgument mesh;
  std::string output;
  mesh::CleanupOptions options;
  bool as_json = false;

  void add_to(CLI::App& app) override;
  /// Refuses an output that is the input or cannot be written before loading; writes nothing
  /// broken or empty.
  int run() override;
};

}  // namespace dresskit::cli
