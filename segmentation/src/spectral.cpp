// Spectra is included here only: the public header speaks Eigen.
#include "dresskit/mesh/names.h"
#include "dresskit/segmentation/spectral.h"

#include <Spectra/MatOp/SparseSymShiftSolve.h>
#include <Spectra/SymEigsShiftSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "dresskit/mesh/errors.h"


namespace dresskit::segmentation {

const NameTable<LaplacianKind> kLaplacians = {{"normalized", LaplacianKind::normalized},
    {"normalised", LaplacianKind::normalized}, {"plain", LaplacianKind::plain}};
LaplacianKind parse_laplacian(const std::string& text) { return parse_name(text, kLaplacians, "laplacian"); }
std::string to_string(LaplacianKind kind) { return name_of(kind, kLaplacians); }

Eigen::SparseMatrix<double> graph_laplacian(const Eigen::SparseMatrix<double>& W,
                                            LaplacianKind kind) {
  const Eigen::VectorXd degree = W * Eigen::VectorXd::Ones(W.cols());
  Eigen::SparseMatrix<double> L(W.rows(), W.cols());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(W.nonZeros() + W.rows());
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(W.rows());
  if (kind == LaplacianKind::normalized)
    for (int i = 0; i < W.rows(); ++i) scale(i) = degree(i) > 0 ? 1.0 / std::sqrt(degree(i)) : 0.0;
  for (int j = 0; j < W.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(W, j); it; ++it)
      t.emplace_back(it.row(), it.col(), -it.value() * scale(it.row()) * scale(it.col()));
  for (int i = 0; i < W.rows(); ++i)
    t.emplace_back(i, i,
                   kind == LaplacianKind::normalized ? (degree(i) > 0 ? 1.0 : 0.0) : degree(i));
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

namespace {

double max_residual(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& values,
                    const Eigen::MatrixXd& vectors) {
  double r = 0.0;
  for (int k = 0; k < values.size(); ++k)
    r = std::max(r, (L * vectors.col(k) - values(k) * vectors.col(k)).norm());
  return r;
}

EigenResult dense_eigenpairs(const Eigen::SparseMatrix<double>& L, int nev) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver{Eigen::MatrixXd(L)};
  if (solver.info() != Eigen::Success) throw EigenSolverError("dense eigen-solver failed");
  EigenResult r;
  r.values = solver.eigenvalues().head(nev);  // ascending
  r.vectors = solver.eigenvectors().leftCols(nev);
  r.method = "dense";
  r.ncv = static_cast<int>(L.rows());
  return r;
}

}  // namespace

EigenResult smallest_eigenpairs(const Eigen::SparseMatrix<double>& L, int nev,
                                const EigenOptions& options) {
  const int n = static_cast<int>(L.rows());
  if (nev < 1 || nev > n)
    throw InputError("eigenpairs: " + std::to_string(nev) + " requested of a " + std::to_string(n) +
                     "-vertex graph");
  EigenResult result;
  if (n < options.dense_below || nev >= n - 1) {
    result = dense_eigenpairs(L, nev);
  } else {
    const double mean_diagonal = L.diagonal().mean();
    const double sigma = options.relative_shift * (mean_diagonal > 0 ? mean_diagonal : 1.0);
    Spectra::SparseSymShiftSolve<double> op(L);
    std::ostringstream tried;
    int ncv = options.ncv > 0 ? options.ncv : std::max(2 * nev + 1, 20);
    int max_iterations = options.max_iterations;
    bool converged = false;
    for (int attempt = 0; attempt < 3 && !converged; ++attempt) {
      ncv = std::min(std::max(ncv, nev + 1), n);
      Spectra::SymEigsShiftSolver<Spectra::SparseSymShiftSolve<double>> solver(op, nev, ncv, sigma);
      solver.init();
      solver.compute(Spectra::SortRule::LargestMagn, max_iterations, options.tolerance,
                     Spectra::SortRule::SmallestAlge);
      tried << (attempt ? "; " : "") << "ncv " << ncv << ", " << max_iterations
            << " iterations, tol " << options.tolerance << ", shift " << sigma;
      if (solver.info() == Spectra::CompInfo::Successful) {
        converged = true;
        result.values = solver.eigenvalues();
        result.vectors = solver.eigenvectors();
        result.iterations += static_cast<int>(solver.num_iterations());
        result.ncv = ncv;
      } else {
        result.iterations += static_cast<int>(solver.num_iterations());
        ncv *= 2;
        max_iterations *= 2;
      }
    }
    if (!converged)
      throw EigenSolverError("eigen-solver did not converge for the " + std::to_string(nev) +
                             " smallest eigenpairs of a " + std::to_string(n) +
                             "-vertex graph; tried " + tried.str());
    result.method = "spectra shift-invert";
  }
  // Ascending order; Spectra returns the sort rule's order.
  std::vector<int> order(result.values.size());
  for (int k = 0; k < static_cast<int>(order.size()); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return result.values(a) < result.values(b); });
  EigenResult sorted = result;
  for (size_t k = 0; k < order.size(); ++k) {
    sorted.values(k) = result.values(order[k]);
    sorted.vectors.col(k) = result.vectors.col(order[k]);
  }
  sorted.residual = max_residual(L, sorted.values, sorted.vectors);
  return sorted;
}

}  // namespace dresskit::segmentation
