// Projective dynamics (Bouaziz et al. 2014, "Projective Dynamics: Fusing Constraint Projections for
// Fast Simulation"; for mass-spring systems Liu et al. 2013, "Fast Simulation of Mass-Spring
// Systems"): backward Euler's incremental potential with every spring as the quadratic
// w/2 |xj − xi − d|². Global step: one constant, prefactored linear system for the three coordinate
// columns. Local step: d along the spring with the length ℓ = L − t(L)/w, so that the quadratic's
// force w (L − ℓ) equals the spring law's tension t(L) at the current length (the nonlinear law,
// with dynamic stiffness, enters through the targets while the matrix stays constant). A converged
// step is therefore backward Euler with the full law. w is the law's tangent stiffness just below the
// knee: the fixed-point iteration contracts while the local stiffness stays within about twice w
// (with w = k_knee the error bench's error grew with the iteration count). Spring damping is not
// modelled (as in the Newton integrator).
#include <Eigen/SparseCholesky>
#include <cmath>

#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/cloth/stiffness_law.h"
#include "simulator_internal.h"

namespace dresskit {

namespace {
/// The spring's weight: the law's tangent stiffness just below the knee, k_knee + (5/3)(k_knee − k0)
/// (the last ramp segment's slope × knee strain, plus k_knee).
double projective_weight(double k_rest, double k_knee) {
  const double knee = std::max(k_rest, k_knee);
  return knee + 5.0 / 3.0 * (knee - k_rest);
}
}  // namespace

struct ClothSimulator::Projective {
  double h = 0.0;
  std::vector<bool> pinned;
  Eigen::VectorXd inertia;                 ///< m/h² + c m/h per particle
  Eigen::SparseMatrix<double> to_pinned;   ///< free-row × pinned-column couplings, moved to the rhs
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> solver;
  bool ok = false;
};

void ClothSimulator::step_projective(StepResult& r) {
  const double h = dt_;
  const int n = static_cast<int>(x_.rows());
  const SpringSet& s = model_.springs;
  const double c = options_.air_damping;
  if (!projective_ || projective_->h != h || projective_->pinned != pinned_) {
    auto p = std::make_shared<Projective>();
    p->h = h;
    p->pinned = pinned_;
    p->inertia = model_.mass * (1.0 / (h * h) + c / h);
    std::vector<Eigen::Triplet<double>> a, b;
    a.reserve(static_cast<std::size_t>(4 * s.size() + n));
    for (int v = 0; v < n; ++v) a.emplace_back(v, v, pinned_[v] ? 1.0 : p->inertia[v]);
    auto couple = [&](int row, int col, double value) {
      if (pinned_[row]) return;
      (pinned_[col] ? b : a).emplace_back(row, col, value);
    };
    for (int k = 0; k < s.size(); ++k) {
      const int i = s.i[k], j = s.j[k];
      const double w = projective_weight(s.k_rest[k], s.k_knee[k]);
      couple(i, i, w);
      couple(j, j, w);
      couple(i, j, -w);
      couple(j, i, -w);
    }
    // A stitch is the quadratic ½ k |Σ w x − d|² with d its soft-threshold target (seams.h).
    int idx[3];
    double sw[3];
    for (int k = 0; k < model_.seams.size(); ++k) {
      seam_weights(model_.seams, k, idx, sw);
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) couple(idx[p], idx[q], model_.seams.stiffness[k] * sw[p] * sw[q]);
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(a.begin(), a.end());
    p->to_pinned.resize(n, n);
    p->to_pinned.setFromTriplets(b.begin(), b.end());
    p->solver.compute(A);
    p->ok = p->solver.info() == Eigen::Success;
    projective_ = p;
  }
  if (!projective_->ok) {
    r.ok = false;
    r.failure = "projective dynamics: the global matrix could not be factorised";
    return;
  }

  // Constant part of the right-hand side: inertia, air (with wind) and gravity.
  const Eigen::MatrixX3d x0 = x_;
  const Eigen::Vector3d wind = wind_at(time_ + h);
  Eigen::MatrixX3d fixed(n, 3);
  for (int v = 0; v < n; ++v) {
    const double m = model_.mass(v);
    fixed.row(v) = (m / (h * h)) * (x0.row(v) + h * v_.row(v)) + (c * m / h) * (x0.row(v) + h * wind.transpose()) +
                   m * options_.gravity.transpose();
  }
  fixed -= projective_->to_pinned * x0;  // pinned particles stay where they are
  for (int v = 0; v < n; ++v)
    if (pinned_[v]) fixed.row(v) = x0.row(v);

  // Start from the inertial prediction.
  for (int v = 0; v < n; ++v)
    if (!pinned_[v]) x_.row(v) = x0.row(v) + h * v_.row(v);
  Eigen::MatrixX3d rhs(n, 3);
  const double beyond = options_.dynamic_stiffness ? 1.0 + options_.strain_limit : 0.0;
  for (int it = 0; it < options_.projective_iterations; ++it) {
    rhs = fixed;
    for (int k = 0; k < s.size(); ++k) {  // local step: each spring's target
      const int i = s.i[k], j = s.j[k];
      Eigen::Vector3d e = detail::row(x_, j) - detail::row(x_, i);
      double L = e.norm();
      if (L < 1e-12) {  // no direction: take the rest direction
        e = detail::row(model_.rest_positions, j) - detail::row(model_.rest_positions, i);
        L = 0.0;
      }
      const double L0 = s.rest_length[k], w = projective_weight(s.k_rest[k], s.k_knee[k]);
      const double strain = L / L0 - 1.0;
      double t = fitted_k(s.k_rest[k], s.k_knee[k], kKneeStrain, strain) * strain * L0;
      if (beyond > 0.0 && L > beyond * L0) t *= L / L0;
      const double target = std::max(L - t / w, 0.0);
      const Eigen::Vector3d d = (w * target / e.norm()) * e;
      if (!pinned_[j]) rhs.row(j) += d.transpose();
      if (!pinned_[i]) rhs.row(i) -= d.transpose();
    }
    int idx[3];
    double sw[3];
    for (int k = 0; k < model_.seams.size(); ++k) {
      seam_weights(model_.seams, k, idx, sw);
      const Eigen::RowVector3d d =
          model_.seams.stiffness[k] * stitch_target(model_.seams, k, seam_gap(model_.seams, k, x_)).transpose();
      for (int p = 0; p < 3; ++p)
        if (!pinned_[idx[p]]) rhs.row(idx[p]) += sw[p] * d;
    }
    const Eigen::MatrixX3d next = projective_->solver.solve(rhs);  // global step
    const double moved = (next - x_).rowwise().norm().maxCoeff();
    x_ = next;
    r.newton_iterations = it + 1;
    if (moved < options_.newton_tolerance) break;
  }
  v_ = (x_ - x0) / h;
}

}  // namespace dresskit
