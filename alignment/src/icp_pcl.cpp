// Every use of PCL in dresskit::alignment lives in this file (its headers cost ~15 s and ~1 GB to
// compile per translation unit): ICP stages, the k-d tree behind PointLocator, normal estimation.
#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/features/normal_3d.h>
#include <pcl/point_types.h>
#include <pcl/registration/correspondence_rejection_median_distance.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation_svd_scale.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <random>

#include "dresskit/alignment/icp.h"
#include "kd_tree.h"

namespace dresskit::alignment {
namespace {

using PointT = pcl::PointNormal;
using Cloud = pcl::PointCloud<PointT>;

Eigen::Matrix4d translation(const Eigen::Vector3d& t) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 1>(0, 3) = t;
  return T;
}

// Points relative to `centre` in single precision, with normals (zero when N is empty).
Cloud::Ptr make_cloud(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& N,
                      const Eigen::Vector3d& centre, const std::vector<int>& rows) {
  Cloud::Ptr cloud(new Cloud);
  cloud->resize(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    PointT& p = (*cloud)[k];
    const Eigen::Vector3d x = V.row(rows[k]).transpose() - centre;
    p.x = static_cast<float>(x.x());
    p.y = static_cast<float>(x.y());
    p.z = static_cast<float>(x.z());
    const Eigen::Vector3d n =
        N.rows() ? Eigen::Vector3d(N.row(rows[k]).transpose()) : Eigen::Vector3d::Zero();
    p.normal_x = static_cast<float>(n.x());
    p.normal_y = static_cast<float>(n.y());
    p.normal_z = static_cast<float>(n.z());
  }
  return cloud;
}

std::vector<int> all_rows(int n) {
  std::vector<int> rows(n);
  std::iota(rows.begin(), rows.end(), 0);
  return rows;
}

// A fixed-seed random subset of at most `limit` rows (all rows when limit is 0 or not smaller).
std::vector<int> subset_rows(int n, int limit) {
  std::vector<int> rows = all_rows(n);
  if (limit <= 0 || limit >= n) return rows;
  std::mt19937 rng(12345);
  std::shuffle(rows.begin(), rows.end(), rng);
  rows.resize(limit);
  return rows;
}

// PCL keeps the iteration count protected; this exposes it.
template <class Base>
struct CountingIcp : Base {
  int iterations() const { return this->nr_iterations_; }
};
using Icp = CountingIcp<pcl::IterativeClosestPointWithNormals<PointT, PointT, double>>;
using ConvergenceState = pcl::registration::DefaultConvergenceCriteria<double>::ConvergenceState;

// Nearest-neighbour correspondences from our k-d tree (see kd_tree.h for why not PCL's): one
// target point per source point within the stage's maximum distance; distance = squared distance,
// as PCL's own estimation reports it (the median rejector works on these).
class TreeCorrespondences
    : public pcl::registration::CorrespondenceEstimationBase<PointT, PointT, double> {
 public:
  explicit TreeCorrespondences(std::shared_ptr<const detail::KdTree3> tree)
      : tree_3_(std::move(tree)) {
    corr_name_ = "TreeCorrespondences";
  }
  void determineCorrespondences(pcl::Correspondences& out, double max_distance) override {
    const double limit =
        std::min<double>(max_distance * max_distance, std::numeric_limits<float>::max());
    out.clear();
    out.reserve(input_->size());
    // The previous iteration's matches (the source cloud keeps its order and size between
    // iterations and stages) bound each search: most points move by much less than the spacing.
    if (hints_.size() != input_->size()) hints_.assign(input_->size(), -1);
    for (std::size_t i = 0; i < input_->size(); ++i) {
      const PointT& p = (*input_)[i];
      float d2 = 0.0f;
      const int j = tree_3_->nearest(Eigen::Vector3f(p.x, p.y, p.z), static_cast<float>(limit), &d2,
                                     hints_[i]);
      if (j >= 0) {
        out.emplace_back(static_cast<int>(i), j, d2);
        hints_[i] = j;
      }
    }
  }
  void determineReciprocalCorrespondences(pcl::Correspondences& out, double max_distance) override {
    determineCorrespondences(out, max_distance);  // ICP here never asks for reciprocal ones
  }
  pcl::registration::CorrespondenceEstimationBase<PointT, PointT, double>::Ptr clone()
      const override {
    return pcl::make_shared<TreeCorrespondences>(*this);
  }

 private:
  std::shared_ptr<const detail::KdTree3> tree_3_;
  std::vector<int> hints_;  // the previous iteration's match per source point
};

// The k nearest target points of every source point within the maximum distance, for the soft
// stage: consecutive entries per source point, distance = squared distance.
class TreeNeighbourCorrespondences
    : public pcl::registration::CorrespondenceEstimationBase<PointT, PointT, double> {
 public:
  TreeNeighbourCorrespondences(std::shared_ptr<const detail::KdTree3> tree, int k)
      : tree_3_(std::move(tree)), k_(std::min(k, kMaxK)) {
    corr_name_ = "TreeNeighbourCorrespondences";
  }
  void determineCorrespondences(pcl::Correspondences& out, double max_distance) override {
    const double limit =
        std::min<double>(max_distance * max_distance, std::numeric_limits<float>::max());
    out.clear();
    out.reserve(input_->size() * k_);
    int index[kMaxK];
    float d2[kMaxK];
    if (hints_.size() != input_->size() * k_) hints_.assign(input_->size() * k_, -1);
    for (std::size_t i = 0; i < input_->size(); ++i) {
      const PointT& p = (*input_)[i];
      int* hint = &hints_[i * k_];
      const int n = tree_3_->nearest_k(Eigen::Vector3f(p.x, p.y, p.z), k_,
                                       static_cast<float>(limit), index, d2, hint);
      for (int m = 0; m < n; ++m) out.emplace_back(static_cast<int>(i), index[m], d2[m]);
      for (int m = 0; m < k_; ++m) hint[m] = m < n ? index[m] : -1;
    }
  }
  void determineReciprocalCorrespondences(pcl::Correspondences& out, double max_distance) override {
    determineCorrespondences(out, max_distance);
  }
  pcl::registration::CorrespondenceEstimationBase<PointT, PointT, double>::Ptr clone()
      const override {
    return pcl::make_shared<TreeNeighbourCorrespondences>(*this);
  }

 private:
  static constexpr int kMaxK = 32;
  std::shared_ptr<const detail::KdTree3> tree_3_;
  int k_;
  std::vector<int> hints_;  // the previous iteration's neighbours, k_ per source point
};

// One EM step of registration against a "surface mixture": every target point j is a Gaussian
// with variance sigma² along its normal n_j and sigma² + tau² across it (tau: how far the surface
// a target point stands for extends sideways), plus a uniform outlier term. E-step: the
// responsibilities w_ij of source point i's neighbours j (normalised over them and the outlier
// term); M-step: the rigid motion minimising sum w_ij e_ijᵀ M_j e_ij with
// M_j = n nᵀ / sigma² + (I − n nᵀ) / (sigma² + tau²), linearised in the rotation (one Gauss–Newton
// step per ICP iteration). tau = 0 is soft point-to-point (EM-ICP / rigid CPD); tau → ∞ is soft
// point-to-plane. Hard nearest-neighbour correspondences bias the minimum when the noise is
// comparable to the point spacing and the curvature (docs/alignment.md); averaging over the
// responsibilities removes most of that bias.
class SurfaceMixtureEstimation
    : public pcl::registration::TransformationEstimation<PointT, PointT, double> {
 public:
  SurfaceMixtureEstimation(double sigma2, double tau2, double outlier)
      : sigma2_(sigma2), tau2_(tau2), outlier_(outlier) {}

  void estimateRigidTransformation(const pcl::PointCloud<PointT>& src,
                                   const pcl::PointCloud<PointT>& tgt,
                                   const pcl::Correspondences& corr,
                                   Matrix4& transform) const override {
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    const double a = 1.0 / sigma2_, b = 1.0 / (sigma2_ + tau2_);
    double m[64];
    int points = 0;
    for (std::size_t first = 0; first < corr.size();) {
      std::size_t last = first;
      while (last < corr.size() && corr[last].index_query == corr[first].index_query &&
             last - first < 64)
        ++last;
      const Eigen::Vector3d x = src[corr[first].index_query].getVector3fMap().cast<double>();
      double total = outlier_;
      for (std::size_t c = first; c < last; ++c) {
        const PointT& t = tgt[corr[c].index_match];
        const Eigen::Vector3d e = x - t.getVector3fMap().cast<double>();
        const double rn = e.dot(t.getNormalVector3fMap().cast<double>());
        m[c - first] = std::exp(-0.5 * (a * rn * rn + b * (e.squaredNorm() - rn * rn)));
        total += m[c - first];
      }
      // e_ij(δ) ≈ e_ij + J δ with J = [−[x]×, I] (the same for all neighbours of x), and
      // Jᵀ M_j J = b JᵀJ + (a − b) J_n J_nᵀ with J_n = Jᵀ n = (x × n, n): the isotropic part is
      // summed once per source point.
      double sum_w = 0.0;
      Eigen::Vector3d sum_we = Eigen::Vector3d::Zero();
      for (std::size_t c = first; c < last; ++c) {
        const double w = m[c - first] / total;
        if (w < 1e-6) continue;
        const PointT& t = tgt[corr[c].index_match];
        const Eigen::Vector3d n = t.getNormalVector3fMap().cast<double>();
        const Eigen::Vector3d e = x - t.getVector3fMap().cast<double>();
        Eigen::Matrix<double, 6, 1> jn;
        jn << x.cross(n), n;
        H.noalias() += (w * (a - b)) * jn * jn.transpose();
        g.noalias() += (w * (a - b) * n.dot(e)) * jn;
        sum_w += w;
        sum_we += w * e;
      }
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() << 0, x.z(), -x.y(), -x.z(), 0, x.x(), x.y(), -x.x(), 0;
      J.rightCols<3>().setIdentity();
      H.noalias() += (b * sum_w) * J.transpose() * J;
      g.noalias() += b * J.transpose() * sum_we;
      ++points;
      first = last;
    }
    transform.setIdentity();
    if (points < 6) return;
    const Eigen::Matrix<double, 6, 1> d = -H.ldlt().solve(g);
    if (!d.allFinite()) return;
    const double angle = d.head<3>().norm();
    if (angle > 0)
      transform.block<3, 3>(0, 0) =
          Eigen::AngleAxisd(angle, d.head<3>() / angle).toRotationMatrix();
    transform.block<3, 1>(0, 3) = d.tail<3>();
  }
  // ICP only calls the overload with correspondences; the others pair points by index.
  void estimateRigidTransformation(const pcl::PointCloud<PointT>& src,
                                   const pcl::PointCloud<PointT>& tgt,
                                   Matrix4& transform) const override {
    pcl::Correspondences corr;
    for (std::size_t i = 0; i < std::min(src.size(), tgt.size()); ++i)
      corr.emplace_back(static_cast<int>(i), static_cast<int>(i), 0.0f);
    estimateRigidTransformation(src, tgt, corr, transform);
  }
  void estimateRigidTransformation(const pcl::PointCloud<PointT>& src, const pcl::Indices& isrc,
                                   const pcl::PointCloud<PointT>& tgt,
                                   Matrix4& transform) const override {
    pcl::Correspondences corr;
    for (std::size_t k = 0; k < std::min(isrc.size(), tgt.size()); ++k)
      corr.emplace_back(isrc[k], static_cast<int>(k), 0.0f);
    estimateRigidTransformation(src, tgt, corr, transform);
  }
  void estimateRigidTransformation(const pcl::PointCloud<PointT>& src, const pcl::Indices& isrc,
                                   const pcl::PointCloud<PointT>& tgt, const pcl::Indices& itgt,
                                   Matrix4& transform) const override {
    pcl::Correspondences corr;
    for (std::size_t k = 0; k < std::min(isrc.size(), itgt.size()); ++k)
      corr.emplace_back(isrc[k], itgt[k], 0.0f);
    estimateRigidTransformation(src, tgt, corr, transform);
  }

 private:
  double sigma2_, tau2_, outlier_;
};

struct QuietPcl {
  QuietPcl() { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }
};

}  // namespace

IcpResult icp_align(const PointSet& source, const PointSet& target, const IcpOptions& options,
                    const Eigen::Matrix4d& initial) {
  static const QuietPcl quiet;  // PCL prints "not enough correspondences" itself; we report it
  check_point_set(source, "source");
  check_point_set(target, "target");
  const auto start = std::chrono::steady_clock::now();
  const double diag = bbox_diagonal(target.V);
  const Eigen::Vector3d cs = source.V.colwise().mean().transpose(),
                        ct = target.V.colwise().mean().transpose();
  const Eigen::MatrixX3d target_normals = target.N.rows() ? target.N : estimate_normals(target.V);

  const std::vector<int> rows = subset_rows(source.size(), options.max_source_points);
  const Cloud::Ptr source_cloud = make_cloud(source.V, source.N, cs, rows);
  const Cloud::Ptr target_cloud = make_cloud(target.V, target_normals, ct, all_rows(target.size()));

  // current maps centred source (x - cs) to centred target (y - ct).
  Eigen::Matrix4d current = translation(-ct) * initial * translation(cs);
  std::vector<Eigen::Vector3f> target_points(target_cloud->size());
  for (std::size_t i = 0; i < target_cloud->size(); ++i)
    target_points[i] = (*target_cloud)[i].getVector3fMap();
  const auto tree = std::make_shared<const detail::KdTree3>(std::move(target_points));
  Icp icp;
  icp.setInputTarget(target_cloud);
  // PCL's own target tree is never built (force_no_recompute): correspondences come from `tree`.
  icp.setSearchMethodTarget(pcl::make_shared<pcl::search::KdTree<PointT>>(), true);
  icp.setCorrespondenceEstimation(pcl::make_shared<TreeCorrespondences>(tree));
  icp.setMaximumIterations(options.max_iterations);
  icp.setTransformationEpsilon(std::pow(options.translation_epsilon * diag, 2));
  icp.setTransformationRotationEpsilon(std::cos(options.rotation_epsilon_deg * M_PI / 180.0));
  icp.setEuclideanFitnessEpsilon(options.fitness_epsilon);
  if (options.median_factor > 0) {
    auto rejector = pcl::make_shared<pcl::registration::CorrespondenceRejectorMedianDistance>();
    rejector->setMedianFactor(options.median_factor);
    icp.addCorrespondenceRejector(rejector);
  }
  using Rigid = pcl::registration::TransformationEstimationPointToPlaneLLS<PointT, PointT, double>;
  using Svd = pcl::registration::TransformationEstimationSVD<PointT, PointT, double>;
  using SvdScale = pcl::registration::TransformationEstimationSVDScale<PointT, PointT, double>;
  const auto rigid =
      options.point_to_plane
          ? pcl::registration::TransformationEstimation<PointT, PointT, double>::Ptr(new Rigid)
          : pcl::registration::TransformationEstimation<PointT, PointT, double>::Ptr(new Svd);

  // Stages of the schedule; with scale, every stage estimates scale by SVD, and one more stage at
  // the finest distance refines rigidly (point-to-plane when asked) with the scale kept.
  struct Stage {
    double distance;
    bool scale;
  };
  std::vector<Stage> stages;
  for (double d : options.correspondence_distances) stages.push_back({d, options.with_scale});
  if (options.with_scale && options.point_to_plane && !stages.empty())
    stages.push_back({options.correspondence_distances.back(), false});

  // Coarse stages (every distance above the finest) only have to bring the source into the
  // basin of the finest one: they stop at looser thresholds.
  const double finest =
      options.correspondence_distances.empty() ? 0.0 : options.correspondence_distances.back();
  const double loose = std::max(1.0, options.coarse_epsilon_factor);

  IcpResult result;
  Cloud moved;
  for (const Stage& stage : stages) {
    const bool coarse = stage.distance > finest;
    // With a soft stage to follow, the finest hard stage only has to get close as well.
    const bool strict = !coarse && options.soft_neighbours <= 0;
    icp.setTransformationEpsilon(
        std::pow((strict ? 1.0 : loose) * options.translation_epsilon * diag, 2));
    icp.setTransformationRotationEpsilon(
        std::cos((strict ? 1.0 : loose) * options.rotation_epsilon_deg * M_PI / 180.0));
    icp.setEuclideanFitnessEpsilon((strict ? 1.0 : loose) * options.fitness_epsilon);
    Cloud::Ptr staged(new Cloud);
    pcl::transformPointCloudWithNormals(*source_cloud, *staged, current);
    icp.setInputSource(staged);
    if (stage.scale) {
      icp.setTransformationEstimation(pcl::make_shared<SvdScale>());
    } else {
      icp.setTransformationEstimation(rigid);
    }
    icp.setMaxCorrespondenceDistance(stage.distance * diag);
    icp.align(moved);
    result.iterations += icp.iterations();
    const ConvergenceState state = icp.getConvergeCriteria()->getConvergenceState();
    using Criteria = pcl::registration::DefaultConvergenceCriteria<double>;
    result.converged = state == Criteria::CONVERGENCE_CRITERIA_TRANSFORM ||
                       state == Criteria::CONVERGENCE_CRITERIA_ABS_MSE ||
                       state == Criteria::CONVERGENCE_CRITERIA_REL_MSE;
    if (state == Criteria::CONVERGENCE_CRITERIA_NO_CORRESPONDENCES) break;
    current = icp.getFinalTransformation() * current;
  }
  if (options.soft_neighbours > 0 && result.iterations > 0 && !stages.empty()) {
    // Noise along the normal, from the point-to-plane residuals of the last hard stage (robust
    // spread: 1.4826 × median absolute residual), and the target's point spacing.
    const double last = stages.back().distance * diag;
    Cloud::Ptr staged(new Cloud);
    pcl::transformPointCloudWithNormals(*source_cloud, *staged, current);
    std::vector<double> residuals;
    residuals.reserve(staged->size());
    for (const PointT& p : *staged) {
      float d2 = 0.0f;
      const int j = tree->nearest(p.getVector3fMap(), static_cast<float>(last * last), &d2);
      if (j >= 0)
        residuals.push_back(std::abs((p.getVector3fMap() - (*target_cloud)[j].getVector3fMap())
                                         .dot((*target_cloud)[j].getNormalVector3fMap())));
    }
    std::vector<double> spacing;
    const int step = std::max<int>(1, static_cast<int>(target_cloud->size()) / 1000);
    for (std::size_t i = 0; i < target_cloud->size(); i += step) {
      int index[2];
      float d2[2];
      if (tree->nearest_k((*target_cloud)[i].getVector3fMap(), 2, std::numeric_limits<float>::max(),
                          index, d2) == 2)
        spacing.push_back(std::sqrt(d2[1]));
    }
    auto median = [](std::vector<double>& v) {
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    };
    if (residuals.size() >= 10 && !spacing.empty()) {
      const double sigma = std::max(1.4826 * median(residuals), 1e-5 * diag);
      const double tau = options.soft_tangential * median(spacing);
      icp.clearCorrespondenceRejectors();
      icp.setCorrespondenceEstimation(
          pcl::make_shared<TreeNeighbourCorrespondences>(tree, options.soft_neighbours));
      icp.setTransformationEstimation(pcl::make_shared<SurfaceMixtureEstimation>(
          sigma * sigma, tau * tau, std::exp(-0.5 * 9.0)));
      icp.setMaxCorrespondenceDistance(std::min(last, 3.0 * std::sqrt(sigma * sigma + tau * tau)));
      // The mean squared distance to the k neighbours hardly changes as the pose improves:
      // only the transform step stops this stage (strict thresholds).
      icp.setTransformationEpsilon(std::pow(options.translation_epsilon * diag, 2));
      icp.setTransformationRotationEpsilon(std::cos(options.rotation_epsilon_deg * M_PI / 180.0));
      icp.setEuclideanFitnessEpsilon(-1.0);
      icp.setInputSource(staged);
      icp.align(moved);
      result.iterations += icp.iterations();
      const ConvergenceState state = icp.getConvergeCriteria()->getConvergenceState();
      using Criteria = pcl::registration::DefaultConvergenceCriteria<double>;
      if (state != Criteria::CONVERGENCE_CRITERIA_NO_CORRESPONDENCES) {
        current = icp.getFinalTransformation() * current;
        result.converged = state == Criteria::CONVERGENCE_CRITERIA_TRANSFORM ||
                           state == Criteria::CONVERGENCE_CRITERIA_ABS_MSE ||
                           state == Criteria::CONVERGENCE_CRITERIA_REL_MSE;
      }
    }
  }
  result.transform = translation(ct) * current * translation(-cs);
  result.scale = std::cbrt(result.transform.block<3, 3>(0, 0).determinant());
  // Fitness and inlier RMSE on the source points that drove ICP (a random subset estimates them as
  // well as all points do, for a quarter of the queries at 10k points), with the same k-d tree.
  Eigen::MatrixX3d driving(rows.size(), 3);
  for (std::size_t k = 0; k < rows.size(); ++k) driving.row(k) = source.V.row(rows[k]);
  const Eigen::MatrixX3d moved_all =
      transform_points(result.transform, driving).rowwise() - ct.transpose();
  const float limit = static_cast<float>(std::pow(options.inlier_distance * diag, 2));
  int inliers = 0;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < moved_all.rows(); ++i) {
    float d2 = 0.0f;
    // nearest() excludes points exactly at the limit; PCL's search included them (measure zero).
    if (tree->nearest(moved_all.row(i).transpose().cast<float>(), limit, &d2) >= 0) {
      ++inliers;
      sum += d2;
    }
  }
  result.fitness = static_cast<double>(inliers) / static_cast<double>(driving.rows());
  result.rmse = inliers ? std::sqrt(sum / inliers) : 0.0;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

struct PointLocator::Impl {
  Eigen::Vector3d centre;
  detail::KdTree3 tree;
};

PointLocator::PointLocator(const Eigen::MatrixX3d& points) : impl_(std::make_unique<Impl>()) {
  impl_->centre = points.rows() ? Eigen::Vector3d(points.colwise().mean().transpose())
                                : Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3f> centred(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    centred[i] = (points.row(i).transpose() - impl_->centre).cast<float>();
  impl_->tree.build(std::move(centred));
}
PointLocator::~PointLocator() = default;
PointLocator::PointLocator(PointLocator&&) noexcept = default;
PointLocator& PointLocator::operator=(PointLocator&&) noexcept = default;
int PointLocator::size() const { return impl_->tree.size(); }

int PointLocator::nearest(const Eigen::Vector3d& p, double* squared_distance) const {
  if (impl_->tree.size() == 0) return -1;
  float d2 = 0.0f;
  const int i = impl_->tree.nearest((p - impl_->centre).cast<float>(),
                                    std::numeric_limits<float>::infinity(), &d2);
  if (squared_distance) *squared_distance = d2;
  return i;
}

Eigen::MatrixX3d estimate_normals(const Eigen::MatrixX3d& V, int k) {
  const Eigen::Vector3d centre = V.colwise().mean().transpose();
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d x = V.row(i).transpose() - centre;
    (*cloud)[i] = pcl::PointXYZ(static_cast<float>(x.x()), static_cast<float>(x.y()),
                                static_cast<float>(x.z()));
  }
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(cloud);
  estimation.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  estimation.setKSearch(std::min<int>(k, static_cast<int>(V.rows())));
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute(normals);
  Eigen::MatrixX3d N(V.rows(), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    Eigen::Vector3d n(normals[i].normal_x, normals[i].normal_y, normals[i].normal_z);
    if (!n.allFinite() || n.norm() == 0) n = Eigen::Vector3d::UnitY();
    if (n.dot(V.row(i).transpose() - centre) < 0) n = -n;  // away from the centroid
    N.row(i) = n.normalized().transpose();
  }
  return N;
}

}  // namespace dresskit::alignment
