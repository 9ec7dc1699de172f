// The body collider's pieces against brute force and independent references: closest points on
// triangles, the segment–triangle crossing test, the BVH's closest point, and the signed distance grid
// (values against exact distances, signs against a winding number) on a sphere and the gc_mean_all body.
#include <gtest/gtest.h>

#include <random>

#include "cloth/collision_helpers.h"
#include "dresskit/cloth/geometry.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "test_data.h"

using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace dresskit {
namespace {

TEST(Geometry, ClosestPointOnTriangleIsNoFartherThanAnySampledPoint) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Eigen::Vector3d p(2 * u(rng), 2 * u(rng), 2 * u(rng));
    Eigen::Vector3d bary;
    const Eigen::Vector3d q = closest_point_on_triangle(p, a, b, c, &bary);
    EXPECT_NEAR((bary[0] * a + bary[1] * b + bary[2] * c - q).norm(), 0.0, 1e-12);
    EXPECT_GE(bary.minCoeff(), -1e-12);
    const double d = (q - p).norm();
    for (int s = 0; s < 300; ++s) {
      double r1 = w(rng), r2 = w(rng);
      if (r1 + r2 > 1.0) r1 = 1.0 - r1, r2 = 1.0 - r2;
      EXPECT_LE(d, (a + r1 * (b - a) + r2 * (c - a) - p).norm() + 1e-12);
    }
  }
}

TEST(Geometry, SegmentCrossesTriangleOnlyThroughItsInterior) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(segment_crosses_triangle({0.2, 0.2, -1}, {0.2, 0.2, 1}, a, b, c));
  EXPECT_TRUE(segment_crosses_triangle({0.2, 0.2, 1}, {0.3, 0.1, -0.5}, a, b, c));
  EXPECT_FALSE(segment_crosses_triangle({0.6, 0.6, -1}, {0.6, 0.6, 1}, a, b, c));  // beyond the hypotenuse
  EXPECT_FALSE(segment_crosses_triangle({0.2, 0.2, 0.1}, {0.2, 0.2, 1}, a, b, c));  // one side only
  EXPECT_FALSE(segment_crosses_triangle({0.2, 0.2, 0.0}, {0.2, 0.2, 1}, a, b, c));  // touches: no crossing
}

TEST(Geometry, SegmentsClosestPointsMatchSampling) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector3d p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng));
    const Eigen::Vector3d q0(u(rng), u(rng), u(rng)), q1(u(rng), u(rng), u(rng));
    double s = 0, t = 0;
    const double d2 = closest_points_of_segments(p0, p1, q0, q1, &s, &t);
    double best = 1e9;
    for (int i = 0; i <= 200; ++i)
      for (int j = 0; j <= 200; ++j)
        best = std::min(best, (p0 + i / 200.0 * (p1 - p0) - q0 - j / 200.0 * (q1 - q0)).squaredNorm());
    EXPECT_LE(d2, best + 1e-12);
    EXPECT_NEAR(std::sqrt(d2), std::sqrt(best), 0.02);
  }
}

TEST(TriangleBvh, ClosestPointEqualsBruteForce) {
  const TriangleMesh sphere = test::sphere_mesh(Eigen::Vector3d(0.1, 0.2, -0.1), 0.3, 0.03);
  const TriangleBvh bvh(sphere.V, sphere.F);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    double brute = 1e9;
    for (int t = 0; t < sphere.num_faces(); ++t) {
      brute = std::min(brute, (closest_point_on_triangle(p, sphere.V.row(sphere.F(t, 0)).transpose(),
                                                         sphere.V.row(sphere.F(t, 1)).transpose(),
                                                         sphere.V.row(sphere.F(t, 2)).transpose()) - p).squaredNorm());
    }
    Eigen::Vector3d q;
    double d2 = -1;
    ASSERT_GE(bvh.closest(p, &q, &d2), 0);
    EXPECT_NEAR(d2, brute, 1e-14);
  }
}

TEST(TriangleBvh, SelfPairsAreExactlyTheOverlappingBoxes) {
  const TriangleMesh sphere = test::sphere_mesh(Eigen::Vector3d::Zero(), 0.3, 0.06);
  const TriangleBvh bvh(sphere.V, sphere.F, 0.01);
  long found = 0;
  bvh.self_pairs([&](int a, int b) {
    EXPECT_NE(a, b);
    ++found;
  });
  long brute = 0;
  for (int a = 0; a < sphere.num_faces(); ++a)
    for (int b = a + 1; b < sphere.num_faces(); ++b) brute += bvh.box(a).intersects(bvh.box(b));
  EXPECT_EQ(found, brute);
  EXPECT_GT(found, sphere.num_faces());
}

// Grid values against the exact (BVH) distance, and signs against the winding number.
// A sign may differ only where the point is nearer the surface than the value tolerance (the grid
// cannot resolve features thinner than a cell there); those are counted in close_wrong_signs.
void check_distance(const TriangleMesh& mesh, const MeshDistance& distance, const std::vector<Eigen::Vector3d>& points,
                    double value_tolerance, int* close_wrong_signs) {
  *close_wrong_signs = 0;
  for (const Eigen::Vector3d& p : points) {
    Eigen::Vector3d n, n_exact;
    const double d = distance.distance(p, &n);
    const double exact = distance.exact_distance(p, &n_exact);
    EXPECT_NEAR(std::abs(d), std::abs(exact), value_tolerance) << p.transpose();
    EXPECT_NEAR(n.norm(), 1.0, 1e-9);
    const bool inside = std::abs(test::winding_number(mesh, p)) > 0.5;
    if ((d < 0.0) == inside) continue;
    if (std::abs(exact) < value_tolerance) ++*close_wrong_signs;
    else ADD_FAILURE() << "sign at " << p.transpose() << ": grid " << d << ", exact " << exact;
  }
}

TEST(MeshDistance, SphereMatchesExactDistanceAndWindingNumber) {
  const TriangleMesh sphere = test::sphere_mesh(Eigen::Vector3d(0.0, 0.5, 0.0), 0.25, 0.02);
  MeshDistanceOptions o;
  o.cell = 0.005;
  const MeshDistance distance(sphere, o);
  EXPECT_TRUE(distance.report().closed);
  EXPECT_EQ(distance.report().sign_disagreements, 0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  std::vector<Eigen::Vector3d> near, far;
  while (near.size() < 400 || far.size() < 100) {
    const Eigen::Vector3d p = Eigen::Vector3d(0.0, 0.5, 0.0) + Eigen::Vector3d(u(rng), u(rng), u(rng));
    Eigen::Vector3d n;
    const double e = distance.exact_distance(p, &n);
    if (std::abs(e) < 0.5 * distance.report().band && near.size() < 400) near.push_back(p);
    else if (std::abs(e) >= distance.report().band && far.size() < 100) far.push_back(p);
  }
  int wrong = 0;
  // Trilinear interpolation of a distance to a curved surface: within a few per cent of a cell.
  check_distance(sphere, distance, near, 0.1 * o.cell, &wrong);
  EXPECT_EQ(wrong, 0);
  for (const Eigen::Vector3d& p : far) {
    Eigen::Vector3d n;
    const double d = distance.distance(p, &n), exact = distance.exact_distance(p, &n);
    if (exact < 0.0) {
      EXPECT_NEAR(d, exact, 1e-9);  // deep inside: the exact closest point
    } else {
      EXPECT_GE(d, 0.99 * distance.report().band);  // far outside: a lower bound beyond the band
      EXPECT_LE(d, exact + 1e-9);
    }
  }
  // The direction points out of the sphere.
  Eigen::Vector3d n;
  distance.distance(Eigen::Vector3d(0.24, 0.5, 0.0), &n);
  EXPECT_GT(n.x(), 0.99);
  distance.distance(Eigen::Vector3d(0.0, 0.5, -0.1), &n);  // deep: the exact closest point
  EXPECT_LT(n.z(), -0.99);
}

// A particle's cached cell gives the lookup without the cache to the bit: along random walks of
// steps much shorter than a cell (most lookups from the cache) and much longer (a new cell each
// time), near the surface, deep inside, across brick borders and beyond the grid.
TEST(MeshDistance, ACachedCellGivesTheSameValueToTheBit) {
  const TriangleMesh sphere = test::sphere_mesh(Eigen::Vector3d(0.0, 0.5, 0.0), 0.25, 0.02);
  const MeshDistance distance(sphere);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int cached = 0, lookups = 0;
  for (const double stride : {0.0004, 0.02}) {
    for (int walk = 0; walk < 40; ++walk) {
      MeshDistance::Cell cell;
      Eigen::Vector3d p = Eigen::Vector3d(0.0, 0.5, 0.0) + 0.35 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      for (int step = 0; step < 200; ++step, ++lookups) {
        p += stride * Eigen::Vector3d(u(rng), u(rng), u(rng));
        const int key = cell.key;
        Eigen::Vector3d n_plain, n_cached;
        const double plain = distance.distance(p, &n_plain), with_cell = distance.distance(p, &n_cached, &cell);
        cached += cell.key == key;
        ASSERT_EQ(plain, with_cell) << "at (" << p.transpose() << ")";
        ASSERT_EQ(n_plain, n_cached);
      }
    }
  }
  EXPECT_GT(cached, lookups / 4);  // the short walks mostly stay in their cells
}

TEST(MeshDistance, BadOptionsAreRejected) {
  const TriangleMesh sphere = test::sphere_mesh(Eigen::Vector3d::Zero(), 0.25, 0.05);
  MeshDistanceOptions o;
  o.cell = 0.0;
  EXPECT_THROW((MeshDistance{sphere, o}), InputError);
  o.cell = 1e-5;  // far too many points
  EXPECT_THROW((MeshDistance{sphere, o}), InputError);
  EXPECT_THROW(MeshDistance{TriangleMesh{}}, InputError);
}

TEST(MeshDistance, GcMeanAllBodySignsAgreeWithTheWindingNumber) {
  DRESSKIT_REQUIRE_DATA();
  const TriangleMesh body = load_mesh(test::data_dir() + "/bodies/gc_mean_all.obj");
  const MeshDistance distance(body);
  // Points along the vertex normals, 1 to 8 mm either side of the surface.
  const Eigen::MatrixX3d N = vertex_normals(body.V, body.F);
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> pick(0, body.num_vertices() - 1);
  std::uniform_real_distribution<double> offset(0.001, 0.008);
  std::vector<Eigen::Vector3d> points;
  while (points.size() < 300) {
    const int v = pick(rng);
    if (N.row(v).norm() < 0.5) continue;  // the isolated vertex
    const double sign = points.size() % 2 ? 1.0 : -1.0;
    points.push_back(body.V.row(v).transpose() + sign * offset(rng) * N.row(v).transpose());
  }
  int wrong = 0;
  check_distance(body, distance, points, 0.5 * distance.report().cell, &wrong);
  // Thin places (ears, fingers) are finer than the 5 mm grid: 1 of these 300 points 1.3 mm inside an
  // ear reads 0.5 mm outside. At most 1 % such, and none farther from the surface than half a cell.
  EXPECT_LE(wrong, 3);
}

}  // namespace
}  // namespace dresskit
