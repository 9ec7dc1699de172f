// As-rigid-as-possible fitting against what it must give exactly: a rigid motion of the rest shape
// is fitted as it is; free vertices take back their rest shape; a stretched sheet held at one end
// returns to its rest lengths.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "dresskit/mesh/arap.h"
#include "dresskit/mesh/errors.h"
#include "mesh_fixtures.h"

using namespace dresskit;
using namespace dresskit::mesh;

namespace {
double largest_edge_strain(const Eigen::MatrixX3d& x, const TriangleMesh& rest) {
  double worst = 0.0;
  for (int f = 0; f < rest.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = rest.F(f, k), b = rest.F(f, (k + 1) % 3);
      worst = std::max(worst, std::abs((x.row(a) - x.row(b)).norm() / (rest.V.row(a) - rest.V.row(b)).norm() - 1.0));
    }
  return worst;
}
}  // namespace

TEST(Arap, FitsARigidMotionOfTheRestShapeExactly) {
  const TriangleMesh m = fixtures::grid(6, 4, 0.1);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::MatrixX3d target = (m.V * R.transpose()).rowwise() + Eigen::RowVector3d(0.3, -1.0, 2.0);
  const Eigen::MatrixX3d x = arap_fit(m.V, m.F, target, Eigen::VectorXd::Ones(m.num_vertices()));
  EXPECT_LT((x - target).cwiseAbs().maxCoeff(), 1e-9);
}

// A flat sheet whose middle vertices were dragged out of its plane and whose edges there were
// stretched: left free, they go back into the plane and to their rest lengths; the held border
// stays where it was.
TEST(Arap, FreeVerticesTakeBackTheRestShape) {
  const TriangleMesh m = fixtures::grid(8, 8, 0.05);
  Eigen::MatrixX3d target = m.V;
  Eigen::VectorXd weight = Eigen::VectorXd::Constant(m.num_vertices(), 100.0);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Eigen::Vector3d p = m.V.row(i).transpose();
    if ((p - Eigen::Vector3d(0.2, 0.2, 0.0)).norm() < 0.11) {
      target(i, 2) = 0.08;  // a tent: its edges stretched by up to 60 %
      weight(i) = 0.0;
    }
  }
  ASSERT_GT(largest_edge_strain(target, m), 0.5);
  const Eigen::MatrixX3d x = arap_fit(m.V, m.F, target, weight);
  EXPECT_LT(largest_edge_strain(x, m), 1e-3);
  EXPECT_LT(x.col(2).cwiseAbs().maxCoeff(), 1e-3);
  for (int i = 0; i < m.num_vertices(); ++i)
    if (weight(i) > 0.0) {
      EXPECT_LT((x.row(i) - m.V.row(i)).norm(), 1e-3) << i;
    }
}

// A strip stretched to twice its length and held only at one end comes back to its rest length
// (local–global rounds converge slowly along a long strip: 1000 of them).
TEST(Arap, AStretchedStripHeldAtOneEndReturnsToItsLength) {
  const TriangleMesh m = fixtures::grid(10, 2, 0.1);
  Eigen::MatrixX3d target = m.V;
  target.col(0) *= 2.0;
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(m.num_vertices());
  for (int i = 0; i < m.num_vertices(); ++i)
    if (m.V(i, 0) < 1e-9) weight(i) = 1.0;
  const Eigen::MatrixX3d x = arap_fit(m.V, m.F, target, weight, {1000});
  EXPECT_LT(largest_edge_strain(x, m), 1e-3);
  EXPECT_NEAR(x.col(0).maxCoeff() - x.col(0).minCoeff(), 1.0, 1e-3);
}

TEST(Arap, RefusesMismatchedInput) {
  const TriangleMesh m = fixtures::grid(2, 2, 0.1);
  EXPECT_THROW(arap_fit(m.V, m.F, m.V.topRows(2), Eigen::VectorXd::Ones(m.num_vertices())), InputError);
  EXPECT_THROW(arap_fit(m.V, m.F, m.V, -Eigen::VectorXd::Ones(m.num_vertices())), InputError);
}
