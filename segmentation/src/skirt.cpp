#include "dresskit/segmentation/skirt.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace dresskit::segmentation {

SkirtFrame detect_skirt(const MeshGraph& graph, const Eigen::MatrixX3d& V,
                        const Eigen::VectorXd& area, const std::vector<int>& vertices,
                        const AxesEstimate& axes) {
  SkirtFrame f;
  std::vector<char> in(graph.num_vertices, 0);
  for (int v : vertices) in[v] = 1;
  const auto loops = boundary_loops(graph, [&](int v) { return in[v] != 0; });
  if (loops.size() != 2) return f;
  Eigen::Vector3d centre[2];
  double radius[2];
  for (int k = 0; k < 2; ++k) {
    centre[k].setZero();
    for (int v : loops[k]) centre[k] += V.row(v).transpose();
    centre[k] /= static_cast<double>(loops[k].size());
    radius[k] = 0;
    for (int v : loops[k]) radius[k] += (V.row(v).transpose() - centre[k]).norm();
    radius[k] /= static_cast<double>(loops[k].size());
  }
  // The waist: the upper loop when up is known, else the narrower one.
  const int waist = axes.up_given ? (centre[0].dot(axes.up) >= centre[1].dot(axes.up) ? 0 : 1)
                                  : (radius[0] <= radius[1] ? 0 : 1);
  const int hem = 1 - waist;
  Eigen::Vector3d axis = centre[waist] - centre[hem];
  if (!(axis.norm() > 0)) return f;
  axis.normalize();
  if (axes.up_given && axis.dot(axes.up) < std::cos(M_PI / 6)) return f;
  if (radius[hem] < radius[waist]) return f;

  // Forward: the axes' own when it is across the skirt's axis (so that the skirt's left is the
  // rest of the mesh's left), else the skirt's depth.
  Eigen::Vector3d forward = axes.forward;
  if (std::abs(forward.dot(axis)) > std::cos(M_PI / 4)) {
    // The skirt's depth: the direction of least spread perpendicular to its axis.
    double total = 0;
    for (int v : vertices) total += area(v);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int v : vertices)
      mean += (total > 0 ? area(v) / total : 1.0 / vertices.size()) * V.row(v).transpose();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - axis * axis.transpose();
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (int v : vertices) {
      const Eigen::Vector3d d = P * (V.row(v).transpose() - mean);
      cov += (total > 0 ? area(v) : 1.0) * d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // ascending; col 0 ≈ axis
    forward = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3 && forward.norm() == 0; ++k)
      if (std::abs(eig.eigenvectors().col(k).dot(axis)) < 0.5) forward = eig.eigenvectors().col(k);
    if (forward.z() < 0) forward = -forward;
  }
  forward -= forward.dot(axis) * axis;
  if (forward.norm() < 1e-9) forward = axis.unitOrthogonal();
  forward.normalize();
  f.is_skirt = true;
  f.axis = axis;
  f.left = axis.cross(forward).normalized();
  f.waist_centre = centre[waist];
  f.hem_centre = centre[hem];
  f.waist_radius = radius[waist];
  f.hem_radius = radius[hem];
  return f;
}

void split_skirt(const MeshGraph& graph, const Eigen::MatrixX3d& V, const Eigen::VectorXd& area,
                 const std::vector<int>& vertices, SkirtFrame& frame, Eigen::VectorXi& labels) {
  const double length = (frame.waist_centre - frame.hem_centre).dot(frame.axis);
  std::vector<char> in(graph.num_vertices, 0);
  for (int v : vertices) in[v] = 1;
  double edge_sum = 0;
  int edges = 0;
  for (int e = 0; e < graph.num_edges(); ++e)
    if (in[graph.from(e)] && graph.faces(e) > 0) edge_sum += graph.length(e), ++edges;
  const double mean_edge = edges ? edge_sum / edges : length;
  const int bins = std::clamp(static_cast<int>(std::lround(length / (2 * mean_edge))), 6, 50);
  const double dh = length / bins;
  auto height = [&](int v) { return (V.row(v).transpose() - frame.hem_centre).dot(frame.axis); };
  auto bin_of = [&](int v) {
    return std::clamp(static_cast<int>(std::floor((length - height(v)) / dh)), 0, bins - 1);
  };
  // Radius profile, slice 0 at the waist: area-weighted mean distance from the slice's centroid,
  // perpendicular to the axis.
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(bins), radius = Eigen::VectorXd::Zero(bins);
  Eigen::MatrixX3d centroid = Eigen::MatrixX3d::Zero(bins, 3);
  auto flat = [&](int v) {
    const Eigen::Vector3d d = V.row(v).transpose() - frame.hem_centre;
    return Eigen::Vector3d(d - d.dot(frame.axis) * frame.axis);
  };
  for (int v : vertices) {
    const int b = bin_of(v);
    weight(b) += area(v);
    centroid.row(b) += area(v) * flat(v).transpose();
  }
  for (int b = 0; b < bins; ++b)
    if (weight(b) > 0) centroid.row(b) /= weight(b);
  for (int v : vertices) {
    const int b = bin_of(v);
    radius(b) += area(v) * (flat(v) - centroid.row(b).transpose()).norm();
  }
  for (int b = 0; b < bins; ++b)
    if (weight(b) > 0) radius(b) /= weight(b);
  // Kneedle: the slice farthest above the chord from the waist slice to the hem slice (by more
  // than 1 % of the waist's radius, so that a plain tube's noise picks none).
  int knee = -1;
  double best = 0.01 * frame.waist_radius;
  for (int b = 1; b + 1 < bins; ++b) {
    if (!(weight(b) > 0)) continue;
    const double chord = radius(0) + (radius(bins - 1) - radius(0)) * b / (bins - 1);
    if (radius(b) - chord > best) best = radius(b) - chord, knee = b;
  }
  frame.band_height = knee >= 0 ? length - (knee + 0.5) * dh : length - dh;
  frame.band_fraction = (length - frame.band_height) / length;
  for (int v : vertices) {
    const double side = flat(v).dot(frame.left);
    if (height(v) >= frame.band_height || std::abs(side) < 0.05 * mean_edge)
      labels(v) = 0;
    else
      labels(v) = side > 0 ? 1 : 2;
  }
}

}  // namespace dresskit::segmentation
