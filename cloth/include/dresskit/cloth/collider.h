#pragma once
// Analytic colliders: plane, sphere and axis-aligned box, with signed distance and outward normal.
#include <Eigen/Core>
#include <string>

namespace dresskit {

struct Collider {
  enum class Kind { plane, sphere, box };
  Kind kind = Kind::plane;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     ///< plane point, sphere or box centre [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();   ///< plane normal (unit)
  double radius = 0.0;                                 ///< sphere radius [m]
  Eigen::Vector3d half_size = Eigen::Vector3d::Zero(); ///< box half extents [m]
  double friction = 0.3;                               ///< Coulomb coefficient [unitless]

  static Collider plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double friction = 0.3);
  static Collider sphere(const Eigen::Vector3d& centre, double radius, double friction = 0.3);
  static Collider box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_size, double friction = 0.3);

  /// Signed distance [m] from p to the surface (negative inside) and the outward unit normal there.
  double distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward) const;
};

}  // namespace dresskit
