#include "dresskit/testing/registration_trials.h"

#include <algorithm>
#include <cmath>
#include <numeric>

using namespace dresskit::alignment;

namespace dresskit {

Trial make_trial(const PointSet& clean, const TrialOptions& options, std::mt19937& rng) {
  Trial t;
  t.target = clean;
  t.diagonal = bbox_diagonal(clean.V);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::Vector3d axis(gauss(rng), gauss(rng), gauss(rng));
  axis.normalize();
  Eigen::Vector3d direction(gauss(rng), gauss(rng), gauss(rng));
  direction.normalize();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(options.angle_deg * M_PI / 180.0, axis).toRotationMatrix();
  // Rotation about the clean centroid, then a translation: the target frame sees source as
  // truth⁻¹(x).
  const Eigen::Vector3d c = clean.V.colwise().mean().transpose();
  const Eigen::Vector3d shift = direction * uniform(rng) * options.max_translation * t.diagonal;
  t.truth.setIdentity();
  t.truth.block<3, 3>(0, 0) = R;
  t.truth.block<3, 1>(0, 3) = c - R * c + shift;
  const Eigen::Matrix4d inverse = t.truth.inverse();

  std::vector<int> rows(clean.size());
  std::iota(rows.begin(), rows.end(), 0);
  std::shuffle(rows.begin(), rows.end(), rng);
  rows.resize(
      std::max<std::size_t>(10, static_cast<std::size_t>(options.source_fraction * clean.size())));
  const int n_out = static_cast<int>(options.outliers * rows.size());
  Eigen::MatrixX3d noisy(rows.size(), 3);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    noisy.row(k) = clean.V.row(rows[k]);
    for (int d = 0; d < 3; ++d) noisy(k, d) += gauss(rng) * options.noise * t.diagonal;
  }
  const Eigen::RowVector3d lo = clean.V.colwise().minCoeff(), hi = clean.V.colwise().maxCoeff();
  const Eigen::RowVector3d pad = 0.05 * (hi - lo);
  t.source.V.resize(rows.size() + n_out, 3);
  t.source.V.topRows(rows.size()) = transform_points(inverse, noisy);
  for (int k = 0; k < n_out; ++k) {
    Eigen::Vector3d p;
    for (int d = 0; d < 3; ++d) p(d) = lo(d) - pad(d) + uniform(rng) * (hi(d) - lo(d) + 2 * pad(d));
    t.source.V.row(rows.size() + k) = transform_points(inverse, p.transpose());
  }
  t.source_centre = t.source.V.topRows(rows.size()).colwise().mean().transpose();
  return t;
}

TrialError trial_error(const Trial& trial, const Eigen::Matrix4d& estimated) {
  TrialError e;
  const Eigen::Matrix3d Re =
      estimated.block<3, 3>(0, 0) / std::cbrt(estimated.block<3, 3>(0, 0).determinant());
  const Eigen::Matrix3d D = Re * trial.truth.block<3, 3>(0, 0).transpose();
  e.rotation_deg = std::acos(std::clamp((D.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
  const Eigen::Vector4d c(trial.source_centre.x(), trial.source_centre.y(), trial.source_centre.z(),
                          1.0);
  e.translation = (estimated * c - trial.truth * c).head<3>().norm() / trial.diagonal;
  return e;
}

}  // namespace dresskit
