#include "dresskit/cloth/collider.h"

#include <Eigen/Geometry>
#include <cmath>

#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/mesh/errors.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {

namespace {
Collider collider_of(Collider::Kind kind, const Eigen::Vector3d& point, double friction) {
  Collider c;
  c.kind = kind;
  c.point = point;
  c.friction = friction;
  return c;
}
}  // namespace

Collider Collider::plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double friction) {
  if (!point.allFinite() || !normal.allFinite() || normal.norm() < 1e-12) {
    throw InputError("plane collider: point and normal must be finite, the normal non-zero");
  }
  Collider c = collider_of(Kind::plane, point, friction);
  c.normal = normal.normalized();
  return c;
}

Collider Collider::sphere(const Eigen::Vector3d& centre, double radius, double friction) {
  if (!centre.allFinite() || !(radius > 0.0) || !std::isfinite(radius)) {
    throw InputError("sphere collider: centre must be finite and radius positive");
  }
  Collider c = collider_of(Kind::sphere, centre, friction);
  c.radius = radius;
  return c;
}

Collider Collider::box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_size, double friction) {
  if (!centre.allFinite() || !half_size.allFinite() || half_size.minCoeff() <= 0.0) {
    throw InputError("box collider: centre must be finite and every half size positive");
  }
  Collider c = collider_of(Kind::box, centre, friction);
  c.half_size = half_size;
  return c;
}

Collider Collider::cylinder(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double radius,
                            double half_length, double friction) {
  if (!centre.allFinite() || !axis.allFinite() || axis.norm() < 1e-12 || !(radius > 0.0) || !std::isfinite(radius) ||
      !(half_length > 0.0) || !std::isfinite(half_length)) {
    throw InputError("cylinder collider: centre finite, axis non-zero, radius and half_length positive");
  }
  Collider c = collider_of(Kind::cylinder, centre, friction);
  c.normal = axis.normalized();
  c.radius = radius;
  c.half_length = half_length;
  return c;
}

Collider Collider::mesh(std::shared_ptr<const MeshDistance> body, double friction) {
  if (!body) throw InputError("mesh collider: no body");
  Collider c = collider_of(Kind::mesh, Eigen::Vector3d::Zero(), friction);
  c.body = std::move(body);
  c.penalty = 20.0;
  return c;
}

double Collider::distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward, MeshDistance::Cell* cell) const {
  switch (kind) {
    case Kind::plane:
      *outward = normal;
      return (p - point).dot(normal);
    case Kind::sphere: {
      const Eigen::Vector3d d = p - point;
      const double r = d.norm();
      *outward = r > 1e-12 ? Eigen::Vector3d(d / r) : Eigen::Vector3d::UnitY();
      return r - radius;
    }
    case Kind::box: {
      const Eigen::Vector3d d = p - point;
      const Eigen::Vector3d q = d.cwiseAbs() - half_size;
      if (q.maxCoeff() > 0.0) {  // outside: distance to the nearest point of the box
        const Eigen::Vector3d outside = q.cwiseMax(0.0).cwiseProduct(d.cwiseSign());
        *outward = outside.normalized();
        return outside.norm();
      }
      int axis = 0;  // inside: leave through the nearest face
      q.maxCoeff(&axis);
      *outward = Eigen::Vector3d::Zero();
      (*outward)(axis) = d(axis) >= 0.0 ? 1.0 : -1.0;
      return q(axis);
    }
    case Kind::cylinder: {
      // In the cylinder's (radial, axial) half-plane it is a rectangle: the box rule in 2D.
      const Eigen::Vector3d d = p - point;
      const double a = d.dot(normal);
      Eigen::Vector3d radial = d - a * normal;
      const double rho = radial.norm();
      radial = rho > 1e-12 ? Eigen::Vector3d(radial / rho) : normal.unitOrthogonal();
      const double qr = rho - radius, qa = std::abs(a) - half_length;
      const Eigen::Vector3d along = (a >= 0.0 ? 1.0 : -1.0) * normal;
      if (qr > 0.0 || qa > 0.0) {
        const Eigen::Vector3d outside = std::max(qr, 0.0) * radial + std::max(qa, 0.0) * along;
        *outward = outside.normalized();
        return outside.norm();
      }
      *outward = qr > qa ? radial : along;
      return std::max(qr, qa);
    }
    case Kind::mesh:
      return body->distance(p, outward, cell);
  }
  return 0.0;
}

}  // namespace dresskit::cloth
