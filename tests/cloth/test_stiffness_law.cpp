#include <gtest/gtest.h>

#include <random>
#include <Eigen/Eigenvalues>

#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/spring_kernels.h"
#include "dresskit/cloth/stiffness_law.h"

using namespace dresskit;
using namespace dresskit::cloth;

namespace {
const StiffnessLaw kLaw = StiffnessLaw::fitted(100.0, 400.0, kKneeStrain);
// Lengths (L0 = 0.5) in compression, inside each of the four segments and far past the knee; none
// sits on a knot, where the derivative jumps.
const double kL0 = 0.5;
const double kLengths[] = {0.3, 0.49, 0.51, 0.52, 0.54, 0.565, 0.57, 0.6, 0.9};
}  // namespace

TEST(StiffnessLaw, KnotsAndStiffeningPastTheKnee) {
  EXPECT_DOUBLE_EQ(kLaw.k(0.0), 100.0);
  EXPECT_DOUBLE_EQ(kLaw.k(-0.3), 100.0);
  EXPECT_NEAR(kLaw.k(kKneeStrain), 400.0, 1e-9);
  EXPECT_NEAR(kLaw.k(kKneeStrain / 3), 100.0 + 300.0 / 9, 1e-9);
  // Continuous at every knot.
  for (double e : kLaw.knot_strain) EXPECT_NEAR(kLaw.k(e - 1e-12), kLaw.k(e + 1e-12), 1e-6);
  // Convex: each segment's slope is larger than the previous one.
  double previous = 0.0;
  for (double e : {0.01, 0.07, 0.13, 0.3}) {
    EXPECT_GT(kLaw.dk(e), previous) << e;
    previous = kLaw.dk(e);
  }
  // A measured softening is not followed.
  EXPECT_GE(StiffnessLaw::fitted(100.0, 50.0, kKneeStrain).k(0.3), 100.0);
}

TEST(StiffnessLaw, TensionIsTheEnergyDerivativeAndItsDerivativeMatches) {
  for (double L : kLengths) {
    const double h = 1e-6;
    const double fd_tension = (kLaw.energy(L + h, kL0) - kLaw.energy(L - h, kL0)) / (2 * h);
    EXPECT_NEAR(kLaw.tension(L, kL0), fd_tension, 1e-6 * (1 + std::abs(fd_tension))) << L;
    const double fd_stiff = (kLaw.tension(L + h, kL0) - kLaw.tension(L - h, kL0)) / (2 * h);
    EXPECT_NEAR(kLaw.tension_derivative(L, kL0), fd_stiff, 1e-5 * (1 + std::abs(fd_stiff))) << L;
  }
  // A linear law is Hooke's law: E = ½ k ΔL², T = k ΔL.
  const StiffnessLaw hooke = StiffnessLaw::linear(250.0);
  EXPECT_NEAR(hooke.energy(0.6, 0.5), 0.5 * 250.0 * 0.01, 1e-12);
  EXPECT_NEAR(hooke.tension(0.45, 0.5), -250.0 * 0.05, 1e-12);
}

TEST(SpringKernels, ForceIsMinusEnergyGradientAndJacobianIsForceGradient) {
  const Eigen::Vector3d xj(0.1, -0.2, 0.05);
  for (double L : kLengths) {
    const Eigen::Vector3d dir = Eigen::Vector3d(0.3, 0.8, -0.52).normalized();
    const Eigen::Vector3d xi = xj - L * dir;
    const double h = 1e-6;
    Eigen::Vector3d grad;
    Eigen::Matrix3d fd_jac;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d p = xi, m = xi;
      p(k) += h;
      m(k) -= h;
      grad(k) = (spring_energy(kLaw, kL0, p, xj) - spring_energy(kLaw, kL0, m, xj)) / (2 * h);
      fd_jac.col(k) = (spring_force(kLaw, kL0, p, xj) - spring_force(kLaw, kL0, m, xj)) / (2 * h);
    }
    const Eigen::Vector3d f = spring_force(kLaw, kL0, xi, xj);
    EXPECT_LT((f + grad).norm(), 1e-6 * (1 + f.norm())) << L;
    const Eigen::Matrix3d J = spring_jacobian(kLaw, kL0, xi, xj);
    EXPECT_LT((J - fd_jac).norm(), 1e-5 * (1 + J.norm())) << L;
    EXPECT_TRUE(J.isApprox(J.transpose(), 1e-12));
  }
}

TEST(SpringKernels, DynamicStiffnessJacobianAndClampedGeometricTerm) {
  const Eigen::Vector3d xj = Eigen::Vector3d::Zero();
  const double allowed = 1.1 * kL0;
  for (double L : {0.52, 0.6, 0.9}) {  // below and above the allowed length
    const Eigen::Vector3d xi(-L, 0.0, 0.0);
    const double h = 1e-6;
    Eigen::Matrix3d fd;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d p = xi, m = xi;
      p(k) += h;
      m(k) -= h;
      fd.col(k) = (spring_force(kLaw, kL0, p, xj, allowed) - spring_force(kLaw, kL0, m, xj, allowed)) / (2 * h);
    }
    EXPECT_LT((spring_jacobian(kLaw, kL0, xi, xj, allowed) - fd).norm(), 1e-5 * (1 + fd.norm())) << L;
    // k·L/L0 beyond the allowed length.
    const double t = spring_force(kLaw, kL0, xi, xj, allowed).norm();
    const double expected = kLaw.tension(L, kL0) * (L > allowed ? L / kL0 : 1.0);
    EXPECT_NEAR(t, expected, 1e-9 * expected) << L;
  }
  // Compressed: the clamped Jacobian is negative semi-definite, the exact one is not.
  const Eigen::Vector3d xi(-0.3, 0.0, 0.0);
  const Eigen::Matrix3d exact = spring_jacobian(kLaw, kL0, xi, xj);
  const Eigen::Matrix3d clamped = spring_jacobian(kLaw, kL0, xi, xj, 0.0, true);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(exact).eigenvalues().maxCoeff(), 0.0);
  EXPECT_LE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(clamped).eigenvalues().maxCoeff(), 1e-12);
  // Coincident ends: no force, no NaN.
  EXPECT_EQ(spring_force(kLaw, kL0, xj, xj), Eigen::Vector3d::Zero());
  EXPECT_TRUE(spring_jacobian(kLaw, kL0, xj, xj).allFinite());
}

TEST(SpringKernels, DampingOpposesTheRelativeVelocityAlongTheSpring) {
  const Eigen::Vector3d xi(0, 0, 0), xj(2, 0, 0);
  const Eigen::Vector3d f = spring_damping_force(3.0, xi, xj, Eigen::Vector3d(1, 5, 0), Eigen::Vector3d(-1, 0, 7));
  EXPECT_TRUE(f.isApprox(Eigen::Vector3d(-6.0, 0, 0)));
}

TEST(StiffnessLaw, InlinedFittedKMatchesTheLaw) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> stiffness(1.0, 500.0), strain(-0.2, 0.5);
  for (int trial = 0; trial < 2000; ++trial) {
    const double k0 = stiffness(rng), kk = stiffness(rng), e = strain(rng);  // kk < k0 half the time
    const StiffnessLaw law = StiffnessLaw::fitted(k0, kk, kKneeStrain);
    EXPECT_NEAR(fitted_k(k0, kk, kKneeStrain, e), law.k(e), 1e-12 * law.k(e)) << k0 << " " << kk << " " << e;
  }
  // At the knots themselves, where the segment changes.
  for (int s = 0; s <= 4; ++s) {
    const double e = s * kKneeStrain / 3.0;
    const StiffnessLaw law = StiffnessLaw::fitted(10.0, 40.0, kKneeStrain);
    EXPECT_NEAR(fitted_k(10.0, 40.0, kKneeStrain, e), law.k(e), 1e-12 * law.k(e)) << s;
  }
}
