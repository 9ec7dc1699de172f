#include <gtest/gtest.h>

#include <tuple>

#include "dresskit/mesh/topology.h"
#include "dresskit/testing/expect.h"
#include "mesh_fixtures.h"

using namespace dresskit;
using namespace dresskit::mesh;

TEST(Topology, TetrahedronIsClosedOutwardWithKnownVolume) {
  const TriangleMesh m = fixtures::tetrahedron();
  const TopologyReport t = analyse_topology(m);
  // Vertices, edges, borders and the Euler characteristic of a sphere.
  EXPECT_EQ(std::make_tuple(t.num_vertices, t.num_edges, t.num_boundary_loops, t.euler_characteristic),
            std::make_tuple(4, 6, 0, 2));
  test::expect_closed_outward(t);
  EXPECT_NEAR(t.signed_volume, 1.0 / 6.0, 1e-15);  // unit right tetrahedron
  EXPECT_NEAR(t.area, 1.5 + std::sqrt(3.0) / 2.0, 1e-12);
}

TEST(Topology, CubeVolumeAndFlippedFaceIsInconsistent) {
  TriangleMesh m = fixtures::cube(2.0);
  TopologyReport t = analyse_topology(m);
  EXPECT_NEAR(t.signed_volume, 8.0, 1e-12);
  EXPECT_NEAR(t.area, 24.0, 1e-12);
  EXPECT_TRUE(t.outward);
  std::swap(m.F(3, 1), m.F(3, 2));
  t = analyse_topology(m);
  EXPECT_EQ(t.num_inconsistent_edges, 3);
  EXPECT_FALSE(t.consistently_oriented);
  EXPECT_FALSE(t.outward);
}

TEST(Topology, OpenGridHasOneBoundaryLoop) {
  const TriangleMesh m = fixtures::grid(4, 3, 1.0);
  const TopologyReport t = analyse_topology(m);
  EXPECT_EQ(t.num_boundary_loops, 1);
  EXPECT_EQ(t.num_boundary_edges, 2 * (4 + 3));
  EXPECT_TRUE(t.manifold);
  EXPECT_FALSE(t.closed);
  EXPECT_EQ(t.euler_characteristic, 1);  // a disc
}

TEST(Topology, TwoTetrahedraSharingAVertexIsNonManifold) {
  const TriangleMesh m = fixtures::bowtie_tetrahedra();
  const TopologyReport t = analyse_topology(m);
  // One piece, one non-manifold vertex, every edge manifold.
  EXPECT_EQ(std::make_tuple(t.num_components, t.num_non_manifold_vertices, t.num_non_manifold_edges),
            std::make_tuple(1, 1, 0));
  EXPECT_FALSE(t.manifold);
  EXPECT_FALSE(t.closed);
}

TEST(Topology, EdgeWithThreeFacesIsNonManifold) {
  TriangleMesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  m.F.resize(3, 3);
  m.F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const TopologyReport t = analyse_topology(m);
  EXPECT_EQ(t.num_non_manifold_edges, 1);
  EXPECT_FALSE(t.manifold);
}

TEST(Topology, SplitComponentsLargestFirstAndOrientOutward) {
  TriangleMesh a = fixtures::cube(1.0), b = fixtures::tetrahedron();
  TriangleMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, (b.V.array() + 5.0).matrix();
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + int(a.V.rows())).matrix();
  // Turn the tetrahedron inside out.
  for (int f = int(a.F.rows()); f < m.num_faces(); ++f) std::swap(m.F(f, 1), m.F(f, 2));
  EXPECT_EQ(analyse_topology(m).num_components, 2);
  EXPECT_EQ(orient_closed_components_outward(m), 4);
  const auto parts = split_components(m);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].num_faces(), 12);
  EXPECT_EQ(parts[1].num_faces(), 4);
  EXPECT_TRUE(analyse_topology(parts[1]).outward);
  EXPECT_NEAR(analyse_topology(parts[1]).signed_volume, 1.0 / 6.0, 1e-12);
}

namespace {
// Summed signed area (along +z) of triangles over planar corners, and whether any is flat or reversed.
double triangulated_area(const std::vector<Eigen::Vector3d>& c, const std::vector<std::array<int, 3>>& t,
                         bool* all_positive) {
  double area = 0.0;
  *all_positive = true;
  for (const auto& f : t) {
    const double a = 0.5 * (c[f[1]] - c[f[0]]).cross(c[f[2]] - c[f[0]]).z();
    *all_positive = *all_positive && a > 1e-9;
    area += a;
  }
  return area;
}
bool has_edge(const std::vector<std::array<int, 3>>& t, int a, int b) {
  for (const auto& f : t)
    for (int k = 0; k < 3; ++k)
      if ((f[k] == a && f[(k + 1) % 3] == b) || (f[k] == b && f[(k + 1) % 3] == a)) return true;
  return false;
}
}  // namespace

TEST(Topology, TriangulatePolygonKeepsConvexFansAndClipsTheRest) {
  bool positive = false;
  // A convex quad: the file's fan from its first corner.
  const std::vector<Eigen::Vector3d> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto fan = triangulate_polygon(square);
  ASSERT_EQ(fan.size(), 2u);
  EXPECT_EQ(fan[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(fan[1], (std::array<int, 3>{0, 2, 3}));
  // A square with a corner halfway along its first side (a T-junction): the fan would hold the flat
  // triangle (0, 1, 2) and the diagonal 0–2 along that side.
  const std::vector<Eigen::Vector3d> t_junction = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto clipped = triangulate_polygon(t_junction);
  ASSERT_EQ(clipped.size(), 3u);
  EXPECT_NEAR(triangulated_area(t_junction, clipped, &positive), 1.0, 1e-12);
  EXPECT_TRUE(positive);
  EXPECT_FALSE(has_edge(clipped, 0, 2));
  // A dart (reflex corner 1): the fan's diagonal 0–2 runs outside; the other diagonal is taken.
  const std::vector<Eigen::Vector3d> dart = {{0, 0, 0}, {1, 0.3, 0}, {2, 0, 0}, {1, 2, 0}};
  const auto dart_triangles = triangulate_polygon(dart);
  ASSERT_EQ(dart_triangles.size(), 2u);
  EXPECT_NEAR(triangulated_area(dart, dart_triangles, &positive), 1.7, 1e-12);
  EXPECT_TRUE(positive);
  EXPECT_TRUE(has_edge(dart_triangles, 1, 3));
  // An L of six corners, the fan's corner at its reflex side, turned in space: area 3, none reversed.
  std::vector<Eigen::Vector3d> ell = {{1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}};
  const auto ell_triangles = triangulate_polygon(ell);
  ASSERT_EQ(ell_triangles.size(), 4u);
  EXPECT_NEAR(triangulated_area(ell, ell_triangles, &positive), 3.0, 1e-12);
  EXPECT_TRUE(positive);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Eigen::Vector3d> turned;
  for (const auto& c : ell) turned.push_back(turn * c + Eigen::Vector3d(5, -2, 9));
  EXPECT_EQ(triangulate_polygon(turned), ell_triangles);
}
