#pragma once
// Skirts (pure kernels): a garment component that is a tube with two openings (waist and hem) has
// no junction for spectral clustering to find, but dressing a body in another pose needs it in a
// waist band that rests on the pelvis and a left and a right half that follow the legs. The cut
// follows from the skirt's own geometry (docs/segmentation.md, "Skirts").
#include <Eigen/Core>
#include <vector>

#include "dresskit/segmentation/graph.h"
#include "dresskit/segmentation/segment.h"

namespace dresskit::segmentation {

/// A skirt's own frame: the axis from the hem's centre to the waist's, and the character's left
/// made perpendicular to it.
struct SkirtFrame {
  bool is_skirt = false;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  ///< hem → waist, unit
  Eigen::Vector3d left = Eigen::Vector3d::UnitX();  ///< ⟂ axis, unit
  Eigen::Vector3d waist_centre = Eigen::Vector3d::Zero(), hem_centre = Eigen::Vector3d::Zero();
  double waist_radius = 0,
         hem_radius = 0;  ///< mean distance of the loop's vertices from its centre
  /// Where the waist band ends: height along the axis above the hem's centre, and as a fraction of
  /// the skirt's length from the waist (set by split_skirt).
  double band_height = 0, band_fraction = 0;
};

/// Whether the component (its vertices) is a skirt: exactly two boundary loops, the hem (the lower
/// loop along a given up axis, else the wider one) at least as wide as the waist, and, with a given
/// up axis, the waist above the hem within 30° of up. Left: the axes' left made perpendicular to
/// the skirt's axis; with an estimated up axis the skirt's axis is taken for up and forward is the
/// direction of least spread perpendicular to it (sign: the given forward, else +Z).
SkirtFrame detect_skirt(const MeshGraph& graph, const Eigen::MatrixX3d& V,
                        const Eigen::VectorXd& vertex_area, const std::vector<int>& vertices,
                        const AxesEstimate& axes);

/// Cuts a skirt into a waist band (label 0) and left (1) and right (2) halves; writes labels(v) for
/// the component's vertices only. The band ends at the knee of the radius profile: the skirt's
/// mean radius per slice along its axis rises from the waist over the hips and then levels off,
/// flares more slowly or narrows again; the band ends at the slice farthest above the chord from
/// the waist slice to the hem slice (Kneedle), i.e. where the skirt stops following the hips.
/// Without a knee (a plain tube, a cone, a skirt that flares ever faster) the band is the top
/// slice. Below the band, each vertex goes to the side of the sagittal plane (through the axis,
/// normal `left`) it lies on; vertices on the plane (within 5 % of the mean edge length: a
/// centre seam) belong to neither half and stay with the band. Slices are two mean edge lengths
/// high (6–50 of them). Fills frame.band_height / band_fraction.
void split_skirt(const MeshGraph& graph, const Eigen::MatrixX3d& V,
                 const Eigen::VectorXd& vertex_area, const std::vector<int>& vertices,
                 SkirtFrame& frame, Eigen::VectorXi& labels);

}  // namespace dresskit::segmentation
