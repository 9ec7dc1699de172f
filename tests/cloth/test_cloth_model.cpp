#include <gtest/gtest.h>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace {
Fabric test_fabric() {
  Fabric f;
  f.name = "test";
  f.areal_density = 0.2;
  f.stretching.row(0) << 100.0, 10.0, 60.0, 5.0;  // C11, C12, C22, C33 at rest
  for (int i = 1; i < 6; ++i) f.stretching.row(i) << 300.0, 10.0, 200.0, 5.0;
  f.bending.setConstant(1e-5);
  return f;
}
}  // namespace

TEST(ClothModel, GridFacesItsNormalWithQuads) {
  const TriangleMesh g = make_grid({2.0, 1.0}, {5, 3}, {0, 1, 0}, {0, 1, 0});
  EXPECT_EQ(g.num_vertices(), 15);
  EXPECT_EQ(g.quads.rows(), 8);
  const TopologyReport t = analyse_topology(g);
  EXPECT_NEAR(t.area, 2.0, 1e-12);
  EXPECT_EQ(t.num_boundary_loops, 1);
  const Eigen::MatrixX3d N = vertex_normals(g.V, g.F);
  EXPECT_TRUE(N.row(7).isApprox(Eigen::RowVector3d(0, 1, 0)));
  EXPECT_NEAR(g.V.col(1).maxCoeff(), 1.0, 1e-12);
  EXPECT_THROW(make_grid({1, 1}, {1, 5}, {0, 0, 0}, {0, 1, 0}), InputError);
  EXPECT_THROW(make_grid({1, -1}, {5, 5}, {0, 0, 0}, {0, 1, 0}), InputError);
  EXPECT_THROW(make_grid({1, 1}, {5, 5}, {0, 0, 0}, {0, 0, 0}), InputError);
}

TEST(ClothModel, SpringCountsStiffnessAndMassOnAGrid) {
  const int n = 4;  // 4×4 vertices, 3×3 cells of h = 1/3
  const double h = 1.0 / 3;
  const TriangleMesh g = make_grid({1.0, 1.0}, {n, n}, {0, 0, 0}, {0, 1, 0});  // first axis +X
  const Fabric f = test_fabric();
  const ClothModel m = build_cloth(g, f);
  const SpringSet& s = m.springs;
  EXPECT_EQ(s.count(SpringType::structural), 2 * n * (n - 1));  // 24 grid lines
  EXPECT_EQ(s.count(SpringType::shear), 2 * (n - 1) * (n - 1));  // 2 per quad
  EXPECT_NEAR(m.mass.sum(), 0.2 * 1.0, 1e-12);
  // Corner vertex: one quad's share, i.e. two triangles' thirds.
  EXPECT_NEAR(m.mass(0), 0.2 * (h * h / 2) / 3 * (m.faces.col(0).cwiseEqual(0).count() + m.faces.col(1).cwiseEqual(0).count() + m.faces.col(2).cwiseEqual(0).count()), 1e-12);
  for (int k = 0; k < s.size(); ++k) {
    const int i = s.i[k], j = s.j[k];
    const Eigen::Vector3d d = m.rest_positions.row(j) - m.rest_positions.row(i);
    if (s.type[k] == SpringType::structural) {
      // Interior springs along warp (x) carry C11, across it C22; boundary springs half of that.
      const bool along_x = std::abs(d.x()) > 1e-9;
      const bool boundary = along_x ? std::abs(std::abs(m.rest_positions(i, 2)) - 0.5) < 1e-9
                                    : std::abs(std::abs(m.rest_positions(i, 0)) - 0.5) < 1e-9;
      const double expected = (along_x ? 100.0 : 60.0) * (boundary ? 0.5 : 1.0);
      EXPECT_NEAR(s.k_rest[k], expected, 1e-9) << k;
      EXPECT_NEAR(s.k_knee[k], (along_x ? 300.0 : 200.0) * (boundary ? 0.5 : 1.0), 1e-9) << k;
      EXPECT_NEAR(s.rest_length[k], h, 1e-12);
    } else if (s.type[k] == SpringType::shear) {
      EXPECT_NEAR(s.k_rest[k], 5.0, 1e-9);  // C33 for a square cell
      EXPECT_NEAR(s.rest_length[k], h * std::sqrt(2.0), 1e-12);
    }
  }
  ClothBuildOptions o;
  o.total_mass = 0.3;
  EXPECT_NEAR(build_cloth(g, f, o).mass.sum(), 0.3, 1e-12);
  o.bending_springs = false;
  EXPECT_EQ(build_cloth(g, f, o).springs.count(SpringType::bending), 0);
}

TEST(ClothModel, ZeroAreaFacesAndZeroLengthSpringsAreSkippedAndCounted) {
  TriangleMesh m;
  m.V.resize(6, 3);
  // Two triangles folded onto each other across edge 0–1 (their far corners 2 and 4 coincide, so
  // the bending spring between them has zero length), and a collinear triangle of zero area.
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 0, 1, 0, 3, 0, 0;
  m.F.resize(3, 3);
  m.F << 0, 1, 2, 1, 0, 4, 1, 3, 5;
  const ClothModel c = build_cloth(m, test_fabric());
  EXPECT_EQ(c.skipped_zero_area_faces, 1);
  EXPECT_EQ(c.skipped_zero_length_springs, 1);  // the bending spring 2–4
  for (double L : c.springs.rest_length) EXPECT_GT(L, 0.0);
  Fabric bad = test_fabric();
  bad.areal_density = 0.0;
  EXPECT_THROW(build_cloth(m, bad), InputError);
  ClothBuildOptions o;
  o.total_mass = -1.0;
  EXPECT_THROW(build_cloth(m, test_fabric(), o), InputError);
}
