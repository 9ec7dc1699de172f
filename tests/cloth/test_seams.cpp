// Seams: the stitch force against its energy and the assembled stiffness against the force by
// finite differences; chains resampled to match; bad input; welding; a seam drawn shut at the
// closing speed goes around a collider between its two sides.
#include <gtest/gtest.h>

#include <random>

#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/scene.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/testing/errors.h"

using namespace dresskit::cloth;

namespace dresskit {
namespace {

ClothModel loose_particles(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  ClothModel m;
  m.rest_positions.resize(n, 3);
  for (int i = 0; i < n; ++i) m.rest_positions.row(i) << u(rng), u(rng), u(rng);
  m.mass = Eigen::VectorXd::Constant(n, 0.01);
  return m;
}

TEST(Seams, ForceIsMinusTheEnergyGradientAndStiffnessItsJacobian) {
  ClothModel m = loose_particles(6, 3);
  add_seam_pairs(m.seams, {{0, 1}}, 6, {40.0, 1e3});  // within its cap
  add_seam_pairs(m.seams, {{4, 2}}, 6, {40.0, 0.5});  // capped: |F| = 0.5 N
  // A point-to-edge stitch: particle 3 to 30 % along 4–5.
  m.seams.a.push_back(3), m.seams.b0.push_back(4), m.seams.b1.push_back(5),
      m.seams.t.push_back(0.3);
  m.seams.stiffness.push_back(25.0);
  m.seams.max_force.push_back(1e3);
  SimulationOptions o;
  o.gravity.setZero();
  ClothSimulator sim(m, o);
  const Eigen::MatrixX3d x = m.rest_positions;
  Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(6, 3);
  add_seam_forces(m.seams, x, f);
  EXPECT_TRUE(f.allFinite());
  EXPECT_NEAR(f.colwise().sum().norm(), 0.0, 1e-12);  // internal forces: no net force
  ASSERT_GT(40.0 * seam_gap(m.seams, 1, x).norm(), 0.5);
  EXPECT_NEAR(f.row(2).norm(), 0.5, 1e-12);  // the capped stitch pulls with its cap
  const double eps = 1e-6;
  const Eigen::SparseMatrix<double> K = sim.stiffness_matrix(false);
  for (int p = 0; p < 6; ++p)
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixX3d xp = x, xm = x;
      xp(p, c) += eps;
      xm(p, c) -= eps;
      const double dE = (seam_energy(m.seams, xp) - seam_energy(m.seams, xm)) / (2 * eps);
      EXPECT_NEAR(f(p, c), -dE, 1e-6 * (1 + std::abs(dE)));
      Eigen::MatrixX3d fp = Eigen::MatrixX3d::Zero(6, 3), fm = fp;
      add_seam_forces(m.seams, xp, fp);
      add_seam_forces(m.seams, xm, fm);
      const Eigen::MatrixX3d df = (fp - fm) / (2 * eps);  // column 3p + c of ∂f/∂x = −K
      for (int q = 0; q < 6; ++q)
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(-K.coeff(3 * q + d, 3 * p + c), df(q, d), 1e-6);
    }
  // The simulator's total force and energy include the seams.
  EXPECT_NEAR((sim.forces() - f).norm(), 0.0, 1e-12);
  EXPECT_NEAR(sim.elastic_energy(), seam_energy(m.seams, x), 1e-15);
}

TEST(Seams, ChainsOfDifferentResolutionsAreResampledToMatch) {
  // Chain a: 3 particles on x ∈ [0, 1]; chain b: 5 particles on the same line 1 m away.
  ClothModel m;
  m.rest_positions.resize(8, 3);
  for (int k = 0; k < 3; ++k) m.rest_positions.row(k) << 0.5 * k, 0, 0;
  for (int k = 0; k < 5; ++k) m.rest_positions.row(3 + k) << 0.25 * k, 1, 0;
  add_seam_chains(m.seams, m.rest_positions, {0, 1, 2}, {3, 4, 5, 6, 7}, {10.0, 1.0});
  // a's three particles land on b's particles 0, 2, 4; b's 1 and 3 land mid-edge on a.
  ASSERT_EQ(m.seams.size(), 5);
  int to_edges = 0;
  for (int k = 0; k < m.seams.size(); ++k) {
    const Eigen::Vector3d c = seam_gap(m.seams, k, m.rest_positions);
    EXPECT_NEAR(c.x(), 0.0, 1e-12) << k;  // straight across
    EXPECT_NEAR(std::abs(c.y()), 1.0, 1e-12) << k;
    if (m.seams.t[k] != 0.0) {
      ++to_edges;
      EXPECT_NEAR(m.seams.t[k], 0.5, 1e-12);
    }
  }
  EXPECT_EQ(to_edges, 2);
  // A dart: two chains sharing their tip; the tip is not stitched to itself.
  SeamSet dart;
  add_seam_chains(dart, m.rest_positions, {3, 0, 1}, {3, 4, 5}, {10.0, 1.0});
  for (int k = 0; k < dart.size(); ++k)
    EXPECT_FALSE(dart.a[k] == 3 && dart.b0[k] == 3 && dart.t[k] == 0.0);
  EXPECT_EQ(dart.size(), 3);  // the far ends, and each middle particle onto the other chain's edge
}

TEST(Seams, BadStitchesAreRefusedWithAClearMessage) {
  const Eigen::MatrixX3d x = loose_particles(4, 1).rest_positions;
  SeamSet s;
  const auto& message = test::input_error_of;
  EXPECT_NE(message([&] {
              add_seam_pairs(s, {{0, 9}}, 4, {1.0, 1.0});
            }).find("out of range"),
            std::string::npos);
  EXPECT_NE(message([&] {
              add_seam_pairs(s, {{2, 2}}, 4, {1.0, 1.0});
            }).find("itself"),
            std::string::npos);
  EXPECT_NE(message([&] {
              add_seam_chains(s, x, {0}, {1, 2}, {1.0, 1.0});
            }).find("two particles"),
            std::string::npos);
  EXPECT_NE(message([&] {
              add_seam_chains(s, x, {0, 0}, {1, 2}, {1.0, 1.0});
            }).find("zero length"),
            std::string::npos);
  EXPECT_NE(message([&] {
              add_seam_chains(s, x, {0, 1}, {1, 7}, {1.0, 1.0});
            }).find("out of range"),
            std::string::npos);
  EXPECT_EQ(s.size(), 0);
}

TEST(Seams, ClosedStitchesWeldIntoOneVertex) {
  // Two triangles side by side whose facing corners coincide (closed) or not (open).
  Eigen::MatrixX3d x(6, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      1, 0, 0.0004, 2, 0, 0, 1, 1, 0.5;
  Eigen::MatrixX3i F(2, 3);
  F << 0, 1, 2, 3, 4, 5;
  SeamSet s;
  add_seam_pairs(s, {{1, 3}, {2, 5}}, 6, {1.0, 1.0});
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i W;
  std::vector<int> to;
  weld_seams(x, F, s, 0.001, V, W, to);
  EXPECT_EQ(V.rows(), 5);  // 1 and 3 welded (0.4 mm apart), 2 and 5 not (0.5 m)
  EXPECT_EQ(to[1], to[3]);
  EXPECT_NE(to[2], to[5]);
  EXPECT_NEAR(V(to[1], 2), 0.0002, 1e-15);  // at their mean
  EXPECT_EQ(W.rows(), 2);
}

// Two square panels stand either side of a sphere, their top edges stitched pair by pair 5 cm below
// the sphere's top: the straight line between the pairs passes through it. Drawn at the closing
// speed (no stitch force, no gravity), every pair is sewn, over the cap, with nothing inside the
// sphere; without a closing speed, stitches without a force stay open.
TEST(Seams, ClosingSpeedSewsAroundAColliderBetweenTheSides) {
  const double margin = 0.002, top = 0.05;
  const Eigen::Vector3d centre(0.0, -0.15, 0.0);
  const double radius = top - centre.y();  // the cap's top at y = top
  mesh::TriangleMesh front = make_grid({0.2, 0.2}, {11, 11}, {0.0, -0.1, 0.22}, {0, 0, 1});
  const mesh::TriangleMesh back = make_grid({0.2, 0.2}, {11, 11}, {0.0, -0.1, -0.22}, {0, 0, -1});
  const int n = static_cast<int>(front.V.rows());
  front.V.conservativeResize(2 * n, 3);
  front.V.bottomRows(n) = back.V;
  front.F.conservativeResize(front.F.rows() + back.F.rows(), 3);
  front.F.bottomRows(back.F.rows()) = back.F.array() + n;
  ClothModel model = build_cloth(front, fabric_by_name("gray-interlock"));
  // Pair each top-edge particle of the front with the back's at the same x.
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i < n; ++i) {
    if (std::abs(front.V(i, 1)) > 1e-9) continue;
    for (int j = n; j < 2 * n; ++j)
      if (std::abs(front.V(j, 1)) < 1e-9 && std::abs(front.V(j, 0) - front.V(i, 0)) < 1e-9)
        pairs.push_back({i, j});
  }
  ASSERT_EQ(pairs.size(), 11u);
  add_seam_pairs(model.seams, pairs, 2 * n, {default_stitch_stiffness(model.springs), 0.0});
  SimulationOptions o;
  o.gravity.setZero();
  o.air_damping = 2.0;
  o.collision_margin = margin;
  o.colliders.push_back(Collider::sphere(centre, radius, 0.0));
  o.seam_closing_speed = 0.5;
  ClothSimulator sim(model, o);
  for (int step = 0; step < 240; ++step) ASSERT_TRUE(sim.step().ok);
  for (const char sewn : sim.sewn()) EXPECT_TRUE(sewn);
  for (const auto& [a, b] : pairs) {
    const Eigen::Vector3d mid = 0.5 * (sim.positions().row(a) + sim.positions().row(b)).transpose();
    EXPECT_LE((sim.positions().row(a) - sim.positions().row(b)).norm(), 0.002);
    EXPECT_GE((mid - centre).norm(), radius) << mid.transpose();  // over the sphere, outside it
  }
  for (Eigen::Index p = 0; p < sim.positions().rows(); ++p)
    EXPECT_GE((sim.positions().row(p).transpose() - centre).norm(), radius + margin - 1e-3) << p;

  o.seam_closing_speed = 0.0;
  ClothSimulator unsewn(model, o);
  for (int step = 0; step < 240; ++step) ASSERT_TRUE(unsewn.step().ok);
  for (const char sewn : unsewn.sewn()) EXPECT_FALSE(sewn);
}

}  // namespace
}  // namespace dresskit
