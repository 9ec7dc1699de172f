#include <gtest/gtest.h>

#include "dresskit/mesh/isosurface.h"
#include "dresskit/mesh/topology.h"
#include "mesh_fixtures.h"

using namespace dresskit;
using namespace dresskit::mesh;

namespace {
ScalarField sphere(double r, Eigen::Vector3d c = Eigen::Vector3d::Zero()) {
  return [r, c](const Eigen::MatrixX3d& p, Eigen::VectorXd& v) {
    v = (p.rowwise() - c.transpose()).rowwise().norm().array() - r;
  };
}
Eigen::AlignedBox3d box(double h) {
  return {Eigen::Vector3d::Constant(-h), Eigen::Vector3d::Constant(h)};
}
}  // namespace

TEST(MarchingTetrahedra, SphereIsClosedOutwardAndConverges) {
  double previous_error = 1e9;
  for (double h : {0.2, 0.1, 0.05}) {
    const TriangleMesh m = marching_tetrahedra(sphere(1.0), box(1.3), h);
    const TopologyReport t = analyse_topology(m);
    EXPECT_TRUE(t.closed) << h;
    EXPECT_TRUE(t.outward) << h;
    EXPECT_EQ(t.num_components, 1);
    EXPECT_EQ(t.euler_characteristic, 2);
    // Vertices lie on grid edges (up to h√3 long) by linear interpolation: off the sphere by at most
    // about L²/(8R) = 3h²/8.
    const double radius_error = (m.V.rowwise().norm().array() - 1.0).abs().maxCoeff();
    EXPECT_LT(radius_error, 0.375 * h * h) << h;
    const double volume_error = std::abs(t.signed_volume - 4.0 / 3.0 * M_PI);
    EXPECT_LT(volume_error, previous_error / 3.0) << h;  // second order: ~4x per halving
    previous_error = volume_error;
  }
}

TEST(MarchingTetrahedra, ZeroOnGridPointsStaysManifold) {
  // A plane slab whose faces pass exactly through grid points.
  const ScalarField slab = [](const Eigen::MatrixX3d& p, Eigen::VectorXd& v) {
    v = p.col(2).cwiseAbs().array() - 0.5;
  };
  const TriangleMesh m = marching_tetrahedra(slab, box(1.0), 0.25);
  const TopologyReport t = analyse_topology(m);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.num_components, 2);  // two sheets, cut open by the box
}

TEST(MarchingTetrahedra, TwoSpheresGiveTwoComponents) {
  const ScalarField two = [](const Eigen::MatrixX3d& p, Eigen::VectorXd& v) {
    Eigen::VectorXd a, b;
    sphere(0.4, {-0.6, 0, 0})(p, a);
    sphere(0.4, {0.6, 0, 0})(p, b);
    v = a.cwiseMin(b);
  };
  const TopologyReport t = analyse_topology(marching_tetrahedra(two, box(1.2), 0.05));
  EXPECT_EQ(t.num_components, 2);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.outward);
}

TEST(CutMesh, KeepsTheNegativeSideWithExactLineAndSharedVertices) {
  const TriangleMesh g = fixtures::grid(10, 10, 0.1);  // unit square
  Eigen::VectorXd value(g.num_vertices());
  for (int i = 0; i < g.num_vertices(); ++i) value(i) = g.V(i, 0) - 0.55;  // a straight line
  const TriangleMesh cut = cut_mesh(g, value);
  const TopologyReport t = analyse_topology(cut);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.num_boundary_loops, 1);
  EXPECT_NEAR(t.area, 0.55, 1e-12);  // exact: the line is straight
  EXPECT_NEAR(cut.V.col(0).maxCoeff(), 0.55, 1e-12);
  // One new vertex per crossed edge, marked as created: 11 vertical-row edges and 10 diagonals.
  EXPECT_EQ((cut.source_vertex.array() < 0).count(), 21);
}

TEST(ProjectToZeroSet, MovesVerticesOntoASphere) {
  Eigen::MatrixX3d V(3, 3);
  V << 1.2, 0, 0, 0, 0.9, 0, 0.5, 0.5, 0.5;
  const double residual = project_to_zero_set(sphere(1.0), V, 4, 1.0);
  EXPECT_LT(residual, 1e-8);
  EXPECT_NEAR(V.row(2).norm(), 1.0, 1e-8);
  EXPECT_TRUE(V.row(2).normalized().isApprox(Eigen::RowVector3d(1, 1, 1).normalized(), 1e-8));
}
