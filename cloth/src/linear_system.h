#pragma once
// The implicit integrators' system matrix M (1 + h c) + h² K (+ h D) (implicit Euler, Newton): its
// sparsity pattern (fixed at the first step; each step writes values through precomputed offsets
// instead of rebuilding it from triplets, which cost over half of a step's time), assembly and
// solvers (sparse Cholesky or conjugate gradients).
#include <Eigen/Sparse>
#include <array>
#include <vector>

#include "dresskit/cloth/simulator.h"

namespace dresskit::cloth {

class SystemMatrix {
 public:
  /// Writes the matrix at sim's state for its step sim.dt_; with_spring_damping adds h D; Kv, when
  /// given, receives K v.
  void assemble(const ClothSimulator& sim, bool with_spring_damping, Eigen::VectorXd* Kv);
  /// Solves the assembled system from guess; false (with r.ok = false, r.failure) when it fails.
  bool solve(const ClothSimulator& sim, const Eigen::VectorXd& rhs, const Eigen::VectorXd& guess,
             Eigen::VectorXd& sol, StepResult& r) const;

 private:
  void build_pattern(const ClothSimulator& sim);
  Eigen::SparseMatrix<double> system_;
  std::vector<std::array<int, 12>> spring_offsets_;  ///< per spring: blocks ii, jj, ij, ji × 3 columns
  std::vector<std::array<int, 3>> vertex_offsets_;   ///< per vertex: its diagonal block's 3 columns
  std::vector<std::array<int, 27>> seam_offsets_;    ///< per stitch: blocks (a, b0, b1)² × 3 columns
};

}  // namespace dresskit::cloth
