#pragma once
// Known-transform trials for the accuracy tests and benchmarks: a point set is moved by a random
// rotation of a given angle and a random translation, noised and mixed with outliers; the error of
// a registration is measured against the known transform.
#include <random>

#include "dresskit/alignment/icp.h"

namespace dresskit {

struct TrialOptions {
  double angle_deg = 10.0;       ///< rotation angle about a uniformly random axis [degrees]
  double max_translation = 0.1;  ///< translation length uniform in [0, this] [fraction of diagonal]
  double noise = 0.005;          ///< Gaussian noise σ per coordinate [fraction of diagonal]
  double outliers = 0.1;  ///< outliers added, uniform in the enlarged box [fraction of points]
  double source_fraction =
      1.0;  ///< share of the clean points drawn (without replacement) as source
};

/// One trial: source = T⁻¹(noisy subset) + outliers; the registration of source onto target
/// should recover `truth` (source → target).
struct Trial {
  alignment::PointSet source, target;
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  Eigen::Vector3d source_centre = Eigen::Vector3d::Zero();  ///< centroid of the clean moved points
  double diagonal = 0.0;                                    ///< target bounding-box diagonal [m]
};

/// Builds a trial from clean points with normals (the target).
Trial make_trial(const alignment::PointSet& clean, const TrialOptions& options, std::mt19937& rng);

struct TrialError {
  double rotation_deg = 0.0;  ///< angle of R_estimated R_trueᵀ [degrees]
  double translation =
      0.0;  ///< |T_est(c) − T_true(c)| at the source centre c [fraction of diagonal]
  bool success(double max_rotation_deg = 0.5, double max_translation = 0.005) const {
    return rotation_deg < max_rotation_deg && translation < max_translation;
  }
};
TrialError trial_error(const Trial& trial, const Eigen::Matrix4d& estimated);

}  // namespace dresskit
