// Backward Euler as the minimisation of its incremental potential: Newton steps with line search.
#include <algorithm>
#include <cmath>

#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/spring_kernels.h"
#include "integrator.h"
#include "linear_system.h"
#include "simulator_internal.h"

namespace dresskit::cloth {

using detail::row;

// Backward Euler as minimisation (the stiff-robust integrator): x minimises the incremental potential
//   G(x) = Σ m/(2h²) |x − x0 − h v0|² + Σ c m/(2h) |x − x0 − h w|² + E(x) − Σ m g·x,
// whose stationarity is exactly backward Euler with air damping c and wind w. Newton steps with the
// clamped (SPD) Hessian; h²·Hessian is implicit Euler's matrix. A backtracking line search keeps G
// decreasing, which is what keeps very stiff springs at large steps stable. Spring damping and
// dynamic stiffness have no potential and are not applied by this integrator.
class Newton final : public TimeIntegrator {
 public:
  void step(ClothSimulator& sim, StepResult& r) override;

 private:
  static double incremental_potential(const ClothSimulator& sim, const Eigen::MatrixX3d& x,
                                      const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& v0);
  SystemMatrix system_;
};

double Newton::incremental_potential(const ClothSimulator& sim, const Eigen::MatrixX3d& x,
                                     const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& v0) {
  const double h = sim.dt_;
  const Eigen::Vector3d w = sim.wind_at(sim.time_ + h);
  double g = 0.0;
  for (int i = 0; i < x.rows(); ++i) {
    const double m = sim.model_.mass(i);
    g += m / (2 * h * h) * (row(x, i) - row(x0, i) - h * row(v0, i)).squaredNorm();
    g += sim.options_.air_damping * m / (2 * h) * (row(x, i) - row(x0, i) - h * w).squaredNorm();
    g -= m * sim.options_.gravity.dot(row(x, i));
  }
  const SpringSet& s = sim.model_.springs;
  for (int k = 0; k < s.size(); ++k) g += spring_energy(s.law(k), s.rest_length[k], row(x, s.i[k]), row(x, s.j[k]));
  return g + seam_energy(sim.model_.seams, x);
}

void Newton::step(ClothSimulator& sim, StepResult& r) {
  const double h = sim.dt_;
  const int n = static_cast<int>(sim.x_.rows());
  const Eigen::MatrixX3d x0 = sim.x_, v0 = sim.v_;
  const Eigen::Vector3d w = sim.wind_at(sim.time_ + h);
  // Start from the explicit prediction: often close, and a good first iterate.
  for (int i = 0; i < n; ++i)
    if (!sim.pinned_[i]) sim.x_.row(i) += h * sim.v_.row(i);
  double G = incremental_potential(sim, sim.x_, x0, v0);
  const SpringSet& s = sim.model_.springs;
  for (int it = 0; it < sim.options_.newton.iterations; ++it) {
    // −h² ∇G: h² × (spring and gravity forces) − M (x − x0 − h v0) − h c M (x − x0 − h w).
    Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(n, 3);
    for (int k = 0; k < s.size(); ++k) {
      const Eigen::Vector3d fi = spring_force(s.law(k), s.rest_length[k], row(sim.x_, s.i[k]), row(sim.x_, s.j[k]));
      f.row(s.i[k]) += fi.transpose();
      f.row(s.j[k]) -= fi.transpose();
    }
    add_seam_forces(sim.model_.seams, sim.x_, f);
    Eigen::VectorXd rhs(3 * n);
    for (int i = 0; i < n; ++i) {
      const double m = sim.model_.mass(i);
      const Eigen::Vector3d gi = h * h * (row(f, i) + m * sim.options_.gravity) - m * (row(sim.x_, i) - row(x0, i) - h * row(v0, i)) -
                                 h * sim.options_.air_damping * m * (row(sim.x_, i) - row(x0, i) - h * w);
      rhs.segment<3>(3 * i) = sim.pinned_[i] ? Eigen::Vector3d::Zero() : gi;
    }
    sim.v_ = (sim.x_ - x0) / h;  // the Hessian does not depend on v; kept consistent for ClothSimulator::forces()
    system_.assemble(sim, false, nullptr);
    Eigen::VectorXd d;
    if (!system_.solve(sim, rhs, Eigen::VectorXd::Zero(rhs.size()), d, r)) return;
    Eigen::MatrixX3d step(n, 3);
    for (int i = 0; i < n; ++i) step.row(i) = d.segment<3>(3 * i).transpose();
    // Backtracking (Armijo) on G; the direction descends since the matrix is SPD.
    const double slope = -rhs.dot(d) / (h * h);
    double alpha = 1.0, G_new = G;
    Eigen::MatrixX3d x_try;
    for (int ls = 0; ls < 30; ++ls, alpha *= 0.5) {
      x_try = sim.x_ + alpha * step;
      G_new = incremental_potential(sim, x_try, x0, v0);
      if (G_new <= G + 1e-4 * alpha * slope) break;
    }
    sim.x_ = x_try;
    const double moved = (alpha * step).rowwise().norm().maxCoeff();
    G = G_new;
    ++r.newton_iterations;
    if (moved < sim.options_.iteration_tolerance) break;
  }
  sim.v_ = (sim.x_ - x0) / h;
  for (int i = 0; i < n; ++i)
    if (sim.pinned_[i]) sim.v_.row(i).setZero();
}

std::unique_ptr<TimeIntegrator> make_newton() { return std::make_unique<Newton>(); }

}  // namespace dresskit::cloth
