#pragma once
// Signed-distance primitives and their smooth union: the pure kernels behind the procedural scene.
// Distances are in metres, negative inside.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace dresskit::mannequin {

/// One solid: an ellipsoid (a = centre, b = semi-axes along x, y, z) or a round cone (a capsule whose
/// radius goes linearly from ra at end a to rb at end b).
struct Primitive {
  enum class Kind { ellipsoid, round_cone };
  Kind kind = Kind::ellipsoid;
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Ones();
  double ra = 0.0, rb = 0.0;  ///< [m] round cone radii at a and b
  int part = -1;              ///< label carried by surface points nearest to this primitive
  std::string name;           ///< e.g. "upper_arm_left"

  static Primitive ellipsoid(const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, int part,
                             std::string name);
  static Primitive round_cone(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra,
                              double rb, int part, std::string name);

  /// Signed distance [m]: exact for the round cone; for the ellipsoid a bound that is exact on the
  /// surface's normal direction near the surface (Quilez's k0·(k0−1)/k1 form).
  double distance(const Eigen::Vector3d& p) const;
  /// A box that contains the primitive.
  Eigen::AlignedBox3d bounds() const;
};

/// Polynomial smooth minimum with blend width k [m]: equals min(a, b) when |a − b| ≥ k and is never
/// above it, so a smooth union contains the plain union.
double smooth_min(double a, double b, double k);

/// Smooth union of primitives, offset outwards by `offset` [m]: f(p) = smin_i d_i(p) − offset.
struct ImplicitUnion {
  std::vector<Primitive> primitives;
  double blend = 0.02;   ///< smooth_min width [m]
  double offset = 0.0;   ///< [m]

  double value(const Eigen::Vector3d& p) const;
  /// Index of the primitive nearest to p (smallest distance).
  int nearest(const Eigen::Vector3d& p) const;
  /// values(i) = value(points.row(i)); the ScalarField form used by marching_tetrahedra.
  void evaluate(const Eigen::MatrixX3d& points, Eigen::VectorXd& values) const;
  /// A box that contains the zero set, padded by `pad` [m].
  Eigen::AlignedBox3d bounds(double pad) const;
};

}  // namespace dresskit::mannequin
