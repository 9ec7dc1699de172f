#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/isosurface.h"
#include "dresskit/mesh/topology.h"
#include "dresskit/testing/expect.h"
#include "mesh_fixtures.h"

using namespace dresskit;
using namespace dresskit::mesh;

namespace {
// The cube as a triangle soup: every triangle has its own three vertices.
TriangleMesh cube_soup() {
  const TriangleMesh c = fixtures::cube(1.0);
  TriangleMesh s;
  s.V.resize(36, 3);
  s.F.resize(12, 3);
  for (int f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k) {
      s.V.row(3 * f + k) = c.V.row(c.F(f, k));
      s.F(f, k) = 3 * f + k;
    }
  return s;
}

void expect_clean_closed_cube(const TriangleMesh& m) {
  const TopologyReport t = analyse_topology(m);
  EXPECT_EQ(t.num_vertices, 8);
  EXPECT_EQ(t.num_faces, 12);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.outward);
  EXPECT_NEAR(t.signed_volume, 1.0, 1e-12);
}
}  // namespace

TEST(Cleanup, CleanMeshIsUntouchedAndKeepsItsQuads) {
  TriangleMesh cube = fixtures::cube(1.0);
  cube.labels = Eigen::VectorXi::LinSpaced(8, 0, 7);
  const CleanupResult r = cleanup_mesh(cube);
  EXPECT_TRUE(r.changes().empty());
  expect_clean_closed_cube(r.mesh);
  EXPECT_EQ(r.mesh.quads.rows(), 6);
  // Every vertex knows where it came from, and its label came with it.
  for (int i = 0; i < 8; ++i) {
    const int s = r.mesh.source_vertex(i);
    ASSERT_GE(s, 0);
    EXPECT_EQ(r.mesh.V.row(i), cube.V.row(s));
    EXPECT_EQ(r.mesh.labels(i), s);
  }
}

TEST(Cleanup, MergesDuplicateVertices) {
  const CleanupResult r = cleanup_mesh(cube_soup());
  EXPECT_EQ(r.duplicate_vertices_merged, 28);
  expect_clean_closed_cube(r.mesh);
}

TEST(Cleanup, RemovesRepeatedIndexZeroAreaAndDuplicateFaces) {
  TriangleMesh g = fixtures::grid(3, 3, 1.0);
  TriangleMesh m = g;
  m.F.conservativeResize(g.F.rows() + 3, 3);
  m.F.row(g.F.rows()) << 0, 0, 5;      // repeated index
  m.F.row(g.F.rows() + 1) = g.F.row(0);                        // a duplicate face
  m.F.row(g.F.rows() + 2) << g.F(0, 1), g.F(0, 0), g.F(0, 2);  // the same face reversed
  const CleanupResult r = cleanup_mesh(m);
  EXPECT_EQ(r.degenerate_faces_removed, 1);
  EXPECT_EQ(r.duplicate_faces_removed, 2);
  EXPECT_EQ(r.mesh.num_faces(), g.num_faces());
  EXPECT_TRUE(analyse_topology(r.mesh).manifold);

  // A zero-area sliver between collinear vertices on the border of a strip.
  TriangleMesh s;
  s.V.resize(5, 3);
  s.V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 1, 0, 1, -1, 0;
  s.F.resize(3, 3);
  s.F << 0, 1, 3, 1, 2, 3, 0, 2, 1;  // the last one has zero area
  const CleanupResult z = cleanup_mesh(s);
  EXPECT_GE(z.degenerate_faces_removed, 1);
  EXPECT_EQ(analyse_topology(z.mesh).num_degenerate_faces, 0);
}

TEST(Cleanup, RemovesIsolatedVertices) {
  TriangleMesh m = fixtures::cube(1.0);
  m.V.conservativeResize(10, 3);
  m.V.row(8) << 5, 5, 5;
  m.V.row(9) << 6, 6, 6;
  const CleanupResult r = cleanup_mesh(m);
  EXPECT_EQ(r.isolated_vertices_removed, 2);
  expect_clean_closed_cube(r.mesh);
}

TEST(Cleanup, FixesAFlippedFaceAndAnInsideOutMesh) {
  TriangleMesh m = fixtures::cube(1.0);
  std::swap(m.F(5, 1), m.F(5, 2));
  CleanupResult r = cleanup_mesh(m);
  EXPECT_EQ(r.faces_reoriented, 1);
  expect_clean_closed_cube(r.mesh);

  TriangleMesh inside_out = fixtures::cube(1.0);
  inside_out.F.col(1).swap(inside_out.F.col(2));
  inside_out.quads.resize(0, 4);
  r = cleanup_mesh(inside_out);
  EXPECT_EQ(r.faces_reoriented, 12);
  expect_clean_closed_cube(r.mesh);
}

TEST(Cleanup, SplitsANonManifoldVertex) {
  const CleanupResult r = cleanup_mesh(fixtures::bowtie_tetrahedra());
  EXPECT_EQ(r.non_manifold_vertices_split, 1);
  const TopologyReport t = analyse_topology(r.mesh);
  test::expect_closed_outward(t, 2);
  EXPECT_EQ(t.num_vertices, 8);
  // Both copies of the split vertex come from input vertex 0.
  EXPECT_EQ((r.mesh.source_vertex.array() == 0).count(), 2);
}

TEST(Cleanup, StitchesCoincidentBorders) {
  // Two halves of a cube whose seam vertices are distinct but coincide: merging makes one cube.
  TriangleMesh m = fixtures::cube(1.0);
  m.V.conservativeResize(12, 3);
  for (int i = 0; i < 4; ++i) m.V.row(8 + i) = m.V.row(i);  // copies of the z = -0.5 face's corners
  for (int f = 0; f < 2; ++f)
    for (int k = 0; k < 3; ++k) m.F(f, k) += 8;  // the bottom face uses the copies
  m.quads.resize(0, 4);
  const CleanupResult r = cleanup_mesh(m);
  expect_clean_closed_cube(r.mesh);
}

TEST(Cleanup, FillsASmallHoleOnlyWhenAsked) {
  TriangleMesh m = fixtures::cube(1.0);
  TriangleMesh open = m;
  open.F = m.F.bottomRows(10);  // remove one side (two triangles): a 4-edge hole
  open.quads.resize(0, 4);
  CleanupResult r = cleanup_mesh(open);
  EXPECT_EQ(r.holes_filled, 0);
  EXPECT_EQ(analyse_topology(r.mesh).num_boundary_loops, 1);

  CleanupOptions options;
  options.fill_holes = true;
  r = cleanup_mesh(open, options);
  EXPECT_EQ(r.holes_filled, 1);
  EXPECT_GE(r.hole_faces_added, 2);
  const TopologyReport t = analyse_topology(r.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.outward);
  EXPECT_NEAR(t.signed_volume, 1.0, 1e-9);  // the planar hole is filled in its plane

  options.max_hole_edges = 3;  // too small for this hole
  r = cleanup_mesh(open, options);
  EXPECT_EQ(r.holes_filled, 0);
}

TEST(Cleanup, KeepsTheLargestComponent) {
  TriangleMesh a = fixtures::cube(1.0), b = fixtures::tetrahedron();
  TriangleMesh m;
  m.V.resize(12, 3);
  m.V << a.V, (b.V.array() + 3.0).matrix();
  m.F.resize(16, 3);
  m.F << a.F, (b.F.array() + 8).matrix();
  CleanupOptions options;
  options.keep_largest_component = true;
  const CleanupResult r = cleanup_mesh(m, options);
  EXPECT_EQ(r.components_removed, 1);
  expect_clean_closed_cube(r.mesh);
}

TEST(Cleanup, RemeshesASphereToTheTargetEdgeLength) {
  const ScalarField sphere = [](const Eigen::MatrixX3d& p, Eigen::VectorXd& v) {
    v = p.rowwise().norm().array() - 1.0;
  };
  const TriangleMesh raw = marching_tetrahedra(sphere, Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1.2), Eigen::Vector3d::Constant(1.2)), 0.08);
  CleanupOptions options;
  options.remesh_edge_length = 0.15;
  const CleanupResult r = cleanup_mesh(raw, options);
  EXPECT_TRUE(r.remeshed);
  const TopologyReport t = analyse_topology(r.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.outward);
  EXPECT_EQ(t.euler_characteristic, 2);
  double total = 0.0;
  int edges = 0;
  for (int f = 0; f < r.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k, ++edges)
      total += (r.mesh.V.row(r.mesh.F(f, k)) - r.mesh.V.row(r.mesh.F(f, (k + 1) % 3))).norm();
  EXPECT_NEAR(total / edges, 0.15, 0.15 * 0.2);
  EXPECT_NEAR(t.signed_volume, 4.0 / 3.0 * M_PI, 0.05 * 4.0 / 3.0 * M_PI);
  // Vertices that remeshing created have no source vertex.
  EXPECT_GT((r.mesh.source_vertex.array() < 0).count(), 0);
}

// A remeshing length that is not a number, or negative, is refused, not passed to CGAL.
TEST(Cleanup, RefusesAnImpossibleRemeshingLength) {
  for (double edge : {std::nan(""), -0.01, std::numeric_limits<double>::infinity()}) {
    CleanupOptions o;
    o.remesh_edge_length = edge;
    EXPECT_THROW(cleanup_mesh(fixtures::cube(1.0), o), InputError) << edge;
  }
  // A length whose triangles would fill the memory: the unit cube's 6 m² at 0.5 mm is 55 million.
  CleanupOptions o;
  o.remesh_edge_length = 0.0005;
  try {
    cleanup_mesh(fixtures::cube(1.0), o);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("would make about 55425626 triangles"), std::string::npos) << e.what();
  }
  o.remesh_edge_length = 0.0017;  // 4.8 million: allowed (not run here: the check comes first)
  EXPECT_LT(6.0 / (std::sqrt(3.0) / 4.0 * 0.0017 * 0.0017), kMaxRemeshTriangles);
}

// The outline of an open surface is not a hole: a single triangle and a flat panel stay open when
// holes are filled (closed onto themselves they were two sheets back to back, and remeshing that
// crashed), and remesh as open surfaces of the same area.
TEST(Cleanup, LeavesTheBorderOfAnOpenSurfaceOpen) {
  TriangleMesh triangle;
  triangle.V = (Eigen::MatrixX3d(3, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0).finished();
  triangle.F = (Eigen::MatrixX3i(1, 3) << 0, 1, 2).finished();
  TriangleMesh panel = fixtures::cube(1.0);
  panel.F = panel.F.topRows(2).eval();  // one side of the cube: a square of two triangles
  panel.quads.resize(0, 4);
  for (const TriangleMesh& m : {triangle, panel}) {
    CleanupOptions o;
    o.fill_holes = true;
    o.remesh_edge_length = 0.05;
    const CleanupResult r = cleanup_mesh(m, o);
    EXPECT_EQ(r.holes_filled, 0);
    EXPECT_EQ(r.borders_left_open, 1);
    const TopologyReport t = analyse_topology(r.mesh);
    EXPECT_EQ(t.num_boundary_loops, 1);
    EXPECT_NEAR(t.area, m.num_faces() == 1 ? 0.5 : 1.0, 1e-9);
  }
}

// A repair keeps each surviving face's corner texture coordinates (a UV seam between the two
// triangles) and its group; the degenerate face it removes takes its own with it.
TEST(Cleanup, FacesKeepTheirCornerTextureCoordinatesAndGroups) {
  TriangleMesh m = fixtures::grid(1, 1, 1.0);  // faces (0, 1, 3) and (0, 3, 2)
  m.F.conservativeResize(3, 3);
  m.F.row(2) << 1, 1, 2;  // degenerate
  m.TC.resize(7, 2);
  m.TC << 0, 0, 1, 0, 1, 1, 2, 0, 3, 1, 2, 1, 9, 9;
  m.FTC.resize(3, 3);
  m.FTC << 0, 1, 2, 3, 4, 5, 6, 6, 6;
  m.face_groups = Eigen::Vector3i(0, 1, 1);
  m.group_names = {"front", "back"};
  const CleanupResult r = cleanup_mesh(m);
  EXPECT_EQ(r.degenerate_faces_removed, 1);
  ASSERT_EQ(r.mesh.num_faces(), 2);
  ASSERT_EQ(r.mesh.FTC.rows(), 2);
  ASSERT_EQ(r.mesh.face_groups.size(), 2);
  EXPECT_EQ(r.mesh.group_names, m.group_names);
  // Each output face is one of the input's: same corners at the same places, same coordinates.
  for (int f = 0; f < 2; ++f) {
    const Eigen::RowVector3d centre = (r.mesh.V.row(r.mesh.F(f, 0)) + r.mesh.V.row(r.mesh.F(f, 1)) +
                                       r.mesh.V.row(r.mesh.F(f, 2))) / 3.0;
    const int g = centre.x() > centre.y() ? 0 : 1;  // (0, 1, 3) lies below the diagonal
    EXPECT_EQ(r.mesh.face_groups(f), g);
    for (int k = 0; k < 3; ++k) {
      const int v = r.mesh.F(f, k);
      int m_corner = -1;
      for (int c = 0; c < 3; ++c)
        if (m.V.row(m.F(g, c)) == r.mesh.V.row(v)) m_corner = c;
      ASSERT_GE(m_corner, 0);
      EXPECT_EQ(r.mesh.TC.row(r.mesh.FTC(f, k)), m.TC.row(m.FTC(g, m_corner))) << f << " " << k;
    }
  }
}
