#pragma once
// An inside test independent of the distance grids and implicit fields under test.
#include <Eigen/Core>
#include <cmath>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::test {

/// Generalised winding number of p with respect to a closed triangle mesh: Σ signed solid angles / 4π
/// (Van Oosterom & Strackee), ≈ ±1 inside, ≈ 0 outside whatever the orientation (the sign says it).
/// Brute force over every triangle.
inline double winding_number(const mesh::TriangleMesh& m, const Eigen::Vector3d& p) {
  double total = 0.0;
  for (int t = 0; t < m.num_faces(); ++t) {
    const Eigen::Vector3d a = m.V.row(m.F(t, 0)).transpose() - p, b = m.V.row(m.F(t, 1)).transpose() - p,
                          c = m.V.row(m.F(t, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(num, den);
  }
  return total / (4.0 * M_PI);
}

}  // namespace dresskit::test
