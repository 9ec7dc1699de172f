// The implicit integrators' system matrix (linear_system.h).
#include "linear_system.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/spring_kernels.h"
#include "simulator_internal.h"

namespace dresskit::cloth {

using detail::add_block;
using detail::add_spring_blocks;
using detail::row;

void SystemMatrix::build_pattern(const ClothSimulator& sim) {
  const int n = static_cast<int>(sim.x_.rows());
  const SpringSet& s = sim.model_.springs;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(s.size()) * 36 + 9 * static_cast<size_t>(n));
  for (int k = 0; k < s.size(); ++k) add_spring_blocks(t, s.i[k], s.j[k], Eigen::Matrix3d::Zero());
  for (int v = 0; v < n; ++v) add_block(t, v, v, Eigen::Matrix3d::Zero());
  const SeamSet& seams = sim.model_.seams;
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

// Writes A = M (1 + h c) + h² K (+ h D for spring damping when with_spring_damping),
// with K = −∂f/∂x at the current positions (compressed springs' transverse terms clamped: SPD) and
// pinned rows and columns replaced by the identity. If Kv is given, it receives K v (unclamped
// blocks are not needed: the same clamped K is used on both sides).
void SystemMatrix::assemble(const ClothSimulator& sim, bool with_spring_damping, Eigen::VectorXd* Kv) {
  const double h = sim.dt_;
  const int n = static_cast<int>(sim.x_.rows());
  const SpringSet& s = sim.model_.springs;
  if (system_.rows() != 3 * n) build_pattern(sim);
  double* values = system_.valuePtr();
  std::fill(values, values + system_.nonZeros(), 0.0);
  auto put = [&](const std::array<int, 12>& off, int block, const Eigen::Matrix3d& B) {
    for (int c = 0; c < 3; ++c)
      for (int r3 = 0; r3 < 3; ++r3) values[off[3 * block + c] + r3] += B(r3, c);
  };
  if (Kv) Kv->setZero(3 * n);
  for (int k = 0; k < s.size(); ++k) {
    const int i = s.i[k], j = s.j[k];
    const Eigen::Vector3d xi = row(sim.x_, i), xj = row(sim.x_, j);
    Eigen::Matrix3d B = -spring_jacobian(s.law(k), s.rest_length[k], xi, xj, sim.allowed_length(k), true);
    if (Kv) {
      Kv->segment<3>(3 * i) += B * (row(sim.v_, i) - row(sim.v_, j));
      Kv->segment<3>(3 * j) += B * (row(sim.v_, j) - row(sim.v_, i));
    }
    B *= h * h;
    if (with_spring_damping && sim.options_.spring_damping > 0.0 && (xj - xi).norm() > 1e-12) {
      const Eigen::Vector3d u = (xj - xi).normalized();
      B += h * sim.options_.spring_damping * s.k_rest[k] * u * u.transpose();
    }
    // Pinned rows and columns stay zero here (their diagonal becomes the identity below).
    if (!sim.pinned_[i]) put(spring_offsets_[k], 0, B);
    if (!sim.pinned_[j]) put(spring_offsets_[k], 1, B);
    if (!sim.pinned_[i] && !sim.pinned_[j]) {
      put(spring_offsets_[k], 2, -B);
      put(spring_offsets_[k], 3, -B);
    }
  }
  // Seams: K = w wᵀ ⊗ S over the stitch's particles (a, b0, b1), S = −∂F/∂c (seams.h).
  const SeamSet& seams = sim.model_.seams;
  int idx[3];
  double w[3];
  for (int k = 0; k < seams.size(); ++k) {
    seam_weights(seams, k, idx, w);
    Eigen::Matrix3d S;
    stitch_force(seams, k, seam_gap(seams, k, sim.x_), &S);
    if (Kv) {
      const Eigen::Vector3d Swv = S * (w[0] * row(sim.v_, idx[0]) + w[1] * row(sim.v_, idx[1]) + w[2] * row(sim.v_, idx[2]));
      for (int p = 0; p < 3; ++p) Kv->segment<3>(3 * idx[p]) += w[p] * Swv;
    }
    S *= h * h;
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) {
        if (sim.pinned_[idx[p]] || sim.pinned_[idx[q]]) continue;
        for (int c = 0; c < 3; ++c)
          for (int r3 = 0; r3 < 3; ++r3) values[seam_offsets_[k][9 * p + 3 * q + c] + r3] += w[p] * w[q] * S(r3, c);
      }
  }
  for (int i = 0; i < n; ++i) {
    const double diag = sim.pinned_[i] ? 1.0 : sim.model_.mass(i) * (1.0 + h * sim.options_.air_damping);
    for (int c = 0; c < 3; ++c) values[vertex_offsets_[i][c] + c] += diag;
  }
  // Implicit Euler (Kv given): the penalty forces' stiffness, h² m a/δ exp(depth/δ) n nᵀ (zero beyond
  // the profile's cap). Newton and projective dynamics leave the penalty out (no potential term):
  // their contacts are the collision projection alone.
  const double delta = sim.options_.penalty_thickness;
  for (std::size_t k = 0; Kv && k < sim.contacts_.particle.size(); ++k) {
    const int i = sim.contacts_.particle[k];
    if (sim.pinned_[i] || sim.contacts_.depth[k] >= 4.0 * delta) continue;
    const double stiffness = sim.model_.mass(i) * sim.options_.colliders[sim.contacts_.collider[k]].penalty / delta *
                             std::exp(sim.contacts_.depth[k] / delta);
    const Eigen::Vector3d& nk = sim.contacts_.normal[k];
    Kv->segment<3>(3 * i) += stiffness * nk.dot(row(sim.v_, i)) * nk;
    const Eigen::Matrix3d B = h * h * stiffness * nk * nk.transpose();
    for (int c = 0; c < 3; ++c)
      for (int r3 = 0; r3 < 3; ++r3) values[vertex_offsets_[i][c] + r3] += B(r3, c);
  }
}

// Solves system_ · sol = rhs with the chosen solver (CG starts from guess).
bool SystemMatrix::solve(const ClothSimulator& sim, const Eigen::VectorXd& rhs, const Eigen::VectorXd& guess,
                         Eigen::VectorXd& sol, StepResult& r) const {
  if (sim.options_.linear.solver == LinearSolver::ldlt) {
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
  solver.setTolerance(sim.options_.linear.cg_tolerance);
  solver.setMaxIterations(sim.options_.linear.cg_max_iterations);
  solver.compute(system_);
  sol = solver.solveWithGuess(rhs, guess);
  r.solver_iterations += static_cast<int>(solver.iterations());
  if (solver.info() != Eigen::Success) {
    r.ok = false;
    r.failure = "conjugate gradient did not converge in " + std::to_string(sim.options_.linear.cg_max_iterations) + " iterations";
    return false;
  }
  return true;
}

}  // namespace dresskit::cloth
