#pragma once
// Helpers shared by the simulator's translation units (simulator*.cpp, the integrators' files).
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

namespace dresskit::cloth::detail {

inline Eigen::Vector3d row(const Eigen::MatrixX3d& m, int i) { return m.row(i).transpose(); }

// Adds a 3×3 block at block position (bi, bj) of a 3n × 3n matrix.
inline void add_block(std::vector<Eigen::Triplet<double>>& t, int bi, int bj, const Eigen::Matrix3d& b) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) t.emplace_back(3 * bi + r, 3 * bj + c, b(r, c));
}

// The four blocks of a spring i–j whose ∂f_i/∂x_i (or ∂f_i/∂v_i) is −B: +B on the diagonal blocks,
// −B off the diagonal (the sign convention of a stiffness matrix K = −∂f/∂x).
inline void add_spring_blocks(std::vector<Eigen::Triplet<double>>& t, int i, int j,
                              const Eigen::Matrix3d& B) {
  add_block(t, i, i, B);
  add_block(t, j, j, B);
  add_block(t, i, j, -B);
  add_block(t, j, i, -B);
}

}  // namespace dresskit::cloth::detail
