// Implicit (backward) Euler with one linearised solve per step (Baraff & Witkin 1998).
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/cloth/spring_kernels.h"
#include "cpu_clock.h"
#include "simulator_internal.h"


namespace dresskit::cloth {

using detail::add_block;
using detail::add_spring_blocks;
using detail::row;

// Linearised backward Euler (Baraff & Witkin 1998): (M + h D + h² K) Δv = h (f0 − h K v0),
// with K = −∂f/∂x (compressed springs' transverse terms clamped, so the system is SPD) and
// D = −∂f/∂v. Pinned rows and columns are replaced by the identity (Δv = 0).
void ClothSimulator::step_implicit(StepResult& r) {
  const double h = dt_;
  const int n = static_cast<int>(x_.rows());
  Eigen::VectorXd Kv;
  const auto start = ThreadCpuClock::now();
  assemble_system(true, &Kv);
  const Eigen::MatrixX3d f0 = forces();
  r.force_seconds = std::chrono::duration<double>(ThreadCpuClock::now() - start).count();
  Eigen::VectorXd rhs(3 * n);
  for (int i = 0; i < n; ++i) {
    rhs.segment<3>(3 * i) = pinned_[i] ? Eigen::Vector3d::Zero()
                                       : Eigen::Vector3d(h * (row(f0, i) - h * Kv.segment<3>(3 * i)));
  }
  Eigen::VectorXd dv;
  if (previous_dv_.size() != rhs.size()) previous_dv_ = Eigen::VectorXd::Zero(rhs.size());
  if (!solve_system(rhs, previous_dv_, dv, r)) return;
  previous_dv_ = dv;  // consecutive steps change little: the next solve starts here
  for (int i = 0; i < n; ++i) {
    if (pinned_[i]) continue;
    v_.row(i) += dv.segment<3>(3 * i).transpose();
    x_.row(i) += h * v_.row(i);
  }
}

}  // namespace dresskit::cloth
