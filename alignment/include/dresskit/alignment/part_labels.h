#pragma once
// Per-vertex part labels from a file: the shared data's label files or `segment`'s output. The
// result has the layout of TriangleMesh::labels / label_names, which is what the part-wise
// placement reads; a segmentation result plugs in by filling those two fields.
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::alignment {

/// Reads labels in the formats of ../shared/data/labels:
/// - {"labels": ["torso", "arm_left", …]}: one name per vertex in the source file's vertex order;
/// - {"labels": {"<key>": [names…], …}}: several meshes in one file; `key` picks one (when empty,
///   the mesh file's stem is tried with and without an "mh_" prefix);
/// - {"<part>": [vertex indices…], …}: 0-based index lists per part (GarmentCode segmentation);
/// - {"vertex_labels": [part ids…], "part_names": [names…], …}: `segment`'s labels.json (−1: none).
/// Sets mesh.labels and mesh.label_names through mesh.source_vertex (so the file's vertex order is
/// kept whatever the loader did). Throws InputError naming the file for a missing key, a count that
/// differs from the mesh's source vertex count, or a malformed file.
void apply_part_labels(mesh::TriangleMesh& mesh, const std::string& labels_path,
                       const std::string& key = "", const std::string& mesh_path = "");

}  // namespace dresskit::alignment
