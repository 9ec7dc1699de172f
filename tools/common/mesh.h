#pragma once
// A mesh argument (path, units, up axis) and a mesh's topology as JSON, as `info`, `clean` and the
// demo's report print it (docs/cli.md).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::cli {

/// MESH [--units U] [--up AXIS]
struct MeshArgument {
  std::string path, units = "m", up = "+y";
  void add_to(CLI::App* command);
  /// Loaded in metres, +Y up; throws InputError naming the file or value.
  mesh::TriangleMesh load() const;
};

nlohmann::json topology_json(const mesh::TriangleMesh& mesh);

}  // namespace dresskit::cli
