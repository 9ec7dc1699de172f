#pragma once
// Pure per-spring kernels: energy, force and force Jacobian of one spring i–j, side by side.
#include <Eigen/Core>

#include "dresskit/cloth/stiffness_law.h"

namespace dresskit::cloth {

/// Elastic energy [J] of the spring with ends at xi, xj.
double spring_energy(const StiffnessLaw& law, double L0, const Eigen::Vector3d& xi,
                     const Eigen::Vector3d& xj);

/// Force on end i [N] (the force on j is its negative): tension · (xj − xi)/|xj − xi|.
/// With dynamic stiffness on (allowed_length > 0) and L > allowed_length, the tension is scaled by
/// L/L0 (methods.md §1: k_new = k·L/L0); this modified force has no energy.
Eigen::Vector3d spring_force(const StiffnessLaw& law, double L0, const Eigen::Vector3d& xi,
                             const Eigen::Vector3d& xj, double allowed_length = 0.0);

/// ∂(force on i)/∂xi, a 3×3 block (∂f_i/∂xj is its negative; ∂f_j/∂xj equals it). With
/// clamp_geometric the transverse term tension/L is clamped at 0 for compressed springs, which keeps
/// the assembled stiffness matrix negative semi-definite for implicit solvers.
Eigen::Matrix3d spring_jacobian(const StiffnessLaw& law, double L0, const Eigen::Vector3d& xi,
                                const Eigen::Vector3d& xj, double allowed_length = 0.0,
                                bool clamp_geometric = false);

/// Damping force on end i [N] along the spring: −kd ((vi − vj)·u) u, u = (xj − xi)/|xj − xi|.
Eigen::Vector3d spring_damping_force(double kd, const Eigen::Vector3d& xi, const Eigen::Vector3d& xj,
                                     const Eigen::Vector3d& vi, const Eigen::Vector3d& vj);

}  // namespace dresskit::cloth
