#include "dresskit/mannequin/implicit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dresskit::mannequin {

Primitive Primitive::ellipsoid(const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, int part,
                               std::string name) {
  Primitive p;
  p.kind = Kind::ellipsoid;
  p.a = centre;
  p.b = radii;
  p.part = part;
  p.name = std::move(name);
  return p;
}

Primitive Primitive::round_cone(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra,
                                double rb, int part, std::string name) {
  Primitive p;
  p.kind = Kind::round_cone;
  p.a = a;
  p.b = b;
  p.ra = ra;
  p.rb = rb;
  p.part = part;
  p.name = std::move(name);
  return p;
}

double Primitive::distance(const Eigen::Vector3d& p) const {
  if (kind == Kind::ellipsoid) {
    const Eigen::Vector3d q = p - a;
    const double k0 = q.cwiseQuotient(b).norm();
    const double k1 = q.cwiseQuotient(b.cwiseProduct(b)).norm();
    if (k1 < 1e-12) return -b.minCoeff();
    return k0 * (k0 - 1.0) / k1;
  }
  // Round cone: the exact distance to the convex hull of two spheres (a, ra) and (b, rb).
  const Eigen::Vector3d ba = b - a, pa = p - a;
  const double l2 = ba.squaredNorm();
  const double rr = ra - rb;
  const double a2 = l2 - rr * rr;
  const double y = pa.dot(ba), z = y - l2;
  const double x2 = (pa * l2 - ba * y).squaredNorm();
  const double y2 = y * y * l2, z2 = z * z * l2;
  const double k = (rr > 0 ? 1.0 : rr < 0 ? -1.0 : 0.0) * rr * rr * x2;
  if ((z > 0 ? 1.0 : z < 0 ? -1.0 : 0.0) * a2 * z2 > k) return std::sqrt(x2 + z2) / l2 - rb;
  if ((y > 0 ? 1.0 : y < 0 ? -1.0 : 0.0) * a2 * y2 < k) return std::sqrt(x2 + y2) / l2 - ra;
  return (std::sqrt(x2 * a2 / l2) + y * rr) / l2 - ra;
}

Eigen::AlignedBox3d Primitive::bounds() const {
  if (kind == Kind::ellipsoid) return {a - b, a + b};
  Eigen::AlignedBox3d box(a.array() - ra, a.array() + ra);
  box.extend(Eigen::AlignedBox3d(b.array() - rb, b.array() + rb));
  return box;
}

double smooth_min(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - 0.25 * h * h * k;
}

double ImplicitUnion::value(const Eigen::Vector3d& p) const {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& prim : primitives) {
    const double di = prim.distance(p);
    d = std::isinf(d) ? di : smooth_min(d, di, blend);
  }
  return d - offset;
}

int ImplicitUnion::nearest(const Eigen::Vector3d& p) const {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < primitives.size(); ++i) {
    const double d = primitives[i].distance(p);
    if (d < best_d) {
      best_d = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void ImplicitUnion::evaluate(const Eigen::MatrixX3d& points, Eigen::VectorXd& values) const {
  values.resize(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) values(i) = value(points.row(i).transpose());
}

Eigen::AlignedBox3d ImplicitUnion::bounds(double pad) const {
  Eigen::AlignedBox3d box;
  for (const auto& prim : primitives) box.extend(prim.bounds());
  box.min().array() -= offset + blend + pad;
  box.max().array() += offset + blend + pad;
  return box;
}

}  // namespace dresskit::mannequin
