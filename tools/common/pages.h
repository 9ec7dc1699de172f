#pragma once
// report.html of `segment` and `simulate` (dresskit/report/page.h; `dress` and `demo` write theirs
// through write_dress_outputs): the meshes in 3D and the command's figures as tables and plots.
#include <nlohmann/json.hpp>
#include <string>

#include "dresskit/cloth/run.h"
#include "dresskit/cloth/scene.h"
#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/report/page.h"

namespace dresskit::cli {

/// The segmented mesh coloured by part (`mesh` with its labels), the parts, the spectrum and the
/// times; `summary` is labels.json without its per-vertex and per-face arrays.
report::ReportPage segment_page(const std::string& path, const mesh::TriangleMesh& mesh,
                        const nlohmann::json& summary);

/// The cloth at its start and at its end (or, when the run failed, at the last good state) with its
/// colliders, strain and distance to the colliders as colour maps, energy over time, the phases'
/// times and the report's main figures.
report::ReportPage simulate_page(const std::string& scene_path, const cloth::ClothScene& scene,
                         const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& end,
                         const cloth::RunResult& result, const nlohmann::json& report);

}  // namespace dresskit::cli
