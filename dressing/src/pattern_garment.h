#pragma once
// Garments given as sewing patterns (dress.cpp): read, cut, sewn around the body and welded into
// one mesh, which the pipeline then treats as a garment mesh; and their panels' areas once dressed.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/dressing/dress.h"

namespace dresskit::dressing::detail {

/// Whether the garment file is a sewing pattern (a .json file) rather than a mesh.
bool is_pattern_garment(const GarmentFile& g);

/// The two bodies a pattern is carried between part by part (GarmentFile::pattern_body), each with
/// part labels (the segmentation's names or a label file's); null: carried by frames.
struct PartBodies {
  const mesh::TriangleMesh* pattern_body = nullptr;
  const mesh::TriangleMesh* body = nullptr;
};

/// Reads the pattern of g, cuts it, sews it around the body (metres; body_distance is its
/// distance) in g's fabric and welds it: fills d.mesh (the sewn garment, its rest shape) and
/// d.pattern; its outputs are to be in the body file's units and axes (`body_units`). Throws
/// InputError naming the file and the panel, edge or stitch for a bad pattern.
void sew_pattern_garment(const GarmentFile& g, const mesh::TriangleMesh& body, const mesh::LoadOptions& body_units,
                         const std::shared_ptr<const cloth::MeshDistance>& body_distance,
                         const DressOptions& options, const PartBodies& parts, DressedGarment& d);

/// Panels carried from the body they are placed around (`from`) to another (`to`), both with part
/// labels, +Y up, facing +Z [m]. Each panel follows the part of `from` that most of its points lie
/// nearest: over an arm (more than half of them), turned about the shoulder in the frontal plane
/// as the arm is (the direction from where the arm meets the torso to the arm's centroid, seen
/// from the front) and moved with it; over one leg (four fifths), the same about the hip; anywhere
/// else, moved as the torso is at the panel's height — as the midpoints of the hips, of the
/// shoulders and the neck are, linearly between. A panel so brought nearer to `to` than it lies to
/// `from` (the least distance of its points to the body's vertices) is then moved out along its
/// normal by the difference. Panels stay rigid (their rest lengths are the flat pattern's).
/// `placed`: the cut vertices as the pattern places them, `panel_of_vertex` their panels.
struct PanelMoves {
  std::vector<Eigen::Matrix4d> moves;  ///< per panel
  std::vector<std::string> parts;      ///< per panel: torso, head, arm_left, arm_right, leg_left, leg_right
};
PanelMoves panel_moves(const Eigen::MatrixX3d& placed, const Eigen::VectorXi& panel_of_vertex, int panels,
                       const mesh::TriangleMesh& from, const mesh::TriangleMesh& to);

/// Each panel's area at the garment's dressed positions into d.pattern.panel_area_dressed (nothing
/// when the cleaning stage changed the sewn mesh's vertices).
void measure_dressed_panels(DressedGarment& d);

}  // namespace dresskit::dressing::detail
