#include "dresskit/segmentation/metrics.h"

#include <algorithm>
#include <limits>

namespace dresskit::segmentation {

std::vector<int> max_weight_matching(const Eigen::MatrixXd& score) {
  // Hungarian method (potentials, O(n³)) on the square cost matrix −score padded with zeros.
  const int rows = static_cast<int>(score.rows()), cols = static_cast<int>(score.cols());
  const int n = std::max(rows, cols);
  Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(n, n);
  cost.topLeftCorner(rows, cols) = -score;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(n + 1, 0);
  std::vector<int> p(n + 1, 0), way(n + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(n + 1, inf);
    std::vector<bool> used(n + 1, false);
    do {
      used[j0] = true;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= n; ++j) {
        if (used[j]) continue;
        const double cur = cost(i0 - 1, j - 1) - u[i0] - v[j];
        if (cur < minv[j]) {
          minv[j] = cur;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= n; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0);
  }
  std::vector<int> result(rows, -1);
  for (int j = 1; j <= n; ++j)
    if (p[j] >= 1 && p[j] <= rows && j <= cols) result[p[j] - 1] = j - 1;
  return result;
}

LabelComparison compare_labels(const Eigen::VectorXi& predicted, const Eigen::VectorXi& truth) {
  LabelComparison out;
  const int kp = predicted.size() ? std::max(predicted.maxCoeff() + 1, 0) : 0;
  const int kt = truth.size() ? std::max(truth.maxCoeff() + 1, 0) : 0;
  // Contingency table; predicted −1 goes to an extra column that is never matched.
  Eigen::MatrixXd table = Eigen::MatrixXd::Zero(kt, kp + 1);
  for (int i = 0; i < truth.size(); ++i) {
    if (truth(i) < 0) continue;
    table(truth(i), predicted(i) < 0 ? kp : predicted(i)) += 1;
    ++out.compared;
  }
  const Eigen::VectorXd truth_size = table.rowwise().sum();
  const Eigen::RowVectorXd pred_size = table.colwise().sum();
  Eigen::MatrixXd iou = Eigen::MatrixXd::Zero(kt, kp);
  for (int t = 0; t < kt; ++t)
    for (int p = 0; p < kp; ++p) {
      const double uni = truth_size(t) + pred_size(p) - table(t, p);
      iou(t, p) = uni > 0 ? table(t, p) / uni : 0.0;
    }
  out.matched = max_weight_matching(iou);
  out.iou.assign(kt, 0.0);
  for (int t = 0; t < kt; ++t) {
    if (out.matched[t] >= 0 && iou(t, out.matched[t]) > 0) {
      out.iou[t] = iou(t, out.matched[t]);
    } else {
      out.matched[t] = -1;
    }
  }
  double agreeing = 0;
  for (int t = 0; t < kt; ++t)
    if (out.matched[t] >= 0) agreeing += table(t, out.matched[t]);
  out.agreement = out.compared ? agreeing / out.compared : 0.0;
  int present = 0;
  double sum = 0;
  for (int t = 0; t < kt; ++t)
    if (truth_size(t) > 0) {
      sum += out.iou[t];
      ++present;
    }
  out.mean_iou = present ? sum / present : 0.0;
  // Rand index from pair counts: agreements = C(n,2) − (pairs together in one labeling only).
  const double n = out.compared;
  auto pairs = [](double x) { return x * (x - 1) / 2; };
  double both = 0, in_truth = 0, in_pred = 0;
  for (int t = 0; t < kt; ++t) {
    in_truth += pairs(truth_size(t));
    for (int p = 0; p <= kp; ++p) both += pairs(table(t, p));
  }
  for (int p = 0; p <= kp; ++p) in_pred += pairs(pred_size(p));
  const double total = pairs(n);
  out.rand_index = total > 0 ? (total - in_truth - in_pred + 2 * both) / total : 1.0;
  return out;
}

}  // namespace dresskit::segmentation
