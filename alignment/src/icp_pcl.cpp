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

namespace dresskit {
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
    for (std::size_t i = 0; i < input_->size(); ++i) {
      const PointT& p = (*input_)[i];
      float d2 = 0.0f;
      const int j =
          tree_3_->nearest(Eigen::Vector3f(p.x, p.y, p.z), static_cast<float>(limit), &d2);
      if (j >= 0) out.emplace_back(static_cast<int>(i), j, d2);
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

  IcpResult result;
  Cloud moved;
  for (const Stage& stage : stages) {
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

}  // namespace dresskit
