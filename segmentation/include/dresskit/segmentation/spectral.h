#pragma once
// The smallest eigenpairs of a graph Laplacian (Spectra, shift-invert; Spectra stays private).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <stdexcept>
#include <string>

namespace dresskit::segmentation {

enum class LaplacianKind {
  normalized,  ///< L = I − D^{−1/2} W D^{−1/2} (default: eigenvalues in [0, 2], scale-free)
  plain,       ///< L = D − W
};
/// "normalized" / "normalised", "plain"; throws InputError naming the value otherwise.
LaplacianKind parse_laplacian(const std::string& text);
std::string to_string(LaplacianKind kind);

struct EigenOptions {
  double tolerance = 1e-10;   ///< Spectra's relative tolerance on the Ritz values
  int ncv = 0;                ///< Krylov subspace size; 0 = max(2·nev + 1, 20), at most #V
  int max_iterations = 1000;  ///< restarts of the implicitly restarted Lanczos method
  /// σ of the shift-invert, relative to the mean diagonal of L: the Laplacian is singular at 0, so
  /// σ < 0 keeps L − σI invertible (see ../shared/docs/pitfalls.md).
  double relative_shift = -1e-3;
  int dense_below = 200;  ///< graphs with fewer vertices use a dense solver
};

struct EigenResult {
  Eigen::VectorXd values;   ///< nev smallest eigenvalues, ascending
  Eigen::MatrixXd vectors;  ///< #V×nev unit eigenvectors
  double residual = 0.0;    ///< max over pairs of ‖L x − λ x‖
  int iterations = 0;       ///< Lanczos restarts (0 for the dense solver)
  int ncv = 0;              ///< subspace size of the successful attempt
  std::string method;       ///< "spectra shift-invert" or "dense"
};

/// Thrown when no attempt converged; the message lists every attempt (ncv, iterations, tolerance).
class EigenSolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The Laplacian of the symmetric affinity matrix W (#V×#V, zero diagonal, no empty rows).
Eigen::SparseMatrix<double> graph_laplacian(const Eigen::SparseMatrix<double>& W,
                                            LaplacianKind kind);

/// The nev smallest eigenpairs of the symmetric positive semi-definite L. Tries the options' ncv,
/// then twice the subspace and iterations; throws EigenSolverError listing what was tried.
EigenResult smallest_eigenpairs(const Eigen::SparseMatrix<double>& L, int nev,
                                const EigenOptions& options = {});

}  // namespace dresskit::segmentation
