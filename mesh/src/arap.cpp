#include "dresskit/mesh/arap.h"

#include <Eigen/SVD>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <utility>
#include <vector>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"

namespace dresskit::mesh {

Eigen::MatrixX3d arap_fit(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& target,
                          const Eigen::VectorXd& weights, const ArapOptions& options) {
  const Eigen::Index n = rest.rows();
  if (target.rows() != n || weights.size() != n)
    throw InputError("arap: rest, target and weights must have one row per vertex");
  if (options.iterations <= 0) throw InputError("arap: iterations must be positive");
  if (n == 0 || F.rows() == 0) return target;

  // Edges, each once, with weight 1 / L0².
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> w(edges.size(), 0.0);
  double h = 0.0;
  int counted = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const double L0 = (rest.row(edges[e].first) - rest.row(edges[e].second)).norm();
    if (!(L0 > 0.0)) continue;
    w[e] = 1.0 / (L0 * L0);
    h += L0;
    ++counted;
  }
  if (counted == 0) return target;
  h /= counted;

  // Global matrix: the weighted graph Laplacian plus the anchors. A piece without anchors gets a
  // tiny one on every vertex, so that the system is definite and the piece keeps its place.
  int pieces = 0;
  const std::vector<int> face_piece = face_components(F, static_cast<int>(n), &pieces);
  std::vector<int> piece(static_cast<std::size_t>(n), pieces);  // pieces: a vertex of no face
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) piece[static_cast<std::size_t>(F(f, k))] = face_piece[static_cast<std::size_t>(f)];
  std::vector<char> anchored(static_cast<std::size_t>(pieces) + 1, 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(weights(i) >= 0.0)) throw InputError("arap: weights must be 0 or more");
    if (weights(i) > 0.0) anchored[static_cast<std::size_t>(piece[static_cast<std::size_t>(i)])] = 1;
  }
  Eigen::VectorXd anchor(n);
  for (Eigen::Index i = 0; i < n; ++i)
    anchor(i) = (anchored[static_cast<std::size_t>(piece[static_cast<std::size_t>(i)])] ? weights(i) : 1e-6) / (h * h);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(4 * edges.size() + static_cast<std::size_t>(n));
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    triplets.emplace_back(a, a, w[e]);
    triplets.emplace_back(b, b, w[e]);
    triplets.emplace_back(a, b, -w[e]);
    triplets.emplace_back(b, a, -w[e]);
  }
  for (Eigen::Index i = 0; i < n; ++i) triplets.emplace_back(i, i, anchor(i));
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) throw InputError("arap: the fitting system cannot be factored");

  Eigen::MatrixX3d x = target;
  std::vector<Eigen::Matrix3d> R(static_cast<std::size_t>(n));
  for (int it = 0; it < options.iterations; ++it) {
    // Local: each vertex's best rotation of its rest edges onto its current ones.
    std::vector<Eigen::Matrix3d> S(static_cast<std::size_t>(n), Eigen::Matrix3d::Zero());
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [a, b] = edges[e];
      const Eigen::Vector3d r = (rest.row(a) - rest.row(b)).transpose();
      const Eigen::Vector3d d = (x.row(a) - x.row(b)).transpose();
      const Eigen::Matrix3d outer = w[e] * d * r.transpose();
      S[static_cast<std::size_t>(a)] += outer;
      S[static_cast<std::size_t>(b)] += outer;
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(S[static_cast<std::size_t>(i)], Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::Matrix3d U = svd.matrixU();
      if ((U * svd.matrixV().transpose()).determinant() < 0.0) U.col(2) *= -1.0;
      R[static_cast<std::size_t>(i)] = U * svd.matrixV().transpose();
    }
    // Global: positions whose edges best match the rotated rest edges, pulled to the targets.
    Eigen::MatrixX3d rhs = target.array().colwise() * anchor.array();
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [a, b] = edges[e];
      const Eigen::Vector3d r = (rest.row(a) - rest.row(b)).transpose();
      const Eigen::Vector3d g = 0.5 * w[e] * (R[static_cast<std::size_t>(a)] + R[static_cast<std::size_t>(b)]) * r;
      rhs.row(a) += g.transpose();
      rhs.row(b) -= g.transpose();
    }
    x = solver.solve(rhs);
  }
  return x;
}

}  // namespace dresskit::mesh
