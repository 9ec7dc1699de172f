// Edge curves against closed forms and fine sampling.
#include <gtest/gtest.h>

#include <cmath>

#include "dresskit/pattern/curves.h"

using namespace dresskit::pattern;

namespace dresskit::pattern {
namespace {

constexpr double kPi = 3.14159265358979323846;

Panel one_edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Edge& shape) {
  Panel p;
  p.name = "test";
  p.vertices.resize(2, 2);
  p.vertices << a.x(), a.y(), b.x(), b.y();
  Edge e = shape;
  e.start = 0;
  e.end = 1;
  p.edges = {e};
  return p;
}

/// ∫₀¹ √(A t² + B t + C) dt in closed form (A > 0).
double sqrt_quadratic_integral(double A, double B, double C) {
  auto F = [&](double t) {
    const double q = std::sqrt(A * t * t + B * t + C);
    return (2.0 * A * t + B) * q / (4.0 * A) +
           (4.0 * A * C - B * B) / (8.0 * std::pow(A, 1.5)) *
               std::log(std::abs(2.0 * std::sqrt(A) * q + 2.0 * A * t + B));
  };
  return F(1.0) - F(0.0);
}

double polyline_length(const Panel& p, int samples) {
  double sum = 0.0;
  Eigen::Vector2d prev = edge_point(p, 0, 0.0);
  for (int i = 1; i <= samples; ++i) {
    const Eigen::Vector2d q = edge_point(p, 0, double(i) / samples);
    sum += (q - prev).norm();
    prev = q;
  }
  return sum;
}

TEST(PatternCurves, QuadraticBezierLengthMatchesClosedForm) {
  const Eigen::Vector2d p0(0.0, 0.0), c(0.13, 0.31), p1(0.4, -0.05);
  Edge e;
  e.kind = CurveKind::quadratic;
  e.controls = {c};
  const Panel p = one_edge(p0, p1, e);
  // B'(t) = 2 (a t + b), a = p0 − 2c + p1, b = c − p0: |B'|² = 4 a·a t² + 8 a·b t + 4 b·b.
  const Eigen::Vector2d a = p0 - 2.0 * c + p1, b = c - p0;
  const double exact = sqrt_quadratic_integral(4.0 * a.dot(a), 8.0 * a.dot(b), 4.0 * b.dot(b));
  EXPECT_NEAR(edge_length(p, 0), exact, 1e-12 * exact);
  EXPECT_GT(exact, (p1 - p0).norm() * 1.1);  // really curved
}

TEST(PatternCurves, CubicBezierLengthMatchesFineSampling) {
  Edge e;
  e.kind = CurveKind::cubic;
  e.controls = {Eigen::Vector2d(0.1, 0.25), Eigen::Vector2d(0.35, -0.2)};
  const Panel p = one_edge({0.0, 0.0}, {0.5, 0.05}, e);
  const double fine = polyline_length(p, 200000);
  EXPECT_NEAR(edge_length(p, 0), fine, 1e-8 * fine);
}

TEST(PatternCurves, ArcLengthsFromRadiusAndFlags) {
  const Eigen::Vector2d a(0.0, 0.0), b(0.2, 0.0);  // chord 0.2
  for (bool large : {false, true}) {
    for (bool ccw : {false, true}) {
      Edge e;
      e.kind = CurveKind::arc;
      e.radius = 0.2;
      e.large_arc = large;
      e.counter_clockwise = ccw;
      const Panel p = one_edge(a, b, e);
      const double small_angle = 2.0 * std::asin(0.1 / 0.2);  // π/3
      const double expected = 0.2 * (large ? 2.0 * kPi - small_angle : small_angle);
      EXPECT_NEAR(edge_length(p, 0), expected, 1e-12) << large << ccw;
      EXPECT_NEAR(polyline_length(p, 100000), expected, 1e-7);
      // The side of the bulge follows SVG's flags: going from a to b (+x), an arc that turns
      // counter-clockwise passes below the chord (small or large), a clockwise one above.
      const Eigen::Vector2d mid = edge_point(p, 0, 0.5);
      if (ccw)
        EXPECT_LT(mid.y(), 0.0);
      else
        EXPECT_GT(mid.y(), 0.0);
      EXPECT_NEAR(
          std::abs(mid.y()),
          large ? 0.2 + 0.2 * std::cos(small_angle / 2) : 0.2 - 0.2 * std::cos(small_angle / 2),
          1e-12);
    }
  }
}

TEST(PatternCurves, SemicircleFromTooSmallRadius) {
  Edge e;
  e.kind = CurveKind::arc;
  e.radius = 0.01;  // below half the chord: grows to it, as in SVG
  const Panel p = one_edge({0.0, 0.0}, {0.3, 0.0}, e);
  EXPECT_NEAR(edge_length(p, 0), kPi * 0.15, 1e-12);
}

TEST(PatternCurves, SamplesAreEquallySpacedInArcLength) {
  Edge e;
  e.kind = CurveKind::cubic;
  e.controls = {Eigen::Vector2d(0.02, 0.3),
                Eigen::Vector2d(0.4, 0.3)};  // speed varies a lot along u
  const Panel p = one_edge({0.0, 0.0}, {0.42, 0.0}, e);
  const int n = 40;
  const Eigen::MatrixX2d s = sample_edge(p, 0, n);
  ASSERT_EQ(s.rows(), n + 1);
  EXPECT_NEAR((s.row(0) - p.vertices.row(0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.row(n) - p.vertices.row(1)).norm(), 0.0, 1e-15);
  // Arc length from the start to each sample, by fine sampling of the curve.
  const int fine = 400000;
  double length = 0.0;
  Eigen::Vector2d prev = edge_point(p, 0, 0.0);
  int next = 1;
  const double total = edge_length(p, 0);
  for (int i = 1; i <= fine && next < n; ++i) {
    const Eigen::Vector2d q = edge_point(p, 0, double(i) / fine);
    length += (q - prev).norm();
    prev = q;
    if ((q - s.row(next).transpose()).norm() < 2e-6) {
      EXPECT_NEAR(length, total * next / n, 2e-5) << "sample " << next;
      ++next;
    }
  }
  EXPECT_EQ(next, n) << "every sample lies on the curve";
}

TEST(PatternCurves, PolygonAreaSign) {
  Eigen::MatrixX2d square(4, 2);
  square << 0, 0, 2, 0, 2, 1, 0, 1;
  EXPECT_DOUBLE_EQ(polygon_area(square), 2.0);
  EXPECT_DOUBLE_EQ(polygon_area(square.colwise().reverse()), -2.0);
}

}  // namespace
}  // namespace dresskit::pattern
