#pragma once
// Rigid (or similarity) registration of two point sets with ICP, and global placement by several
// candidate orientations. Public types speak Eigen; PCL stays inside src/icp_pcl.cpp.
// Method and choices: docs/alignment.md.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace dresskit::alignment {

/// Points with optional unit normals, in metres.
struct PointSet {
  Eigen::MatrixX3d V;  ///< #P×3 positions [m]
  Eigen::MatrixX3d N;  ///< #P×3 unit normals, or empty (then estimated from neighbours when needed)
  int size() const { return static_cast<int>(V.rows()); }
};

/// Throws InputError("<what>: <problem>") for a point set that cannot be registered: fewer than
/// min_points points, a non-finite coordinate or normal, all points (nearly) identical, or all
/// points on one line (the rotation about that line is undetermined).
void check_point_set(const PointSet& points, const std::string& what, int min_points = 10);

/// Bounding-box diagonal [m] of the points (0 for an empty set).
double bbox_diagonal(const Eigen::MatrixX3d& V);

/// Applies a 4×4 similarity transform to every row of V.
Eigen::MatrixX3d transform_points(const Eigen::Matrix4d& T, const Eigen::MatrixX3d& V);
/// Rotates normals by the rotation part of T (scale removed).
Eigen::MatrixX3d transform_normals(const Eigen::Matrix4d& T, const Eigen::MatrixX3d& N);

/// ICP settings. Distances are fractions of the target's bounding-box diagonal, so one set of
/// defaults works for a 10 cm sleeve and a 2 m body in any unit.
struct IcpOptions {
  /// Coarse-to-fine schedule of maximum correspondence distances [fraction of the target's
  /// bounding-box diagonal]; one PCL ICP run per entry, each starting where the previous stopped.
  std::vector<double> correspondence_distances = {0.2, 0.06, 0.02};
  int max_iterations = 40;             ///< per stage of the schedule
  double translation_epsilon = 1e-5;   ///< stop when a step moves less [fraction of diagonal]
  double rotation_epsilon_deg = 1e-2;  ///< ... and rotates less [degrees]
  double fitness_epsilon = 1e-5;       ///< or the mean squared error changes less [relative]
  /// Outlier rejection: correspondences farther than this many times the median distance are
  /// dropped (on top of the stage's maximum distance). 0 disables it.
  double median_factor = 3.0;
  bool point_to_plane = true;  ///< point-to-plane with target normals; false = point-to-point
  /// Similarity transform (uniform scale) instead of a rigid one: point-to-point stages with an SVD
  /// that estimates scale (Umeyama), then the point-to-plane stages with the scale kept.
  bool with_scale = false;
  /// At most this many source points drive ICP and its fitness and RMSE (a fixed-seed random
  /// subset); 0 = all. More points average the noise down but cost time.
  int max_source_points = 2500;
  /// The coarse stages (every distance of the schedule above the finest) stop at thresholds this
  /// many times looser than the ones above: they only have to reach the basin of the finest stage.
  /// With a soft stage, the finest hard stage is loose too, and the soft stage stops at the
  /// thresholds above.
  double coarse_epsilon_factor = 10.0;
  /// Inlier threshold for the reported fitness and RMSE [fraction of the target's diagonal].
  double inlier_distance = 0.02;
  /// Final soft-assignment stage after the schedule (EM against a mixture of flattened Gaussians
  /// on the target points, docs/alignment.md): this many nearest target points share each
  /// source point by their likelihood; 0 = no soft stage (plain hard-correspondence ICP).
  int soft_neighbours = 8;
  /// Sideways spread tau of a target point's Gaussian in that stage [multiple of the median
  /// target point spacing]; the spread along the normal is the noise, measured from the residuals
  /// of the last hard stage.
  double soft_tangential = 2.0;
};

/// What one registration did.
struct IcpResult {
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  ///< maps source into target's frame [m]
  double scale = 1.0;      ///< the uniform scale in transform (1 for rigid)
  double fitness = 0.0;    ///< fraction of source points with a target point within inlier_distance
  double rmse = 0.0;       ///< RMS distance of those inliers to their nearest target point [m]
  int iterations = 0;      ///< ICP iterations over all stages
  bool converged = false;  ///< the last stage met a convergence criterion (not just max iterations)
  double seconds = 0.0;    ///< wall time
};

/// Registers source onto target starting from `initial` (source → target). Both are centred on the
/// target's centroid before PCL sees them (single precision far from the origin loses millimetres).
/// Target normals are estimated from 12 neighbours when target.N is empty. Throws InputError (via
/// check_point_set) for unusable inputs.
IcpResult icp_align(const PointSet& source, const PointSet& target, const IcpOptions& options = {},
                    const Eigen::Matrix4d& initial = Eigen::Matrix4d::Identity());

/// Fitness (fraction within inlier_distance [m]) and inlier RMSE [m] of source mapped by T onto
/// target.
struct FitScore {
  double fitness = 0.0, rmse = 0.0;
};
FitScore score_fit(const PointSet& source, const PointSet& target, const Eigen::Matrix4d& T,
                   double inlier_distance);

/// Global placement: the source's principal axes are matched to the target's in every candidate
/// orientation, each candidate is refined briefly by ICP and scored, and the best is refined fully.
struct GlobalOptions {
  IcpOptions icp;  ///< the final refinement
  /// 24 = every proper axis permutation with sign flips of the PCA frame (covers any rotation when
  /// the principal axes are distinct); 1 = the PCA frame as it is; 0 = start from the identity.
  int candidates = 24;
  int brief_iterations = 8;        ///< ICP iterations per stage when refining a candidate
  int brief_source_points = 1500;  ///< source subset for the candidates [points]
  bool with_scale = false;  ///< also estimate a uniform scale (initial guess: RMS radius ratio)
};

struct CandidateScore {
  Eigen::Matrix4d start, refined;
  double fitness = 0.0, rmse = 0.0;
};

struct GlobalResult {
  IcpResult result;  ///< the final refinement of the best candidate
  int best_candidate = -1;
  std::vector<CandidateScore> candidates;
  double seconds = 0.0;  ///< total, candidates included
};

GlobalResult global_align(const PointSet& source, const PointSet& target,
                          const GlobalOptions& options = {});

/// Nearest-neighbour queries over a fixed point set (a k-d tree; PCL inside).
class PointLocator {
 public:
  explicit PointLocator(const Eigen::MatrixX3d& points);
  ~PointLocator();
  PointLocator(PointLocator&&) noexcept;
  PointLocator& operator=(PointLocator&&) noexcept;
  /// Index of the nearest point to p and its squared distance [m²].
  int nearest(const Eigen::Vector3d& p, double* squared_distance = nullptr) const;
  int size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Unit normals estimated by PCA over the k nearest neighbours, oriented away from the centroid.
Eigen::MatrixX3d estimate_normals(const Eigen::MatrixX3d& V, int k = 12);

}  // namespace dresskit::alignment
