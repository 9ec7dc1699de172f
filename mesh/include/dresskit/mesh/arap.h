#pragma once
// As-rigid-as-possible fitting (Sorkine & Alexa, "As-rigid-as-possible surface modeling", SGP 2007):
// a mesh bent towards target positions while each vertex's ring keeps its rest shape up to a
// rotation, so that edges keep their lengths where the targets would stretch or fold them.
#include <Eigen/Core>

namespace dresskit::mesh {

struct ArapOptions {
  int iterations = 10;  ///< local (rotations) / global (positions) rounds, > 0
};

/// Positions x minimising Σ_edges Σ_{v ∈ {i, j}} |(x_i − x_j) − R_v (r_i − r_j)|² / (2 |r_i − r_j|²)
///                      + Σ_i weight_i |x_i − target_i|² / h²
/// over x and one rotation R_v per vertex (each edge seen by both its ends' rotations; weights
/// 1 / L0², not cotangents, so that a term is the edge's relative change), from x = target;
/// r = rest, h = the rest shape's mean edge length. An edge's term is its relative change of shape squared; weight_i = 1 makes moving a
/// vertex one mean edge away from its target cost as much as one edge stretched by 100 %; weight 0
/// leaves a vertex to its neighbours. A mesh piece with no positive weight keeps its targets' mean
/// position. rest, target: #V×3; F: #F×3; weights: #V, ≥ 0.
Eigen::MatrixX3d arap_fit(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& target,
                          const Eigen::VectorXd& weights, const ArapOptions& options = {});

}  // namespace dresskit::mesh
