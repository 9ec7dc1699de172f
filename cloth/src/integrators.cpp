// The simulator's integrators — symplectic Euler, implicit (backward) Euler with one linearised solve
// per step, and Newton with line search on backward Euler's incremental potential — with the shared
// assembly of the system matrix and its solvers.
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

namespace dresskit {

using detail::add_block;
using detail::add_spring_blocks;
using detail::row;

void ClothSimulator::step_symplectic(StepResult&) {
  const Eigen::MatrixX3d f = forces();
  for (int i = 0; i < x_.rows(); ++i) {
    if (pinned_[i]) continue;
    v_.row(i) += dt_ / model_.mass(i) * f.row(i);
    x_.row(i) += dt_ * v_.row(i);
  }
}

void ClothSimulator::build_pattern() {
  const int n = static_cast<int>(x_.rows());
  const SpringSet& s = model_.springs;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(s.size()) * 36 + 9 * static_cast<size_t>(n));
  for (int k = 0; k < s.size(); ++k) add_spring_blocks(t, s.i[k], s.j[k], Eigen::Matrix3d::Zero());
  for (int v = 0; v < n; ++v) add_block(t, v, v, Eigen::Matrix3d::Zero());
  const SeamSet& seams = model_.seams;
  int idx[3];
  double w[3];
  for (int k = 0; k < seams.size(); ++k) {
    seam_weights(seams, k, idx, w);
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) add_block(t, idx[p], idx[q], Eigen::Matrix3d::Zero());
  }
  system_.resize(3 * n, 3 * n);
  system_.setFromTriplets(t.begin(), t.end());
  system_.makeCompressed();
  const int* inner = system_.innerIndexPtr();
  const int* outer = system_.outerIndexPtr();
  // Offset of entry (row, col) in the value array; rows of a 3×3 block are contiguous in a column.
  auto offset = [&](int row, int col) {
    return static_cast<int>(std::lower_bound(inner + outer[col], inner + outer[col + 1], row) - inner);
  };
  spring_offsets_.resize(static_cast<size_t>(s.size()));
  for (int k = 0; k < s.size(); ++k) {
    const int blocks[4][2] = {{s.i[k], s.i[k]}, {s.j[k], s.j[k]}, {s.i[k], s.j[k]}, {s.j[k], s.i[k]}};
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 3; ++c) spring_offsets_[k][3 * b + c] = offset(3 * blocks[b][0], 3 * blocks[b][1] + c);
  }
  vertex_offsets_.resize(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) vertex_offsets_[v][c] = offset(3 * v, 3 * v + c);
  seam_offsets_.resize(static_cast<size_t>(seams.size()));
  for (int k = 0; k < seams.size(); ++k) {
    seam_weights(seams, k, idx, w);
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        for (int c = 0; c < 3; ++c) seam_offsets_[k][9 * p + 3 * q + c] = offset(3 * idx[p], 3 * idx[q] + c);
  }
}

// Writes A = M (1 + h c) + h² K (+ h D for spring damping when with_spring_damping) into system_,
// with K = −∂f/∂x at the current positions (compressed springs' transverse terms clamped: SPD) and
// pinned rows and columns replaced by the identity. If Kv is given, it receives K v (unclamped
// blocks are not needed: the same clamped K is used on both sides).
void ClothSimulator::assemble_system(bool with_spring_damping, Eigen::VectorXd* Kv) {
  const double h = dt_;
  const int n = static_cast<int>(x_.rows());
  const SpringSet& s = model_.springs;
  if (system_.rows() != 3 * n) build_pattern();
  double* values = system_.valuePtr();
  std::fill(values, values + system_.nonZeros(), 0.0);
  auto put = [&](const std::array<int, 12>& off, int block, const Eigen::Matrix3d& B) {
    for (int c = 0; c < 3; ++c)
      for (int r3 = 0; r3 < 3; ++r3) values[off[3 * block + c] + r3] += B(r3, c);
  };
  if (Kv) Kv->setZero(3 * n);
  for (int k = 0; k < s.size(); ++k) {
    const int i = s.i[k], j = s.j[k];
    const Eigen::Vector3d xi = row(x_, i), xj = row(x_, j);
    Eigen::Matrix3d B = -spring_jacobian(s.law(k), s.rest_length[k], xi, xj, allowed_length(k), true);
    if (Kv) {
      Kv->segment<3>(3 * i) += B * (row(v_, i) - row(v_, j));
      Kv->segment<3>(3 * j) += B * (row(v_, j) - row(v_, i));
    }
    B *= h * h;
    if (with_spring_damping && options_.spring_damping > 0.0 && (xj - xi).norm() > 1e-12) {
      const Eigen::Vector3d u = (xj - xi).normalized();
      B += h * options_.spring_damping * s.k_rest[k] * u * u.transpose();
    }
    // Pinned rows and columns stay zero here (their diagonal becomes the identity below).
    if (!pinned_[i]) put(spring_offsets_[k], 0, B);
    if (!pinned_[j]) put(spring_offsets_[k], 1, B);
    if (!pinned_[i] && !pinned_[j]) {
      put(spring_offsets_[k], 2, -B);
      put(spring_offsets_[k], 3, -B);
    }
  }
  // Seams: K = w wᵀ ⊗ S over the stitch's particles (a, b0, b1), S = −∂F/∂c (seams.h).
  const SeamSet& seams = model_.seams;
  int idx[3];
  double w[3];
  for (int k = 0; k < seams.size(); ++k) {
    seam_weights(seams, k, idx, w);
    Eigen::Matrix3d S;
    stitch_force(seams, k, seam_gap(seams, k, x_), &S);
    if (Kv) {
      const Eigen::Vector3d Swv = S * (w[0] * row(v_, idx[0]) + w[1] * row(v_, idx[1]) + w[2] * row(v_, idx[2]));
      for (int p = 0; p < 3; ++p) Kv->segment<3>(3 * idx[p]) += w[p] * Swv;
    }
    S *= h * h;
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) {
        if (pinned_[idx[p]] || pinned_[idx[q]]) continue;
        for (int c = 0; c < 3; ++c)
          for (int r3 = 0; r3 < 3; ++r3) values[seam_offsets_[k][9 * p + 3 * q + c] + r3] += w[p] * w[q] * S(r3, c);
      }
  }
  for (int i = 0; i < n; ++i) {
    const double diag = pinned_[i] ? 1.0 : model_.mass(i) * (1.0 + h * options_.air_damping);
    for (int c = 0; c < 3; ++c) values[vertex_offsets_[i][c] + c] += diag;
  }
  // Implicit Euler (Kv given): the penalty forces' stiffness, h² m a/δ exp(depth/δ) n nᵀ (zero beyond
  // the profile's cap). Newton and projective dynamics leave the penalty out (no potential term):
  // their contacts are the collision projection alone.
  const double delta = options_.penalty_thickness;
  for (std::size_t k = 0; Kv && k < contacts_.particle.size(); ++k) {
    const int i = contacts_.particle[k];
    if (pinned_[i] || contacts_.depth[k] >= 4.0 * delta) continue;
    const double stiffness = model_.mass(i) * options_.colliders[contacts_.collider[k]].penalty / delta *
                             std::exp(contacts_.depth[k] / delta);
    const Eigen::Vector3d& nk = contacts_.normal[k];
    Kv->segment<3>(3 * i) += stiffness * nk.dot(row(v_, i)) * nk;
    const Eigen::Matrix3d B = h * h * stiffness * nk * nk.transpose();
    for (int c = 0; c < 3; ++c)
      for (int r3 = 0; r3 < 3; ++r3) values[vertex_offsets_[i][c] + r3] += B(r3, c);
  }
}

// Solves system_ · sol = rhs with the chosen solver (CG starts from guess).
bool ClothSimulator::solve_system(const Eigen::VectorXd& rhs, const Eigen::VectorXd& guess,
                                  Eigen::VectorXd& sol, StepResult& r) {
  if (options_.linear_solver == LinearSolver::ldlt) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system_);
    if (solver.info() != Eigen::Success) {
      r.ok = false;
      r.failure = "LDLT factorisation failed";
      return false;
    }
    sol = solver.solve(rhs);
    return true;
  }
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> solver;
  solver.setTolerance(options_.cg_tolerance);
  solver.setMaxIterations(options_.cg_max_iterations);
  solver.compute(system_);
  sol = solver.solveWithGuess(rhs, guess);
  r.solver_iterations += static_cast<int>(solver.iterations());
  if (solver.info() != Eigen::Success) {
    r.ok = false;
    r.failure = "conjugate gradient did not converge in " + std::to_string(options_.cg_max_iterations) + " iterations";
    return false;
  }
  return true;
}

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

// Backward Euler as minimisation (the stiff-robust integrator): x minimises the incremental potential
//   G(x) = Σ m/(2h²) |x − x0 − h v0|² + Σ c m/(2h) |x − x0 − h w|² + E(x) − Σ m g·x,
// whose stationarity is exactly backward Euler with air damping c and wind w. Newton steps with the
// clamped (SPD) Hessian; h²·Hessian is implicit Euler's matrix. A backtracking line search keeps G
// decreasing, which is what keeps very stiff springs at large steps stable. Spring damping and
// dynamic stiffness have no potential and are not applied by this integrator.
double ClothSimulator::incremental_potential(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& x0,
                                            const Eigen::MatrixX3d& v0) const {
  const double h = dt_;
  const Eigen::Vector3d w = wind_at(time_ + h);
  double g = 0.0;
  for (int i = 0; i < x.rows(); ++i) {
    const double m = model_.mass(i);
    g += m / (2 * h * h) * (row(x, i) - row(x0, i) - h * row(v0, i)).squaredNorm();
    g += options_.air_damping * m / (2 * h) * (row(x, i) - row(x0, i) - h * w).squaredNorm();
    g -= m * options_.gravity.dot(row(x, i));
  }
  const SpringSet& s = model_.springs;
  for (int k = 0; k < s.size(); ++k) g += spring_energy(s.law(k), s.rest_length[k], row(x, s.i[k]), row(x, s.j[k]));
  return g + seam_energy(model_.seams, x);
}

void ClothSimulator::step_newton(StepResult& r) {
  const double h = dt_;
  const int n = static_cast<int>(x_.rows());
  const Eigen::MatrixX3d x0 = x_, v0 = v_;
  const Eigen::Vector3d w = wind_at(time_ + h);
  // Start from the explicit prediction: often close, and a good first iterate.
  for (int i = 0; i < n; ++i)
    if (!pinned_[i]) x_.row(i) += h * v_.row(i);
  double G = incremental_potential(x_, x0, v0);
  const SpringSet& s = model_.springs;
  for (int it = 0; it < options_.newton_iterations; ++it) {
    // −h² ∇G: h² × (spring and gravity forces) − M (x − x0 − h v0) − h c M (x − x0 − h w).
    Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(n, 3);
    for (int k = 0; k < s.size(); ++k) {
      const Eigen::Vector3d fi = spring_force(s.law(k), s.rest_length[k], row(x_, s.i[k]), row(x_, s.j[k]));
      f.row(s.i[k]) += fi.transpose();
      f.row(s.j[k]) -= fi.transpose();
    }
    add_seam_forces(model_.seams, x_, f);
    Eigen::VectorXd rhs(3 * n);
    for (int i = 0; i < n; ++i) {
      const double m = model_.mass(i);
      const Eigen::Vector3d gi = h * h * (row(f, i) + m * options_.gravity) - m * (row(x_, i) - row(x0, i) - h * row(v0, i)) -
                                 h * options_.air_damping * m * (row(x_, i) - row(x0, i) - h * w);
      rhs.segment<3>(3 * i) = pinned_[i] ? Eigen::Vector3d::Zero() : gi;
    }
    v_ = (x_ - x0) / h;  // the Hessian does not depend on v; kept consistent for forces()
    assemble_system(false, nullptr);
    Eigen::VectorXd d;
    if (!solve_system(rhs, Eigen::VectorXd::Zero(rhs.size()), d, r)) return;
    Eigen::MatrixX3d step(n, 3);
    for (int i = 0; i < n; ++i) step.row(i) = d.segment<3>(3 * i).transpose();
    // Backtracking (Armijo) on G; the direction descends since the matrix is SPD.
    const double slope = -rhs.dot(d) / (h * h);
    double alpha = 1.0, G_new = G;
    Eigen::MatrixX3d x_try;
    for (int ls = 0; ls < 30; ++ls, alpha *= 0.5) {
      x_try = x_ + alpha * step;
      G_new = incremental_potential(x_try, x0, v0);
      if (G_new <= G + 1e-4 * alpha * slope) break;
    }
    x_ = x_try;
    const double moved = (alpha * step).rowwise().norm().maxCoeff();
    G = G_new;
    ++r.newton_iterations;
    if (moved < options_.newton_tolerance) break;
  }
  v_ = (x_ - x0) / h;
  for (int i = 0; i < n; ++i)
    if (pinned_[i]) v_.row(i).setZero();
}

}  // namespace dresskit
