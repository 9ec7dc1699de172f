#pragma once
// Colliders: analytic ones (plane, sphere, axis-aligned box, capped cylinder) and body meshes (a precomputed signed
// distance, cloth/mesh_distance.h), each with a signed distance, an outward normal and friction.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "dresskit/cloth/mesh_distance.h"

namespace dresskit::cloth {

struct Collider {
  enum class Kind { plane, sphere, box, cylinder, mesh };
  Kind kind = Kind::plane;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     ///< plane point, sphere, box or cylinder centre [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();   ///< plane normal, cylinder axis (unit)
  double radius = 0.0;                                 ///< sphere or cylinder radius [m]
  double half_length = 0.0;                            ///< cylinder: half its length along the axis [m]
  Eigen::Vector3d half_size = Eigen::Vector3d::Zero(); ///< box half extents [m]
  std::shared_ptr<const MeshDistance> body;            ///< mesh colliders: the body's distance
  double friction = 0.3;         ///< kinetic Coulomb coefficient [unitless]
  /// Static coefficient [unitless]: a sliding particle whose tangential speed is at most this × the
  /// normal speed the contact removed stops; a negative value means "the same as friction".
  double static_friction = -1.0;
  /// Penalty force a in f = m a (exp(depth / δ) − 1) n on a particle closer than the collision
  /// margin + δ (SimulationOptions::penalty_thickness), depth measured from there [m/s²]; 0 = none.
  /// Mesh colliders default to 20 (the particle rests about 0.6 δ above the margin), analytic ones 0.
  double penalty = 0.0;

  static Collider plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double friction = 0.3);
  static Collider sphere(const Eigen::Vector3d& centre, double radius, double friction = 0.3);
  static Collider box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_size, double friction = 0.3);
  /// A solid cylinder with flat caps.
  static Collider cylinder(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double radius,
                           double half_length, double friction = 0.3);
  /// A body: fabric on skin, μ = 0.5 by default (measured fabric–skin coefficients lie around
  /// 0.3–0.6; at 0.3 a square dropped onto a head slid off it within 2 s, at 0.5 it stays on).
  static Collider mesh(std::shared_ptr<const MeshDistance> body, double friction = 0.5);

  /// Signed distance [m] from p to the surface (negative inside) and the outward unit normal there.
  /// `cell`: a mesh collider's lookup cache for the particle at p (MeshDistance::Cell), or null;
  /// the other kinds do not use it.
  double distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward, MeshDistance::Cell* cell = nullptr) const;
};

}  // namespace dresskit::cloth
