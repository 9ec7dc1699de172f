#pragma once
// Label clean-up on the vertex graph (pure kernels): one connected patch per label, smooth
// boundaries.
#include <Eigen/Core>

#include "dresskit/segmentation/graph.h"

namespace dresskit {

/// Keeps the largest connected patch (by vertex area) of every label and gives each other patch to
/// the neighbouring label that shares the most affinity with it, until every label present is one
/// patch. Labels −1 are left alone. Returns the number of vertices relabelled.
int merge_orphan_patches(const MeshGraph& graph, const Adjacency& adjacency,
                         const Eigen::VectorXd& vertex_area, Eigen::VectorXi& labels);

/// Boundary smoothing: `iterations` sweeps in which a vertex on a label boundary takes the label
/// with the largest total affinity among itself (weight: its mean edge affinity) and its
/// neighbours. Returns the number of label changes.
int smooth_label_boundaries(const MeshGraph& graph, const Adjacency& adjacency, int iterations,
                            Eigen::VectorXi& labels);

/// Merges adjacent parts until `target` labels remain (labels ≥ 0 of the vector, which must be
/// 0..q−1 with every label present): each step takes the merge that leaves the most leaf parts
/// (parts that touch exactly one other part: limbs, sleeves, trouser legs), then the lowest
/// normalised cut. A body over-segmented into head, chest, belly and limbs thus merges chest and
/// belly, not head and chest. Relabels to 0..target−1 and returns the number of leaf parts at the
/// end.
int merge_parts_towards_star(const MeshGraph& graph, int target, Eigen::VectorXi& labels);

/// Number of leaf parts (touching exactly one other part) of a labelling (labels ≥ 0).
int count_leaf_parts(const MeshGraph& graph, const Eigen::VectorXi& labels);

/// #F face labels: the label that at least two corners share, else the first corner's.
Eigen::VectorXi face_labels_from_vertices(const Eigen::MatrixX3i& F, const Eigen::VectorXi& labels);

}  // namespace dresskit
