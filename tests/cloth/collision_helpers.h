#pragma once
// Independent references for the collision tests: the brute-force generalised winding number (an
// inside test that shares nothing with the distance grid's ray parity) and a sphere mesh.
#include <Eigen/Geometry>
#include <cmath>

#include "dresskit/mesh/isosurface.h"
#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/testing/winding_number.h"

namespace dresskit::test {

inline mesh::TriangleMesh sphere_mesh(const Eigen::Vector3d& centre, double radius, double spacing) {
  const mesh::ScalarField f = [&](const Eigen::MatrixX3d& P, Eigen::VectorXd& v) {
    v = (P.rowwise() - centre.transpose()).rowwise().norm().array() - radius;
  };
  const Eigen::AlignedBox3d box(centre.array() - 1.3 * radius, centre.array() + 1.3 * radius);
  return mesh::marching_tetrahedra(f, box, spacing);
}

}  // namespace dresskit::test
