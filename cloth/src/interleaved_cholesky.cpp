#include "interleaved_cholesky.h"

#include <Eigen/SparseCholesky>
#include <algorithm>

namespace dresskit::cloth::detail {

namespace {
/// Compressed rows or columns of a strictly lower triangle, `Scalar` values.
template <typename Scalar>
void compress(const Eigen::SparseMatrix<double, Eigen::RowMajor>& M, std::vector<int>& start,
              std::vector<int>& index, std::vector<Scalar>& value) {
  start.assign(1, 0);
  index.clear();
  value.clear();
  for (int o = 0; o < M.outerSize(); ++o) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(M, o); it; ++it) {
      if (it.col() == o) continue;
      index.push_back(static_cast<int>(it.col()));
      value.push_back(static_cast<Scalar>(it.value()));
    }
    start.push_back(static_cast<int>(index.size()));
  }
}
}  // namespace

template <typename Scalar>
bool InterleavedCholesky<Scalar>::compute(const Eigen::SparseMatrix<double>& A) {
  llt_ = std::make_shared<
      Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>>(A);
  if (llt_->info() != Eigen::Success) return false;
  n_ = static_cast<int>(A.rows());
  // LLT factorises P A Pᵀ with (P v)[indices[i]] = v[i]: factor row indices[i] is the matrix's row
  // i.
  perm_.assign(static_cast<std::size_t>(n_), 0);
  const auto& p = llt_->permutationP().indices();
  for (int i = 0; i < n_; ++i) perm_[static_cast<std::size_t>(p[i])] = i;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> L = llt_->matrixL();
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Lt = llt_->matrixU();
  inv_diag_.assign(static_cast<std::size_t>(n_), 0.0);
  for (int j = 0; j < n_; ++j) inv_diag_[static_cast<std::size_t>(j)] = 1.0 / L.coeff(j, j);
  compress(L, row_start_, row_index_, row_value_);
  compress(Lt, col_start_, col_index_, col_value_);
  work_.assign(4 * static_cast<std::size_t>(n_), 0.0);
  // For refactor: A's sparsity, and where each strictly lower entry of the column-major factor
  // (column j, rows increasing) goes among the rows (row i, columns increasing).
  pattern_outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
  pattern_inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  const Eigen::SparseMatrix<double>& C = llt_->matrixL().nestedExpression();
  std::vector<int> fill(row_start_.begin(), row_start_.end() - 1);
  row_place_.clear();
  for (int j = 0; j < n_; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(C, j); it; ++it)
      if (it.row() != j) row_place_.push_back(fill[static_cast<std::size_t>(it.row())]++);
  return true;
}

template <typename Scalar>
bool InterleavedCholesky<Scalar>::refactor(const Eigen::SparseMatrix<double>& A) {
  const bool same = llt_ && A.rows() == n_ && A.isCompressed() &&
                    static_cast<std::size_t>(A.nonZeros()) == pattern_inner_.size() &&
                    std::equal(pattern_outer_.begin(), pattern_outer_.end(), A.outerIndexPtr()) &&
                    std::equal(pattern_inner_.begin(), pattern_inner_.end(), A.innerIndexPtr());
  if (!same) return compute(A);
  llt_->factorize(A);
  if (llt_->info() != Eigen::Success) return false;
  return copy_values();
}

template <typename Scalar>
bool InterleavedCholesky<Scalar>::copy_values() {
  const Eigen::SparseMatrix<double>& C = llt_->matrixL().nestedExpression();
  std::size_t column_entry = 0, lower = 0;
  for (int j = 0; j < n_; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(C, j); it; ++it) {
      if (it.row() == j) {
        inv_diag_[static_cast<std::size_t>(j)] = 1.0 / it.value();
        continue;
      }
      col_value_[column_entry++] = static_cast<Scalar>(it.value());  // row j of Lᵀ, in order
      row_value_[static_cast<std::size_t>(row_place_[lower++])] = static_cast<Scalar>(it.value());
    }
  return column_entry == col_value_.size() && lower == row_value_.size();
}

/// Row r of a triangular solve as a gather: y_r = (s − Σ_k value_k y_{index_k}) / diagonal, three
/// columns at once (y holds four per row; the fourth is padding).
template <typename Scalar>
inline void solve_row(int r, const double* s, const std::vector<int>& start,
                      const std::vector<int>& index, const std::vector<Scalar>& value,
                      double inv_diag, double* y) {
  double s0 = s[0], s1 = s[1], s2 = s[2];
  for (int k = start[r]; k < start[r + 1]; ++k) {
    const double l = value[k];
    const double* t = y + 4 * index[k];
    s0 -= l * t[0];
    s1 -= l * t[1];
    s2 -= l * t[2];
  }
  y[4 * r] = s0 * inv_diag, y[4 * r + 1] = s1 * inv_diag, y[4 * r + 2] = s2 * inv_diag;
}

template <typename Scalar>
void InterleavedCholesky<Scalar>::solve_in_place(double* b) const {
  double* y = work_.data();
  // L y' = P b, row by row.
  for (int r = 0; r < n_; ++r)
    solve_row(r, b + 3 * perm_[r], row_start_, row_index_, row_value_, inv_diag_[r], y);
  // Lᵀ z = y', from the last row (each row's right-hand side is its own entry of y', read first).
  for (int r = n_ - 1; r >= 0; --r) {
    const double s[3] = {y[4 * r], y[4 * r + 1], y[4 * r + 2]};
    solve_row(r, s, col_start_, col_index_, col_value_, inv_diag_[r], y);
  }
  for (int r = 0; r < n_; ++r)
    for (int c = 0; c < 3; ++c) b[3 * perm_[r] + c] = y[4 * r + c];
}

template class InterleavedCholesky<float>;
template class InterleavedCholesky<double>;

}  // namespace dresskit::cloth::detail
