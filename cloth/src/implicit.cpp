// Implicit (backward) Euler with one linearised solve per step (Baraff & Witkin 1998).
#include <chrono>

#include "cpu_clock.h"
#include "integrator.h"
#include "linear_system.h"
#include "simulator_internal.h"

namespace dresskit::cloth {

using detail::row;

// Linearised backward Euler (Baraff & Witkin 1998): (M + h D + h² K) Δv = h (f0 − h K v0),
// with K = −∂f/∂x (compressed springs' transverse terms clamped, so the system is SPD) and
// D = −∂f/∂v. Pinned rows and columns are replaced by the identity (Δv = 0).
class ImplicitEuler final : public TimeIntegrator {
 public:
  void step(ClothSimulator& sim, StepResult& r) override;

 private:
  SystemMatrix system_;
  Eigen::VectorXd previous_dv_;  ///< warm start for conjugate gradient
};

void ImplicitEuler::step(ClothSimulator& sim, StepResult& r) {
  const double h = sim.dt_;
  const int n = static_cast<int>(sim.x_.rows());
  Eigen::VectorXd Kv;
  const auto start = ThreadCpuClock::now();
  system_.assemble(sim, true, &Kv);
  const Eigen::MatrixX3d f0 = sim.forces();
  r.force_seconds = std::chrono::duration<double>(ThreadCpuClock::now() - start).count();
  Eigen::VectorXd rhs(3 * n);
  for (int i = 0; i < n; ++i) {
    rhs.segment<3>(3 * i) = sim.pinned_[i] ? Eigen::Vector3d::Zero()
                                       : Eigen::Vector3d(h * (row(f0, i) - h * Kv.segment<3>(3 * i)));
  }
  Eigen::VectorXd dv;
  if (previous_dv_.size() != rhs.size()) previous_dv_ = Eigen::VectorXd::Zero(rhs.size());
  if (!system_.solve(sim, rhs, previous_dv_, dv, r)) return;
  previous_dv_ = dv;  // consecutive steps change little: the next solve starts here
  for (int i = 0; i < n; ++i) {
    if (sim.pinned_[i]) continue;
    sim.v_.row(i) += dv.segment<3>(3 * i).transpose();
    sim.x_.row(i) += h * sim.v_.row(i);
  }
}

std::unique_ptr<TimeIntegrator> make_implicit_euler() { return std::make_unique<ImplicitEuler>(); }

}  // namespace dresskit::cloth
