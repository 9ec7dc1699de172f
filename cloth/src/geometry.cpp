#include "dresskit/cloth/geometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace dresskit::cloth {

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

namespace {

double cubic(const double c[4], double t) { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }

/// Coefficients of the cubic (u(t) × w(t)) · r(t) for u, w, r linear in t (u = u0 + t du, ...).
void triple_product_cubic(const Eigen::Vector3d& u0, const Eigen::Vector3d& du, const Eigen::Vector3d& w0,
                          const Eigen::Vector3d& dw, const Eigen::Vector3d& r0, const Eigen::Vector3d& dr,
                          double c[4]) {
  const Eigen::Vector3d k0 = u0.cross(w0), k1 = u0.cross(dw) + du.cross(w0), k2 = du.cross(dw);
  c[0] = k0.dot(r0);
  c[1] = k0.dot(dr) + k1.dot(r0);
  c[2] = k1.dot(dr) + k2.dot(r0);
  c[3] = k2.dot(dr);
}

Eigen::Vector3d lerp(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t) { return a + t * (b - a); }

/// Insertion sort of a few numbers (std::sort on a small fixed array trips GCC 12's bounds warning).
void sort_few(double* v, int n) {
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && v[j] < v[j - 1]; --j) std::swap(v[j], v[j - 1]);
}

}  // namespace

int cubic_candidates(const double c[4], double out[5]) {
  // Break [0, 1] at the derivative's roots: f is monotone between breaks.
  double br[4];
  int nb = 0;
  br[nb++] = 0.0;
  const double A = 3.0 * c[3], B = 2.0 * c[2], C = c[1];
  double crit[2];
  int nc = 0;
  if (std::abs(A) > 1e-300) {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      const double sq = std::sqrt(disc);
      // Numerically stable pair of roots.
      const double q = -0.5 * (B + (B >= 0.0 ? sq : -sq));
      crit[nc++] = q / A;
      if (q != 0.0) crit[nc++] = C / q;
    }
  } else if (std::abs(B) > 1e-300) {
    crit[nc++] = -C / B;
  }
  if (nc == 2 && crit[0] > crit[1]) std::swap(crit[0], crit[1]);
  for (int k = 0; k < nc; ++k)
    if (crit[k] > 0.0 && crit[k] < 1.0) br[nb++] = crit[k];
  br[nb++] = 1.0;
  int n = 0;
  for (int k = 0; k + 1 < nb; ++k) {
    double lo = br[k], hi = br[k + 1];
    double flo = cubic(c, lo), fhi = cubic(c, hi);
    if (k > 0) out[n++] = lo;  // an interior extremum: a touching root if f is (nearly) zero there
    if ((flo < 0.0 && fhi > 0.0) || (flo > 0.0 && fhi < 0.0)) {
      for (int it = 0; it < 52 && hi - lo > 1e-12; ++it) {
        const double mid = 0.5 * (lo + hi), fm = cubic(c, mid);
        if ((fm < 0.0) == (flo < 0.0)) {
          lo = mid;
          flo = fm;
        } else {
          hi = mid;
        }
      }
      out[n++] = 0.5 * (lo + hi);
    }
  }
  sort_few(out, n);
  return n;
}

namespace {
/// The times to test along a step for a contact of two primitives whose relative vectors are
/// u0 + t du, w0 + t dw, r0 + t dr: the step's ends and where the three become coplanar, in order.
int contact_times(const Eigen::Vector3d& u0, const Eigen::Vector3d& du, const Eigen::Vector3d& w0,
                  const Eigen::Vector3d& dw, const Eigen::Vector3d& r0, const Eigen::Vector3d& dr, double times[7]) {
  double c[4];
  triple_product_cubic(u0, du, w0, dw, r0, dr, c);
  int n = 0;
  times[n++] = 0.0;
  n += cubic_candidates(c, times + n);
  times[n++] = 1.0;
  sort_few(times, n);
  return n;
}
}  // namespace

Contact vertex_triangle_ccd(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& a0,
                            const Eigen::Vector3d& a1, const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                            const Eigen::Vector3d& c0, const Eigen::Vector3d& c1, double eta) {
  double times[7];
  const int n = contact_times(b0 - a0, (b1 - a1) - (b0 - a0), c0 - a0, (c1 - a1) - (c0 - a0), p0 - a0,
                              (p1 - a1) - (p0 - a0), times);
  Contact hit;
  for (int k = 0; k < n; ++k) {
    const double t = times[k];
    const Eigen::Vector3d p = lerp(p0, p1, t), a = lerp(a0, a1, t), b = lerp(b0, b1, t), cc = lerp(c0, c1, t);
    Eigen::Vector3d bary;
    const Eigen::Vector3d q = closest_point_on_triangle(p, a, b, cc, &bary);
    if ((p - q).squaredNorm() >= eta * eta) continue;
    hit.t = t;
    hit.w[0] = 1.0;
    hit.w[1] = bary[0], hit.w[2] = bary[1], hit.w[3] = bary[2];
    Eigen::Vector3d n_t = (b - a).cross(cc - a);
    if (n_t.squaredNorm() < 1e-40) n_t = p - q;  // degenerate triangle: along the gap
    // Side A (the vertex) on the positive side at the start; if it started in the plane, against
    // the approach.
    const Eigen::Vector3d q0 = bary[0] * a0 + bary[1] * b0 + bary[2] * c0;
    double side = n_t.dot(p0 - q0);
    if (std::abs(side) < 1e-300) side = -n_t.dot((p1 - p0) - (bary[0] * (a1 - a0) + bary[1] * (b1 - b0) + bary[2] * (c1 - c0)));
    hit.normal = (side >= 0.0 ? 1.0 : -1.0) * n_t.normalized();
    return hit;
  }
  return hit;
}

Contact edge_edge_ccd(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                      const Eigen::Vector3d& q1, const Eigen::Vector3d& r0, const Eigen::Vector3d& r1,
                      const Eigen::Vector3d& s0, const Eigen::Vector3d& s1, double eta) {
  double times[7];
  const int n = contact_times(q0 - p0, (q1 - p1) - (q0 - p0), s0 - r0, (s1 - r1) - (s0 - r0), r0 - p0,
                              (r1 - p1) - (r0 - p0), times);
  Contact hit;
  for (int k = 0; k < n; ++k) {
    const double t = times[k];
    const Eigen::Vector3d p = lerp(p0, p1, t), q = lerp(q0, q1, t), r = lerp(r0, r1, t), s = lerp(s0, s1, t);
    double a, b;
    if (closest_points_of_segments(p, q, r, s, &a, &b) >= eta * eta) continue;
    hit.t = t;
    hit.w[0] = 1.0 - a, hit.w[1] = a, hit.w[2] = 1.0 - b, hit.w[3] = b;
    Eigen::Vector3d n_t = (q - p).cross(s - r);
    const Eigen::Vector3d gap = (p + a * (q - p)) - (r + b * (s - r));
    if (n_t.squaredNorm() < 1e-12 * (q - p).squaredNorm() * (s - r).squaredNorm()) n_t = gap;  // parallel edges
    if (n_t.squaredNorm() < 1e-40) n_t = (q - p).unitOrthogonal();
    const Eigen::Vector3d gap0 = (p0 + a * (q0 - p0)) - (r0 + b * (s0 - r0));
    double side = n_t.dot(gap0);
    if (std::abs(side) < 1e-300) {
      const Eigen::Vector3d rel = ((p1 - p0) + a * ((q1 - p1) - (q0 - p0))) - ((r1 - r0) + b * ((s1 - r1) - (s0 - r0)));
      side = -n_t.dot(rel);
    }
    hit.normal = (side >= 0.0 ? 1.0 : -1.0) * n_t.normalized();
    return hit;
  }
  return hit;
}

void shift_weighted_difference(Eigen::MatrixX3d& x, const Eigen::VectorXd& inverse_mass, const int idx[4],
                               const double alpha[4], const Eigen::Vector3d& change) {
  double S = 0.0;
  for (int k = 0; k < 4; ++k) S += alpha[k] * alpha[k] * inverse_mass[idx[k]];
  if (!(S > 0.0)) return;
  for (int k = 0; k < 4; ++k) {
    const double share = alpha[k] * inverse_mass[idx[k]] / S;
    if (share != 0.0) x.row(idx[k]) += share * change.transpose();
  }
}

}  // namespace dresskit::cloth
