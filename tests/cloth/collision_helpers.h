#pragma once
// Independent references for the collision tests: a brute-force generalised winding number (inside
// test that shares nothing with the distance grid's ray parity), a brute-force closest distance, and
// a sphere mesh.
#include <Eigen/Geometry>
#include <cmath>

#include "dresskit/mesh/isosurface.h"
#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::test {

/// Σ solid angles / 4π (Van Oosterom & Strackee): ≈ ±1 inside a closed surface, ≈ 0 outside, whatever
/// the orientation (the sign says it). Brute force over every triangle.
inline double winding_number(const TriangleMesh& m, const Eigen::Vector3d& p) {
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

inline TriangleMesh sphere_mesh(const Eigen::Vector3d& centre, double radius, double spacing) {
  const ScalarField f = [&](const Eigen::MatrixX3d& P, Eigen::VectorXd& v) {
    v = (P.rowwise() - centre.transpose()).rowwise().norm().array() - radius;
  };
  const Eigen::AlignedBox3d box(centre.array() - 1.3 * radius, centre.array() + 1.3 * radius);
  return marching_tetrahedra(f, box, spacing);
}

}  // namespace dresskit::test
