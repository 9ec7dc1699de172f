#pragma once
// The shapes of the alignment accuracy tests and bench: whole meshes and single parts, from the
// procedural mannequin and from ../shared/data (used by path; skipped when the data is missing).
#include <filesystem>
#include <string>
#include <vector>

#include "dresskit/alignment/icp.h"
#include "dresskit/alignment/part_labels.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mannequin/mannequin.h"

namespace dresskit::test {

struct Shape {
  std::string name;
  alignment::PointSet points;  // vertices with area-weighted normals
};

inline alignment::PointSet part_points(const mesh::TriangleMesh& mesh, const std::string& part) {
  const Eigen::MatrixX3d N = mesh::vertex_normals(mesh.V, mesh.F);
  alignment::PointSet out;
  if (part.empty()) return alignment::PointSet{mesh.V, N};
  std::vector<int> rows;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.labels(v) >= 0 && mesh.label_names[mesh.labels(v)] == part) rows.push_back(v);
  out.V.resize(rows.size(), 3);
  out.N.resize(rows.size(), 3);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    out.V.row(k) = mesh.V.row(rows[k]);
    out.N.row(k) = N.row(rows[k]);
  }
  return out;
}

/// The mannequin and its torso; with data_dir, also a MakeHuman body and its torso, and when
/// with_large a MakeHuman leg, the GarmentCode body and a garment.
inline std::vector<Shape> alignment_shapes(const std::string& data_dir, bool with_large) {
  std::vector<Shape> shapes;
  const mesh::TriangleMesh mannequin = make_mannequin(mannequin::BodyShape(mannequin::MannequinOptions{}));
  shapes.push_back({"mannequin", part_points(mannequin, "")});
  shapes.push_back({"mannequin torso", part_points(mannequin, "torso")});
  if (data_dir.empty() || !std::filesystem::is_directory(data_dir)) return shapes;
  mesh::LoadOptions dm;
  dm.units = mesh::Units::parse("dm");
  const std::string body_path = data_dir + "/bodies/mh_woman_young_average.obj";
  mesh::TriangleMesh body = mesh::load_mesh(body_path, dm);
  alignment::apply_part_labels(body, data_dir + "/labels/mh_body_part_labels.json");
  shapes.push_back({"mh_woman body", part_points(body, "")});
  shapes.push_back({"mh_woman torso", part_points(body, "torso")});
  if (with_large) {
    // A limb is nearly a surface of revolution: its rotation about its own axis is only weakly
    // determined under 0.5 % noise (reported separately in docs/alignment.md).
    shapes.push_back({"mh_woman leg_left", part_points(body, "leg_left")});
    shapes.push_back(
        {"gc_mean_all body", part_points(mesh::load_mesh(data_dir + "/bodies/gc_mean_all.obj"), "")});
    const std::string garment = data_dir + "/garments/mh_female_casualsuit01.obj";
    shapes.push_back({"casualsuit01 garment", part_points(mesh::load_mesh(garment, dm), "")});
  }
  return shapes;
}

}  // namespace dresskit::test
