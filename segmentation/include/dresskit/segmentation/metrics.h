#pragma once
// Segmentation accuracy against ground truth (pure kernels): per-part IoU after the best one-to-one
// matching of labels (Hungarian) and the Rand index. Vertices whose truth label is −1 are ignored.
#include <Eigen/Core>
#include <vector>

namespace dresskit::segmentation {

struct LabelComparison {
  /// For every truth label t: the predicted label matched to it (−1 when none) and the IoU of the
  /// two vertex sets (0 when unmatched).
  std::vector<int> matched;
  std::vector<double> iou;
  double mean_iou = 0.0;    ///< mean over truth labels (unmatched count as 0)
  double rand_index = 0.0;  ///< fraction of vertex pairs on which both labelings agree
  double agreement =
      0.0;  ///< fraction of compared vertices whose label is the one matched to their truth
  int compared = 0;  ///< vertices with a truth label
};

/// Compares predicted labels (−1 = unlabelled, never matched) with truth labels (−1 = ignored);
/// both of length #V.
LabelComparison compare_labels(const Eigen::VectorXi& predicted, const Eigen::VectorXi& truth);

/// The assignment of rows to columns that maximises the total score (rows ≤ or ≥ columns);
/// result[r] = column or −1. O(n³) Hungarian method.
std::vector<int> max_weight_matching(const Eigen::MatrixXd& score);

}  // namespace dresskit::segmentation
