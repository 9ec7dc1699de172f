#include "dresskit/segmentation/kmeans.h"

#include <cassert>
#include <limits>
#include <random>

namespace dresskit::segmentation {
namespace {

// k-means++ seeding: each next centre drawn with probability ∝ squared distance to the nearest one.
Eigen::MatrixXd seed_centres(const Eigen::MatrixXd& X, int k, std::mt19937& rng) {
  const int n = static_cast<int>(X.rows());
  Eigen::MatrixXd C(k, X.cols());
  C.row(0) = X.row(std::uniform_int_distribution<int>(0, n - 1)(rng));
  Eigen::VectorXd d2 = (X.rowwise() - C.row(0)).rowwise().squaredNorm();
  for (int c = 1; c < k; ++c) {
    const double total = d2.sum();
    int pick = n - 1;
    if (total > 0) {
      double r = std::uniform_real_distribution<double>(0.0, total)(rng);
      for (int i = 0; i < n; ++i) {
        r -= d2(i);
        if (r <= 0) {
          pick = i;
          break;
        }
      }
    } else {
      pick = std::uniform_int_distribution<int>(0, n - 1)(rng);
    }
    C.row(c) = X.row(pick);
    d2 = d2.cwiseMin((X.rowwise() - C.row(c)).rowwise().squaredNorm());
  }
  return C;
}

}  // namespace

KMeansResult kmeans(const Eigen::MatrixXd& X, int k, const KMeansOptions& options) {
  const int n = static_cast<int>(X.rows()), dim = static_cast<int>(X.cols());
  assert(k >= 1 && k <= n);
  // Points as columns: each distance reads contiguous memory.
  const Eigen::MatrixXd P = X.transpose();
  std::mt19937 rng(options.seed);
  KMeansResult best;
  best.cost = std::numeric_limits<double>::infinity();
  for (int start = 0; start < std::max(1, options.restarts); ++start) {
    Eigen::MatrixXd C = seed_centres(X, k, rng).transpose();  // dim × k
    Eigen::VectorXi labels = Eigen::VectorXi::Constant(n, -1);
    double cost = 0.0;
    int it = 0;
    for (; it < options.max_iterations; ++it) {
      bool changed = false;
      cost = 0.0;
      for (int i = 0; i < n; ++i) {
        int arg = 0;
        double best_d = std::numeric_limits<double>::infinity();
        for (int c = 0; c < k; ++c) {
          double d = 0.0;
          for (int j = 0; j < dim; ++j) {
            const double t = P(j, i) - C(j, c);
            d += t * t;
          }
          if (d < best_d) best_d = d, arg = c;
        }
        cost += best_d;
        if (labels(i) != arg) labels(i) = arg, changed = true;
      }
      if (!changed) break;
      Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(dim, k);
      Eigen::VectorXi count = Eigen::VectorXi::Zero(k);
      for (int i = 0; i < n; ++i) {
        sum.col(labels(i)) += P.col(i);
        ++count(labels(i));
      }
      for (int c = 0; c < k; ++c)
        if (count(c) > 0) C.col(c) = sum.col(c) / count(c);  // an empty cluster keeps its centre
    }
    if (cost < best.cost) {
      best.cost = cost;
      best.labels = labels;
      best.centres = C.transpose();
      best.iterations = it;
    }
  }
  return best;
}

}  // namespace dresskit::segmentation
