// Every use of PCL in dresskit::alignment lives in this file (its headers cost ~15 s and ~1 GB to
// compile per translation unit): ICP stages, the k-d tree behind PointLocator, normal estimation.
#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/features/normal_3d.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/registration/correspondence_rejection_median_distance.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation_svd_scale.h>

#include <chrono>
#include <cmath>
#include <numeric>
#include <random>

#include "dresskit/alignment/icp.h"

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
  Icp icp;
  icp.setInputTarget(target_cloud);
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
  // well as all points do, for a quarter of the queries at 10k points), with ICP's target k-d tree.
  const auto tree = icp.getSearchMethodTarget();
  Eigen::MatrixX3d driving(rows.size(), 3);
  for (std::size_t k = 0; k < rows.size(); ++k) driving.row(k) = source.V.row(rows[k]);
  const Eigen::MatrixX3d moved_all =
      transform_points(result.transform, driving).rowwise() - ct.transpose();
  const double limit = std::pow(options.inlier_distance * diag, 2);
  std::vector<int> index(1);
  std::vector<float> d2(1);
  int inliers = 0;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < moved_all.rows(); ++i) {
    PointT p;
    p.x = static_cast<float>(moved_all(i, 0));
    p.y = static_cast<float>(moved_all(i, 1));
    p.z = static_cast<float>(moved_all(i, 2));
    if (tree->nearestKSearch(p, 1, index, d2) > 0 && d2[0] <= limit) {
      ++inliers;
      sum += d2[0];
    }
  }
  result.fitness = static_cast<double>(inliers) / static_cast<double>(driving.rows());
  result.rmse = inliers ? std::sqrt(sum / inliers) : 0.0;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

struct PointLocator::Impl {
  Eigen::Vector3d centre;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  int size = 0;
};

PointLocator::PointLocator(const Eigen::MatrixX3d& points) : impl_(std::make_unique<Impl>()) {
  impl_->size = static_cast<int>(points.rows());
  impl_->centre = points.rows() ? Eigen::Vector3d(points.colwise().mean().transpose())
                                : Eigen::Vector3d::Zero();
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d x = points.row(i).transpose() - impl_->centre;
    (*cloud)[i] = pcl::PointXYZ(static_cast<float>(x.x()), static_cast<float>(x.y()),
                                static_cast<float>(x.z()));
  }
  if (points.rows()) impl_->tree.setInputCloud(cloud);
}
PointLocator::~PointLocator() = default;
PointLocator::PointLocator(PointLocator&&) noexcept = default;
PointLocator& PointLocator::operator=(PointLocator&&) noexcept = default;
int PointLocator::size() const { return impl_->size; }

int PointLocator::nearest(const Eigen::Vector3d& p, double* squared_distance) const {
  if (impl_->size == 0) return -1;
  const Eigen::Vector3d x = p - impl_->centre;
  std::vector<int> index(1);
  std::vector<float> d2(1);
  impl_->tree.nearestKSearch(pcl::PointXYZ(static_cast<float>(x.x()), static_cast<float>(x.y()),
                                           static_cast<float>(x.z())),
                             1, index, d2);
  if (squared_distance) *squared_distance = d2[0];
  return index[0];
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
