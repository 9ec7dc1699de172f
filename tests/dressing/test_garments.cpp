// A garment's rest shape loosened where the body it is placed on is larger than its wearer
// (dressing/src/garments.h, loosened_rest): checked on an open tube whose placed rings are wider
// than its rest rings over its lower half, against the radii the length limit gives in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "garments.h"

using namespace dresskit::dressing::detail;

namespace {

constexpr int kAround = 48, kRows = 13;
constexpr double kHeight = 0.36;

/// An open tube of kRows rings of kAround vertices, ring r at height r × kHeight / (kRows − 1),
/// its radius radius(r); faces: each quad between rings split in two.
template <class Radius>
Eigen::MatrixX3d tube(Radius radius) {
  Eigen::MatrixX3d V(kAround * kRows, 3);
  for (int r = 0; r < kRows; ++r)
    for (int a = 0; a < kAround; ++a) {
      const double t = 2.0 * M_PI * a / kAround;
      V.row(r * kAround + a) << radius(r) * std::cos(t), r * kHeight / (kRows - 1), radius(r) * std::sin(t);
    }
  return V;
}

Eigen::MatrixX3i tube_faces() {
  Eigen::MatrixX3i F(2 * kAround * (kRows - 1), 3);
  int f = 0;
  for (int r = 0; r + 1 < kRows; ++r)
    for (int a = 0; a < kAround; ++a) {
      const int p = r * kAround + a, q = r * kAround + (a + 1) % kAround;
      F.row(f++) << p, q, q + kAround;
      F.row(f++) << p, q + kAround, p + kAround;
    }
  return F;
}

/// The mean distance of ring r's vertices from the tube's axis, and its mean height.
std::pair<double, double> ring(const Eigen::MatrixX3d& V, int r) {
  double radius = 0.0, height = 0.0;
  const Eigen::RowVector3d centre = V.middleRows(r * kAround, kAround).colwise().mean();
  for (int a = 0; a < kAround; ++a) {
    const Eigen::RowVector3d d = V.row(r * kAround + a) - centre;
    radius += std::hypot(d(0), d(2)) / kAround;
    height += V(r * kAround + a, 1) / kAround;
  }
  return {radius, height};
}

}  // namespace

TEST(LoosenedRest, GrowsWhereThePlacementStretchesBeyondTheLimit) {
  const Eigen::MatrixX3d rest = tube([](int) { return 0.10; });
  const Eigen::MatrixX3i F = tube_faces();
  // Placed over a body 30 % wider below the middle ring: the lower rings must grow to
  // 0.13 / 1.1 so that the placement stretches them by no more than the 10 % limit.
  const Eigen::MatrixX3d placed = tube([](int r) { return r <= kRows / 2 ? 0.13 : 0.10; });
  int grown = 0;
  const Eigen::MatrixX3d loose = loosened_rest(rest, F, placed, 0.1, 1.3, &grown);
  EXPECT_GT(grown, 0);
  EXPECT_NEAR(ring(loose, 0).first, 0.13 / 1.1, 0.002);
  EXPECT_NEAR(ring(loose, 3).first, 0.13 / 1.1, 0.002);
  // The upper rings, which the placement does not stretch, grow only where the shape must join the
  // lower ones, less and less away from them: the top ring by less than a third of the lower rings'
  // growth (a uniform growth would give them all of it).
  const double lower_growth = 0.13 / 1.1 - 0.10;
  EXPECT_GT(ring(loose, kRows / 2 + 1).first, ring(loose, kRows - 3).first);
  EXPECT_GT(ring(loose, kRows - 3).first, ring(loose, kRows - 1).first);
  EXPECT_LT(ring(loose, kRows - 1).first - 0.10, lower_growth / 3.0);
  // Rows keep their spacing: the growth is around the tube, not along it.
  EXPECT_NEAR(ring(loose, kRows - 1).second - ring(loose, 0).second, kHeight, 0.01);
}

TEST(LoosenedRest, NoGrowthWithinTheLimitAndNoMoreThanTheLargest) {
  const Eigen::MatrixX3d rest = tube([](int) { return 0.10; });
  const Eigen::MatrixX3i F = tube_faces();
  int grown = -1;
  const Eigen::MatrixX3d within = loosened_rest(rest, F, tube([](int) { return 0.109; }), 0.1, 1.3, &grown);
  EXPECT_EQ(grown, 0);
  EXPECT_EQ(within, rest);
  // Twice as wide all along: the growth stops at 1.3 times.
  const Eigen::MatrixX3d capped = loosened_rest(rest, F, tube([](int) { return 0.20; }), 0.1, 1.3, &grown);
  EXPECT_EQ(grown, kAround * kRows + kAround * (kRows - 1));  // the rings' edges and the diagonals
  EXPECT_NEAR(ring(capped, kRows / 2).first, 0.13, 0.004);
}
