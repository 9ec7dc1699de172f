#pragma once
// k-means++ with restarts and a fixed seed (deterministic), a pure kernel.
#include <Eigen/Core>

namespace dresskit::segmentation {

struct KMeansOptions {
  int restarts = 10;         ///< independent k-means++ starts; the lowest cost wins
  int max_iterations = 100;  ///< Lloyd iterations per start
  unsigned seed = 5489;      ///< seed of the std::mt19937 that picks the centres
};

struct KMeansResult {
  Eigen::VectorXi labels;   ///< #points cluster index in [0, k)
  Eigen::MatrixXd centres;  ///< k × dim
  double cost = 0.0;        ///< sum of squared distances to the centres
  int iterations = 0;       ///< Lloyd iterations of the winning start
};

/// Clusters the rows of X (#points × dim) into k clusters (1 ≤ k ≤ #points).
KMeansResult kmeans(const Eigen::MatrixXd& X, int k, const KMeansOptions& options = {});

}  // namespace dresskit::segmentation
