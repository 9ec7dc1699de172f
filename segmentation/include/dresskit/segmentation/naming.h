#pragma once
// Semantic part names from geometry relative to the up/forward axes (pure kernels).
#include <Eigen/Core>
#include <vector>

#include "dresskit/segmentation/graph.h"
#include "dresskit/segmentation/segment.h"

namespace dresskit::segmentation {

/// Up from the area-weighted PCA (largest spread; sign: towards the side where the area centroid
/// lies relative to the middle of the extent), forward from the feet (the lowest 4% of the height
/// sits ahead of the ankles) where the mesh has feet (`has_feet`: a body, not a garment, whose hem
/// at the lowest 4 % may flare behind or ahead) or else the axis of least spread with the sign of
/// +Z; given axes are kept.
AxesEstimate estimate_axes(const Eigen::MatrixX3d& V, const Eigen::VectorXd& vertex_area,
                           const Eigen::Vector3d& up_given, const Eigen::Vector3d& forward_given,
                           bool has_feet = true);

/// Names the parts (labels 0..P−1; label_component[l] = component of label l). A component cut into
/// a hub part touching five limb parts is a body (torso, head, arm_left, arm_right, leg_left,
/// leg_right: legs attach lowest, the head nearest the hub's axis); any other component is a
/// garment (one part: skirt when it has two boundary loops or widens downwards, else body; several
/// parts: the hub is body, a part below the hub more than beside it is leg_*, else sleeve_*). Left
/// is the character's left (axes.left).
std::vector<NamedPart> name_parts(const Eigen::MatrixX3d& V, const MeshGraph& graph,
                                  const Eigen::VectorXd& vertex_area, const Eigen::VectorXi& labels,
                                  const std::vector<int>& label_component,
                                  const AxesEstimate& axes);

}  // namespace dresskit::segmentation
