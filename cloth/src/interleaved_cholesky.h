#pragma once
// A sparse Cholesky factor kept for many solves with three right-hand sides at once (the x, y and z
// columns of projective dynamics' global step). Eigen's SimplicialLLT factorises (AMD ordering);
// the factor is then copied into plain compressed columns of `Scalar` and solved with the three
// columns interleaved, so that each stored entry is read once per solve instead of once per column.
// Projective dynamics' solves are bound by reading the factor (about 0.3–0.5 M entries for the
// 81×81 cloth), so this, and storing it in single precision (half the bytes), is what makes them
// faster (measured in docs/results.md). Single precision is used for corrections only
// (solve_correction): the caller solves A δ = b − A x for the change δ of an iterate x, so the
// rounding of the factor scales with |δ|, not with the positions.
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <memory>
#include <vector>

namespace dresskit::cloth::detail {

template <typename Scalar>
class InterleavedCholesky {
 public:
  /// Factorises the SPD matrix A (both triangles stored); false if it is not positive definite.
  bool compute(const Eigen::SparseMatrix<double>& A);
  /// The same for a matrix of the last one's sparsity with new values: the ordering, the symbolic
  /// factorisation and the layout of the interleaved copy are kept, only the values are computed
  /// again (about half the time of compute on the error bench's cloth). Falls back to compute when
  /// the sparsity differs.
  bool refactor(const Eigen::SparseMatrix<double>& A);
  int rows() const { return n_; }
  /// Solves A X = B in place for B of n rows × 3 columns stored row by row (x0 y0 z0 x1 y1 z1 ...).
  void solve_in_place(double* b) const;
  /// Entries of the factor, diagonal included.
  long factor_nonzeros() const { return static_cast<long>(col_value_.size()) + n_; }

 private:
  int n_ = 0;
  std::vector<int> perm_;  ///< factor row r is the matrix's row perm_[r]
  /// The strictly lower part of L twice: by rows (forward solve) and by columns (rows of Lᵀ,
  /// backward solve), so that both solves are gathers (dot products) with one store per row.
  std::vector<int> row_start_, row_index_, col_start_, col_index_;
  std::vector<Scalar> row_value_, col_value_;
  std::vector<double> inv_diag_;
  mutable std::vector<double> work_;
  /// For refactor: the factorisation (symbolic part kept), A's sparsity, and for each strictly
  /// lower entry of the column-major factor its place in row_value_.
  std::shared_ptr<
      Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>>
      llt_;
  std::vector<int> pattern_outer_, pattern_inner_;
  std::vector<int> row_place_;
  bool copy_values();
};

extern template class InterleavedCholesky<float>;
extern template class InterleavedCholesky<double>;

}  // namespace dresskit::cloth::detail
