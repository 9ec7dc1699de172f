#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/topology.h"
#include "mesh_fixtures.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::mesh;

namespace {
void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Same surface up to vertex order and single precision: counts, area, volume, bounding box.
void expect_same_surface(const TriangleMesh& a, const TriangleMesh& b, double tol) {
  const TopologyReport ta = analyse_topology(a), tb = analyse_topology(b);
  EXPECT_EQ(ta.num_faces, tb.num_faces);
  EXPECT_EQ(ta.num_components, tb.num_components);
  EXPECT_EQ(ta.closed, tb.closed);
  EXPECT_EQ(ta.outward, tb.outward);
  EXPECT_NEAR(ta.area, tb.area, tol * ta.area);
  EXPECT_NEAR(ta.signed_volume, tb.signed_volume, tol * std::abs(ta.signed_volume) + 1e-12);
  EXPECT_TRUE(bounding_box(a).min().isApprox(bounding_box(b).min(), tol));
  EXPECT_TRUE(bounding_box(a).max().isApprox(bounding_box(b).max(), tol));
}
}  // namespace

TEST(Units, ParseNamesAndScales) {
  EXPECT_DOUBLE_EQ(Units::parse("m").metres_per_unit, 1.0);
  EXPECT_DOUBLE_EQ(Units::parse("dm").metres_per_unit, 0.1);
  EXPECT_DOUBLE_EQ(Units::parse("cm").metres_per_unit, 0.01);
  EXPECT_DOUBLE_EQ(Units::parse("mm").metres_per_unit, 0.001);
  EXPECT_DOUBLE_EQ(Units::parse("0.0033333").metres_per_unit, 0.0033333);
  EXPECT_THROW(Units::parse("inch"), InputError);
  EXPECT_THROW(Units::parse("-1"), InputError);
  EXPECT_THROW(Units::parse("nan"), InputError);
  EXPECT_THROW(Units::parse(""), InputError);
  EXPECT_THROW(parse_up_axis("w"), InputError);
}

TEST(Io, ObjRoundTripIsExactAndKeepsQuads) {
  test::TempDir dir;
  TriangleMesh cube = fixtures::cube(0.3);
  cube.V.row(0) << -0.15000000000000002, -0.1, 0.1234567890123456789;  // needs 17 digits
  save_mesh(cube, dir.file("cube.obj"));
  const TriangleMesh back = load_mesh(dir.file("cube.obj"));
  EXPECT_EQ(back.V, cube.V);  // exact: shortest round-trip numbers, file order kept
  EXPECT_EQ(back.quads, cube.quads);
  EXPECT_EQ(back.F, cube.F);
  EXPECT_EQ(back.source_vertex, Eigen::VectorXi::LinSpaced(8, 0, 7));
}

TEST(Io, PolygonsMeetingAtATJunctionLoadManifold) {
  // Two pentagons side by side, each with a corner halfway along the side they share and listed
  // first from the side's end: fanned, each would add a flat triangle and an edge along that side,
  // which four faces would then use.
  test::TempDir dir;
  write_text(dir.file("t.obj"),
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 2 0 0\nv 2 2 0\n"
             "f 2 3 4 5 1\nf 4 3 2 6 7\n");
  const TriangleMesh m = load_mesh(dir.file("t.obj"));
  const TopologyReport t = analyse_topology(m);
  EXPECT_EQ(t.num_faces, 6);
  EXPECT_EQ(t.num_non_manifold_edges, 0);
  EXPECT_EQ(t.num_degenerate_faces, 0);
  EXPECT_TRUE(t.manifold);
  EXPECT_NEAR(t.area, 4.0, 1e-12);
  // A dart-shaped quad is split along the diagonal inside it and kept as a quad from that corner.
  write_text(dir.file("dart.obj"), "v 0 0 0\nv 1 0.3 0\nv 2 0 0\nv 1 2 0\nf 1 2 3 4\n");
  const TriangleMesh dart = load_mesh(dir.file("dart.obj"));
  ASSERT_EQ(dart.quads.rows(), 1);
  EXPECT_EQ(dart.quads.row(0), Eigen::RowVector4i(1, 2, 3, 0));
  EXPECT_NEAR(analyse_topology(dart).area, 1.7, 1e-12);
  save_mesh(dart, dir.file("back.obj"));
  EXPECT_EQ(load_mesh(dir.file("back.obj")).quads, dart.quads);
}

TEST(Io, PlyRoundTripKeepsOrderAndQuads) {
  test::TempDir dir;
  TriangleMesh m = fixtures::cube(1.7);
  m.labels = Eigen::VectorXi::LinSpaced(8, 0, 7);
  save_mesh(m, dir.file("cube.ply"));
  const TriangleMesh back = load_mesh(dir.file("cube.ply"));
  ASSERT_EQ(back.num_vertices(), 8);
  // The file holds doubles, but assimp reads PLY in single precision.
  EXPECT_TRUE(back.V.isApprox(m.V, 1e-7));
  EXPECT_EQ(back.quads, m.quads);
  expect_same_surface(m, back, 1e-6);
}

// Every format the loader reads, written by save_mesh and read back.
class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, SurfaceSurvives) {
  test::TempDir dir;
  TriangleMesh m = fixtures::cube(0.5);
  m.V.col(1).array() += 1.0;  // off the origin, so a lost translation would show
  const std::string path = dir.file("cube." + GetParam());
  save_mesh(m, path);
  EXPECT_TRUE(std::filesystem::exists(path));
  // STL has no shared vertices, and assimp splits vertices by normal: compare after merging.
  const TriangleMesh back = cleanup_mesh(load_mesh(path)).mesh;
  EXPECT_EQ(back.num_vertices(), 8);
  expect_same_surface(m, back, 1e-6);
  // No temporary file left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().rfind(".dresskit-tmp", 0), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(AllFormats, RoundTrip,
                         ::testing::Values("obj", "ply", "off", "stl", "glb", "gltf", "fbx"));

// STL stores each triangle's corners anew: read, the corners at one position are one vertex, so a
// closed surface is closed as read (a body or garment in STL is usable without cleaning).
TEST(Io, StlCornersAtOnePositionAreOneVertex) {
  test::TempDir dir;
  const TriangleMesh m = fixtures::cube(0.5);
  save_mesh(m, dir.file("cube.stl"));
  const TriangleMesh back = load_mesh(dir.file("cube.stl"));
  EXPECT_EQ(back.num_vertices(), 8);
  EXPECT_EQ(back.num_faces(), 12);
  const auto t = analyse_topology(back);
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.num_components, 1);
  expect_same_surface(m, back, 1e-6);
}

TEST(Io, UnitsAndUpAxisAreApplied) {
  test::TempDir dir;
  write_text(dir.file("tri.obj"), "v 0 0 0\nv 10 0 0\nv 0 0 20\nf 1 2 3\n");
  LoadOptions options;
  options.units = Units::parse("cm");
  options.up = UpAxis::pos_z;
  const TriangleMesh m = load_mesh(dir.file("tri.obj"), options);
  // +Z up becomes +Y up: (x, y, z) -> (x, z, -y); then centimetres -> metres.
  EXPECT_TRUE(m.V.row(1).isApprox(Eigen::RowVector3d(0.1, 0, 0)));
  EXPECT_TRUE(m.V.row(2).isApprox(Eigen::RowVector3d(0, 0.2, 0)));
  for (UpAxis up : {UpAxis::pos_x, UpAxis::neg_x, UpAxis::neg_y, UpAxis::neg_z}) {
    options.up = up;
    options.units = Units::parse("m");
    const TriangleMesh r = load_mesh(dir.file("tri.obj"), options);
    // A proper rotation: lengths and the triangle's orientation are kept.
    EXPECT_NEAR((r.V.row(2) - r.V.row(1)).norm(), std::sqrt(500.0), 1e-12) << to_string(up);
    EXPECT_NEAR(analyse_topology(r).area, 100.0, 1e-9) << to_string(up);
  }
}

TEST(Io, ObjVertexOrderMapSurvivesUvSeamsAndUnusedVertices) {
  test::TempDir dir;
  // Vertex 3 is unused; vertices 1 and 2 get two different UVs (a seam), which assimp splits.
  write_text(dir.file("seam.obj"),
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 9 9 9\nv 0 1 0\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 0.5\nvt 0.25 0.25\nvt 0 1\n"
             "f 1/1 2/2 3/3\nf 1/1 3/4 5/6\nf 2/5 3/3 5/6\n");
  const TriangleMesh m = load_mesh(dir.file("seam.obj"));
  ASSERT_EQ(m.num_vertices(), 5);  // exactly the `v` lines, in file order
  EXPECT_TRUE(m.V.row(3).isApprox(Eigen::RowVector3d(9, 9, 9)));
  EXPECT_EQ(m.F.rows(), 3);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 4));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(1, 2, 4));
  ASSERT_EQ(m.UV.rows(), 5);
  EXPECT_TRUE(m.UV.row(4).isApprox(Eigen::RowVector2d(0, 1)));
  // The seam's corners keep their own coordinates, also through a save and a load.
  ASSERT_EQ(m.FTC.rows(), 3);
  const auto corner = [](const TriangleMesh& mesh, int f, int k) -> Eigen::RowVector2d {
    return mesh.TC.row(mesh.FTC(f, k));
  };
  EXPECT_EQ(corner(m, 0, 1), Eigen::RowVector2d(1, 0));
  EXPECT_EQ(corner(m, 1, 1), Eigen::RowVector2d(0.5, 0.5));
  EXPECT_EQ(corner(m, 2, 0), Eigen::RowVector2d(0.25, 0.25));
  save_mesh(m, dir.file("again.obj"));
  const TriangleMesh again = load_mesh(dir.file("again.obj"));
  ASSERT_EQ(again.F, m.F);
  ASSERT_EQ(again.FTC.rows(), 3);
  for (int f = 0; f < 3; ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(corner(again, f, k), corner(m, f, k)) << f << " " << k;
  // Two quads with a seam between them are written back as they were read.
  const std::string quads = "f 1/1 2/2 5/3 4/4\nf 2/5 3/6 6/7 5/8\n";
  write_text(dir.file("quads.obj"),
             "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 3 0\nvt 4 0\nvt 4 1\nvt 3 1\n" + quads);
  save_mesh(load_mesh(dir.file("quads.obj")), dir.file("quads_again.obj"));
  std::ifstream in(dir.file("quads_again.obj"));
  std::string faces;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("f ", 0) == 0) faces += line + "\n";
  EXPECT_EQ(faces, quads);
}

// Two triangles that share an edge but not its texture coordinates (a UV seam, as between a
// garment's panels): OBJ keeps one `v` per vertex and one `vt` per coordinate; glTF, with attributes
// per vertex only, writes the seam's vertices once for each of their coordinates.
TEST(Io, CornerTextureCoordinatesKeepTheirSeam) {
  test::TempDir dir;
  TriangleMesh m = fixtures::grid(1, 1, 1.0);  // faces (0, 1, 3) and (0, 3, 2)
  m.TC.resize(6, 2);
  m.TC << 0, 0, 1, 0, 1, 1, 2, 0, 3, 1, 2, 1;
  m.FTC.resize(2, 3);
  m.FTC << 0, 1, 2, 3, 4, 5;
  // One group per face, as a pattern's panels (a name's blank becomes an underscore).
  m.face_groups = Eigen::Vector2i(0, 1);
  m.group_names = {"front panel", "back"};
  save_mesh(m, dir.file("seam.obj"));
  std::ifstream in(dir.file("seam.obj"));
  std::vector<std::string> faces;
  int vertices = 0, coordinates = 0;
  for (std::string line; std::getline(in, line);) {
    vertices += line.rfind("v ", 0) == 0;
    coordinates += line.rfind("vt ", 0) == 0;
    if (line.rfind("f ", 0) == 0 || line.rfind("g ", 0) == 0) faces.push_back(line);
  }
  EXPECT_EQ(vertices, 4);
  EXPECT_EQ(coordinates, 6);
  ASSERT_EQ(faces.size(), 4u);
  EXPECT_EQ(faces[0], "g front_panel");
  EXPECT_EQ(faces[1], "f 1/1 2/2 4/3");
  EXPECT_EQ(faces[2], "g back");
  EXPECT_EQ(faces[3], "f 1/4 4/5 3/6");
  const TriangleMesh obj = load_mesh(dir.file("seam.obj"));
  EXPECT_EQ(obj.V, m.V);
  EXPECT_EQ(obj.F, m.F);

  save_mesh(m, dir.file("seam.glb"));
  const TriangleMesh glb = load_mesh(dir.file("seam.glb"));
  ASSERT_EQ(glb.num_vertices(), 6);  // vertices 0 and 3 twice, with their two coordinates each
  ASSERT_EQ(glb.UV.rows(), 6);
  // Every written vertex is a corner of m: its position and its coordinate together.
  for (int w = 0; w < 6; ++w) {
    bool found = false;
    for (int f = 0; f < 2; ++f)
      for (int k = 0; k < 3; ++k)
        found = found || (glb.V.row(w).isApprox(m.V.row(m.F(f, k)), 1e-6) &&
                          (glb.UV.row(w) - m.TC.row(m.FTC(f, k))).norm() < 1e-6);
    EXPECT_TRUE(found) << "written vertex " << w;
  }
  EXPECT_NEAR(analyse_topology(glb).area, 1.0, 1e-6);
  // Corners that name a coordinate the mesh does not have, or faces in a group without a name,
  // are refused.
  validate_mesh(m, "good");
  m.face_groups(1) = 2;
  EXPECT_THROW(validate_mesh(m, "bad"), InputError);
  m.face_groups(1) = 1;
  m.FTC(1, 2) = 6;
  EXPECT_THROW(validate_mesh(m, "bad"), InputError);
}

TEST(Io, SaveLeavesNothingWhenTheFolderIsMissing) {
  test::TempDir dir;
  const std::string path = dir.file("missing/out.obj");
  EXPECT_THROW(save_mesh(fixtures::cube(1.0), path), OutputError);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_THROW(save_mesh(fixtures::cube(1.0), dir.file("out.xyz")), OutputError);
  TriangleMesh bad = fixtures::cube(1.0);
  bad.V(0, 0) = std::nan("");
  EXPECT_THROW(save_mesh(bad, dir.file("nan.obj")), OutputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}
