// Input checks, transform helpers, fit scores and the multi-start global placement (no PCL here).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

#include "dresskit/alignment/icp.h"
#include "dresskit/mesh/errors.h"


namespace dresskit::alignment {
namespace {

struct Frame {
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;       // columns: principal axes, largest variance first, right-handed
  Eigen::Vector3d variances;  // descending
};

Frame principal_frame(const Eigen::MatrixX3d& V) {
  Frame f;
  f.centre = V.colwise().mean().transpose();
  const Eigen::MatrixX3d X = V.rowwise() - f.centre.transpose();
  const Eigen::Matrix3d C = X.transpose() * X / static_cast<double>(V.rows());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
  for (int k = 0; k < 3; ++k) {  // Eigen sorts ascending
    f.axes.col(k) = eig.eigenvectors().col(2 - k);
    f.variances(k) = std::max(0.0, eig.eigenvalues()(2 - k));
  }
  if (f.axes.determinant() < 0) f.axes.col(2) = -f.axes.col(2);
  return f;
}

// The 24 rotations that map the coordinate axes onto signed coordinate axes; identity first.
std::vector<Eigen::Matrix3d> axis_rotations() {
  std::vector<Eigen::Matrix3d> out;
  int perm[3] = {0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
      for (int k = 0; k < 3; ++k) P(perm[k], k) = (signs >> k & 1) ? -1.0 : 1.0;
      if (P.determinant() > 0) out.push_back(P);
    }
  } while (std::next_permutation(perm, perm + 3));
  return out;
}

FitScore score_with(const PointLocator& locator, const Eigen::MatrixX3d& V,
                    const Eigen::Matrix4d& T, double inlier_distance) {
  FitScore s;
  if (V.rows() == 0) return s;
  const Eigen::MatrixX3d moved = transform_points(T, V);
  int inliers = 0;
  double sum = 0.0;
  const double limit = inlier_distance * inlier_distance;
  for (Eigen::Index i = 0; i < moved.rows(); ++i) {
    double d2 = 0.0;
    locator.nearest(moved.row(i).transpose(), &d2);
    if (d2 <= limit) {
      ++inliers;
      sum += d2;
    }
  }
  s.fitness = static_cast<double>(inliers) / static_cast<double>(V.rows());
  s.rmse = inliers ? std::sqrt(sum / inliers) : 0.0;
  return s;
}

Eigen::Matrix4d similarity(double s, const Eigen::Matrix3d& R, const Eigen::Vector3d& from,
                           const Eigen::Vector3d& to) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 3>(0, 0) = s * R;
  T.block<3, 1>(0, 3) = to - s * R * from;
  return T;
}

}  // namespace

double bbox_diagonal(const Eigen::MatrixX3d& V) {
  if (V.rows() == 0) return 0.0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

void check_point_set(const PointSet& points, const std::string& what, int min_points) {
  if (points.size() < min_points) {
    throw InputError(what + ": only " + std::to_string(points.size()) + " points (need at least " +
                     std::to_string(min_points) + ")");
  }
  for (Eigen::Index i = 0; i < points.V.rows(); ++i) {
    if (!points.V.row(i).allFinite())
      throw InputError(what + ": point " + std::to_string(i) + " has a non-finite coordinate");
  }
  if (points.N.rows() && (points.N.rows() != points.V.rows() || !points.N.allFinite()))
    throw InputError(what + ": normals missing or non-finite");
  const Frame f = principal_frame(points.V);
  const double extent = std::sqrt(f.variances(0));
  const double scale = std::max(1.0, points.V.cwiseAbs().maxCoeff());
  if (extent <= 1e-9 * scale) throw InputError(what + ": all points are (nearly) identical");
  if (std::sqrt(f.variances(1)) <= 1e-6 * extent)
    throw InputError(what + ": all points lie on one line (rotation about it is undetermined)");
}

Eigen::MatrixX3d transform_points(const Eigen::Matrix4d& T, const Eigen::MatrixX3d& V) {
  return (V * T.block<3, 3>(0, 0).transpose()).rowwise() + T.block<3, 1>(0, 3).transpose();
}

Eigen::MatrixX3d transform_normals(const Eigen::Matrix4d& T, const Eigen::MatrixX3d& N) {
  const Eigen::Matrix3d A = T.block<3, 3>(0, 0);
  const Eigen::Matrix3d R = A / std::cbrt(A.determinant());
  return N * R.transpose();
}

FitScore score_fit(const PointSet& source, const PointSet& target, const Eigen::Matrix4d& T,
                   double inlier_distance) {
  return score_with(PointLocator(target.V), source.V, T, inlier_distance);
}

GlobalResult global_align(const PointSet& source, const PointSet& target,
                          const GlobalOptions& options) {
  check_point_set(source, "source");
  check_point_set(target, "target");
  const auto start = std::chrono::steady_clock::now();
  const PointSet full_target{target.V, target.N.rows() ? target.N : estimate_normals(target.V)};
  const double diag = bbox_diagonal(target.V);

  // Candidates are refined and scored on a fixed random subset of the source.
  PointSet small;
  {
    std::vector<int> rows(source.size());
    for (int i = 0; i < source.size(); ++i) rows[i] = i;
    std::mt19937 rng(777);
    std::shuffle(rows.begin(), rows.end(), rng);
    rows.resize(std::min<int>(source.size(), std::max(options.brief_source_points, 10)));
    small.V.resize(rows.size(), 3);
    if (source.N.rows()) small.N.resize(rows.size(), 3);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      small.V.row(k) = source.V.row(rows[k]);
      if (source.N.rows()) small.N.row(k) = source.N.row(rows[k]);
    }
  }

  const Frame fs = principal_frame(source.V), ft = principal_frame(target.V);
  const double s0 = options.with_scale ? std::sqrt(ft.variances.sum() / fs.variances.sum()) : 1.0;
  std::vector<Eigen::Matrix4d> starts;
  if (options.candidates <= 0) {
    starts.push_back(Eigen::Matrix4d::Identity());
  } else {
    const std::vector<Eigen::Matrix3d> flips = axis_rotations();
    const int n = std::min<int>(options.candidates, static_cast<int>(flips.size()));
    for (int k = 0; k < n; ++k)
      starts.push_back(
          similarity(s0, ft.axes * flips[k] * fs.axes.transpose(), fs.centre, ft.centre));
  }

  IcpOptions brief = options.icp;
  brief.max_iterations = options.brief_iterations;
  brief.with_scale = options.with_scale;
  brief.max_source_points = 0;
  if (brief.correspondence_distances.size() > 2) brief.correspondence_distances.resize(2);
  // Candidates only have to be ranked: plain hard-correspondence stages at the thresholds they
  // had before the soft stage existed; the winner gets the full refinement below.
  brief.soft_neighbours = 0;
  brief.coarse_epsilon_factor = 1.0;
  const PointLocator locator(target.V);

  GlobalResult out;
  double best_fitness = -1.0, best_rmse = 0.0;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    CandidateScore c;
    c.start = starts[k];
    c.refined = icp_align(small, full_target, brief, starts[k]).transform;
    const FitScore fit =
        score_with(locator, small.V, c.refined, options.icp.inlier_distance * diag);
    c.fitness = fit.fitness;
    c.rmse = fit.rmse;
    // Highest fitness wins; within half a percent, the lower RMSE.
    if (c.fitness > best_fitness + 0.005 ||
        (std::abs(c.fitness - best_fitness) <= 0.005 && c.rmse < best_rmse)) {
      best_fitness = c.fitness;
      best_rmse = c.rmse;
      out.best_candidate = static_cast<int>(k);
    }
    out.candidates.push_back(c);
  }
  IcpOptions final_options = options.icp;
  final_options.with_scale = options.with_scale;
  out.result =
      icp_align(source, full_target, final_options, out.candidates[out.best_candidate].refined);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace dresskit::alignment
