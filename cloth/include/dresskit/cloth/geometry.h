#pragma once
// Pure geometric kernels for collisions: closest points on triangles and segments, and the exact
// segment–triangle crossing test behind the intersection counts. No state, no allocation.
#include <Eigen/Core>

namespace dresskit {

/// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection §5.1.5), with its
/// barycentric coordinates in bary (u, v, w: q = u a + v b + w c) if bary is not null.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          Eigen::Vector3d* bary = nullptr);

/// Closest points of segments p0–p1 and q0–q1: parameters s, t in [0, 1] (Ericson §5.1.9); returns
/// the squared distance.
double closest_points_of_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, double* s, double* t);

/// True when segment p–q crosses triangle (a, b, c) at a point strictly inside both (a touch at an
/// end or on an edge counts as no crossing). Orientation signs of the five tetrahedra.
bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace dresskit
