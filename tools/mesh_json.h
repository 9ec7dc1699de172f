#pragma once
// A mesh's topology as JSON, as `info --json`, `clean --json` and the demo's report print it
// (docs/cli.md).
#include <nlohmann/json.hpp>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::cli {

nlohmann::json topology_json(const TriangleMesh& mesh);

}  // namespace dresskit::cli
