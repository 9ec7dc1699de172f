#include "dresskit/pattern/curves.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace dresskit::pattern {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// An arc's centre, radius and start angle and signed sweep [rad], as SVG defines an arc between
/// two points (a radius too small for the chord grows to half the chord).
struct ArcGeometry {
  Eigen::Vector2d centre;
  double radius, angle0, sweep;
};

ArcGeometry arc_geometry(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Edge& e) {
  const Eigen::Vector2d chord = p1 - p0;
  const double half = 0.5 * chord.norm();
  const double r = std::max(e.radius, half);
  const Eigen::Vector2d u = chord / (2.0 * half);
  const Eigen::Vector2d left(-u.y(), u.x());
  const double h = std::sqrt(std::max(0.0, r * r - half * half));
  // SVG arc implementation notes (F.6.5): the centre lies left of the chord when the flags differ.
  const double side = e.large_arc != e.counter_clockwise ? 1.0 : -1.0;
  ArcGeometry g;
  g.centre = 0.5 * (p0 + p1) + side * h * left;
  g.radius = r;
  g.angle0 = std::atan2(p0.y() - g.centre.y(), p0.x() - g.centre.x());
  const double angle1 = std::atan2(p1.y() - g.centre.y(), p1.x() - g.centre.x());
  double d = angle1 - g.angle0;
  if (e.counter_clockwise) {
    while (d <= 0.0) d += 2.0 * kPi;
  } else {
    while (d >= 0.0) d -= 2.0 * kPi;
  }
  g.sweep = d;
  return g;
}

Eigen::Vector2d bezier_point(const Eigen::Vector2d& p0, const Edge& e, const Eigen::Vector2d& p1,
                             double u) {
  const double s = 1.0 - u;
  if (e.kind == CurveKind::quadratic) return s * s * p0 + 2.0 * s * u * e.controls[0] + u * u * p1;
  return s * s * s * p0 + 3.0 * s * s * u * e.controls[0] + 3.0 * s * u * u * e.controls[1] +
         u * u * u * p1;
}

Eigen::Vector2d bezier_velocity(const Eigen::Vector2d& p0, const Edge& e, const Eigen::Vector2d& p1,
                                double u) {
  const double s = 1.0 - u;
  if (e.kind == CurveKind::quadratic)
    return 2.0 * s * (e.controls[0] - p0) + 2.0 * u * (p1 - e.controls[0]);
  return 3.0 * s * s * (e.controls[0] - p0) + 6.0 * s * u * (e.controls[1] - e.controls[0]) +
         3.0 * u * u * (p1 - e.controls[1]);
}

// 8-point Gauss–Legendre nodes and weights on [−1, 1].
constexpr double kNodes[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                              -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                              0.7966664774136267,  0.9602898564975363};
constexpr double kWeights[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                0.2223810344533745, 0.1012285362903763};
constexpr int kPieces = 32;

/// Bézier arc length from u = a to u = b.
double bezier_length(const Eigen::Vector2d& p0, const Edge& e, const Eigen::Vector2d& p1, double a,
                     double b) {
  double sum = 0.0;
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  for (int k = 0; k < 8; ++k)
    sum += kWeights[k] * bezier_velocity(p0, e, p1, m + h * kNodes[k]).norm();
  return sum * h;
}

/// Cumulative Bézier length at u = i / kPieces, i = 0..kPieces.
std::vector<double> bezier_table(const Eigen::Vector2d& p0, const Edge& e,
                                 const Eigen::Vector2d& p1) {
  std::vector<double> c(kPieces + 1, 0.0);
  for (int i = 0; i < kPieces; ++i)
    c[i + 1] = c[i] + bezier_length(p0, e, p1, double(i) / kPieces, double(i + 1) / kPieces);
  return c;
}

/// The Bézier parameter at arc length s, by Newton's method inside the piece that holds s.
double bezier_parameter(const Eigen::Vector2d& p0, const Edge& e, const Eigen::Vector2d& p1,
                        const std::vector<double>& table, double s) {
  const int i = std::clamp(int(std::upper_bound(table.begin(), table.end(), s) - table.begin()) - 1,
                           0, kPieces - 1);
  const double a = double(i) / kPieces, b = double(i + 1) / kPieces;
  double u = a + (b - a) * (s - table[i]) / std::max(table[i + 1] - table[i], 1e-300);
  for (int it = 0; it < 30; ++it) {
    const double f = table[i] + bezier_length(p0, e, p1, a, u) - s;
    const double speed = bezier_velocity(p0, e, p1, u).norm();
    if (speed <= 0.0) break;
    const double next = std::clamp(u - f / speed, a, b);
    if (std::abs(next - u) < 1e-15) break;
    u = next;
  }
  return u;
}

}  // namespace

Eigen::Vector2d edge_point(const Panel& panel, int edge, double u) {
  const Edge& e = panel.edges[edge];
  const Eigen::Vector2d p0 = panel.vertices.row(e.start).transpose(),
                        p1 = panel.vertices.row(e.end).transpose();
  switch (e.kind) {
    case CurveKind::straight:
      return (1.0 - u) * p0 + u * p1;
    case CurveKind::quadratic:
    case CurveKind::cubic:
      return bezier_point(p0, e, p1, u);
    case CurveKind::arc: {
      const ArcGeometry g = arc_geometry(p0, p1, e);
      if (u <= 0.0) return p0;
      if (u >= 1.0) return p1;
      const double a = g.angle0 + u * g.sweep;
      return g.centre + g.radius * Eigen::Vector2d(std::cos(a), std::sin(a));
    }
  }
  return p0;
}

double edge_length(const Panel& panel, int edge) {
  const Edge& e = panel.edges[edge];
  const Eigen::Vector2d p0 = panel.vertices.row(e.start).transpose(),
                        p1 = panel.vertices.row(e.end).transpose();
  switch (e.kind) {
    case CurveKind::straight:
      return (p1 - p0).norm();
    case CurveKind::quadratic:
    case CurveKind::cubic:
      return bezier_table(p0, e, p1).back();
    case CurveKind::arc: {
      if ((p1 - p0).norm() == 0.0) return 0.0;
      const ArcGeometry g = arc_geometry(p0, p1, e);
      return g.radius * std::abs(g.sweep);
    }
  }
  return 0.0;
}

Eigen::MatrixX2d sample_edge(const Panel& panel, int edge, int n) {
  assert(n >= 1);
  const Edge& e = panel.edges[edge];
  const Eigen::Vector2d p0 = panel.vertices.row(e.start).transpose(),
                        p1 = panel.vertices.row(e.end).transpose();
  Eigen::MatrixX2d out(n + 1, 2);
  if (e.kind == CurveKind::quadratic || e.kind == CurveKind::cubic) {
    const std::vector<double> table = bezier_table(p0, e, p1);
    for (int i = 0; i <= n; ++i) {
      const double u = i == 0   ? 0.0
                       : i == n ? 1.0
                                : bezier_parameter(p0, e, p1, table, table.back() * i / n);
      out.row(i) = bezier_point(p0, e, p1, u).transpose();
    }
  } else {
    // Straight edges and arcs: the parameter is proportional to arc length.
    for (int i = 0; i <= n; ++i) out.row(i) = edge_point(panel, edge, double(i) / n).transpose();
  }
  out.row(0) = p0.transpose();
  out.row(n) = p1.transpose();
  return out;
}

Eigen::MatrixX2d sample_outline(const Panel& panel, double step, Eigen::VectorXi* edge_of_point) {
  std::vector<Eigen::Vector2d> points;
  std::vector<int> owner;
  for (int k = 0; k < int(panel.edges.size()); ++k) {
    const int n = std::max(1, int(std::ceil(edge_length(panel, k) / step)));
    const Eigen::MatrixX2d s = sample_edge(panel, k, n);
    for (int i = 0; i < n; ++i) {  // the end is the next edge's start
      points.push_back(s.row(i).transpose());
      owner.push_back(k);
    }
  }
  Eigen::MatrixX2d out(points.size(), 2);
  for (std::size_t i = 0; i < points.size(); ++i) out.row(i) = points[i].transpose();
  if (edge_of_point) *edge_of_point = Eigen::Map<Eigen::VectorXi>(owner.data(), owner.size());
  return out;
}

double polygon_area(const Eigen::MatrixX2d& polygon) {
  double twice = 0.0;
  const Eigen::Index n = polygon.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = (i + 1) % n;
    twice += polygon(i, 0) * polygon(j, 1) - polygon(j, 0) * polygon(i, 1);
  }
  return 0.5 * twice;
}

}  // namespace dresskit::pattern
