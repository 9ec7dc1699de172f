#include "dresskit/cloth/spring_kernels.h"

#include <Eigen/Geometry>

namespace dresskit::cloth {
namespace {
constexpr double kTiny = 1e-12;  // [m] below this a spring has no direction: no force
}

double spring_energy(const StiffnessLaw& law, double L0, const Eigen::Vector3d& xi,
                     const Eigen::Vector3d& xj) {
  return law.energy((xj - xi).norm(), L0);
}

Eigen::Vector3d spring_force(const StiffnessLaw& law, double L0, const Eigen::Vector3d& xi,
                             const Eigen::Vector3d& xj, double allowed_length) {
  const Eigen::Vector3d d = xj - xi;
  const double L = d.norm();
  if (L < kTiny) return Eigen::Vector3d::Zero();
  double t = law.tension(L, L0);
  if (allowed_length > 0.0 && L > allowed_length) t *= L / L0;
  return (t / L) * d;
}

Eigen::Matrix3d spring_jacobian(const StiffnessLaw& law, double L0, const Eigen::Vector3d& xi,
                                const Eigen::Vector3d& xj, double allowed_length,
                                bool clamp_geometric) {
  const Eigen::Vector3d d = xj - xi;
  const double L = d.norm();
  if (L < kTiny) return Eigen::Matrix3d::Zero();
  const Eigen::Vector3d u = d / L;
  double t = law.tension(L, L0), dt = law.tension_derivative(L, L0);
  if (allowed_length > 0.0 && L > allowed_length) {
    dt = dt * L / L0 + t / L0;
    t *= L / L0;
  }
  double transverse = t / L;
  if (clamp_geometric) transverse = std::max(transverse, 0.0);
  const Eigen::Matrix3d uu = u * u.transpose();
  // f_i = t(L) u with ∂L/∂xi = −u and ∂u/∂xi = −(I − uuᵀ)/L.
  return -dt * uu - transverse * (Eigen::Matrix3d::Identity() - uu);
}

Eigen::Vector3d spring_damping_force(double kd, const Eigen::Vector3d& xi, const Eigen::Vector3d& xj,
                                     const Eigen::Vector3d& vi, const Eigen::Vector3d& vj) {
  const Eigen::Vector3d d = xj - xi;
  const double L = d.norm();
  if (L < kTiny) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d u = d / L;
  return -kd * (vi - vj).dot(u) * u;
}

}  // namespace dresskit::cloth
