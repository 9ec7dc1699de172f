// Projective dynamics' global solve on the error bench's 81×81 cloth (6,561 vertices): Eigen's
// SimplicialLLT solve of the three coordinate columns against the interleaved factor
// (cloth/src/interleaved_cholesky.h) in double and single precision, with the bending springs'
// couplings in the matrix and without (projective.cpp lags them). CPU time of this thread per
// solve, median of 9 rounds of 50 solves. Usage: bench_cloth_solve
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "bench_common.h"
#include "dresskit/cloth/simulator.h"
#include "interleaved_cholesky.h"

using namespace dresskit;
using namespace dresskit::cloth;

namespace {
template <typename Solve>
double median_ms(Solve solve) {
  std::vector<double> rounds;
  for (int r = 0; r < 9; ++r) {
    const double t0 = bench::thread_cpu_seconds();
    for (int i = 0; i < 50; ++i) solve();
    rounds.push_back((bench::thread_cpu_seconds() - t0) / 50 * 1e3);
  }
  std::sort(rounds.begin(), rounds.end());
  return rounds[4];
}
}  // namespace

int main() {
  const int n = 81, N = n * n;
  const ClothModel model = build_cloth(make_grid({1.0, 1.0}, {n, n}, {0, 0, 0}, {0, 0, 1}),
                                       fabric_by_name("gray-interlock"));
  const SpringSet& s = model.springs;
  const double h = 1.0 / 60;
  for (bool bending : {true, false}) {
    std::vector<Eigen::Triplet<double>> t;
    for (int v = 0; v < N; ++v) t.emplace_back(v, v, model.mass(v) / (h * h));
    for (int k = 0; k < s.size(); ++k) {
      const double w = s.k_knee[k];
      t.emplace_back(s.i[k], s.i[k], w);
      t.emplace_back(s.j[k], s.j[k], w);
      if (!bending && s.type[k] == SpringType::bending) continue;
      t.emplace_back(s.i[k], s.j[k], -w);
      t.emplace_back(s.j[k], s.i[k], -w);
    }
    Eigen::SparseMatrix<double> A(N, N);
    A.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(A);
    detail::InterleavedCholesky<float> single;
    detail::InterleavedCholesky<double> full;
    if (llt.info() != Eigen::Success || !single.compute(A) || !full.compute(A)) {
      std::fprintf(stderr, "factorisation failed\n");
      return 1;
    }
    const Eigen::MatrixX3d B = Eigen::MatrixX3d::Random(N, 3);
    Eigen::MatrixX3d X;
    std::vector<double> b(3 * static_cast<std::size_t>(N), 1.0);
    const double eigen_ms = median_ms([&] { X = llt.solve(B); });
    const double full_ms = median_ms([&] { full.solve_in_place(b.data()); });
    const double single_ms = median_ms([&] { single.solve_in_place(b.data()); });
    std::printf(
        "bending couplings in the matrix: %-3s factor %ld entries; solve (3 columns, CPU ms): "
        "Eigen LLT %.3f, interleaved double %.3f, interleaved single %.3f\n",
        bending ? "yes" : "no", single.factor_nonzeros(), eigen_ms, full_ms, single_ms);
  }
  return 0;
}
