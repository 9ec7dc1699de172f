#include "dresskit/cloth/geometry.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace dresskit {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          Eigen::Vector3d* bary) {
  auto out = [&](double u, double v, double w) {
    if (bary) *bary = Eigen::Vector3d(u, v, w);
    return Eigen::Vector3d(u * a + v * b + w * c);
  };
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return out(1, 0, 0);
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return out(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return out(1 - v, v, 0);
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return out(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return out(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return out(0, 1 - w, w);
  }
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return out(1, 0, 0);  // degenerate triangle: its first corner
  const double v = vb / denom, w = vc / denom;
  return out(1 - v - w, v, w);
}

double closest_points_of_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, double* s_out,
                                  double* t_out) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  const double eps = 1e-30;
  if (a <= eps && e <= eps) {
    s = t = 0.0;
  } else if (a <= eps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= eps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > eps ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  *s_out = s;
  *t_out = t;
  return (p0 + s * d1 - (q0 + t * d2)).squaredNorm();
}

namespace {
double orient(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}
}  // namespace

bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
  if (!(sp > 0.0 && sq < 0.0) && !(sp < 0.0 && sq > 0.0)) return false;  // same side or touching
  // The line p–q passes inside the triangle when it sees the three edges with the same orientation.
  const double e0 = orient(p, q, a, b), e1 = orient(p, q, b, c), e2 = orient(p, q, c, a);
  return (e0 > 0.0 && e1 > 0.0 && e2 > 0.0) || (e0 < 0.0 && e1 < 0.0 && e2 < 0.0);
}

}  // namespace dresskit
