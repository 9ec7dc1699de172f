#include <gtest/gtest.h>

#include <set>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"
#include "mannequin_fixture.h"

using namespace dresskit::mannequin;

using namespace dresskit;
using namespace dresskit::mesh;

class Garment : public ::testing::TestWithParam<GarmentKind> {
 protected:
  const TriangleMesh& garment() const {
    const auto& kinds = all_garment_kinds();
    const size_t i = std::find(kinds.begin(), kinds.end(), GetParam()) - kinds.begin();
    return test::DefaultScene::get().garments[i];
  }
};

TEST_P(Garment, OpenManifoldOrientedWithTheRightOpenings) {
  const TopologyReport t = analyse_topology(garment());
  EXPECT_TRUE(t.manifold);
  EXPECT_TRUE(t.consistently_oriented);
  EXPECT_EQ(t.num_components, 1);
  EXPECT_EQ(t.num_degenerate_faces, 0);
  const int loops = GetParam() == GarmentKind::tshirt ? 4 : GetParam() == GarmentKind::skirt ? 2 : 3;
  EXPECT_EQ(t.num_boundary_loops, loops);
  // A sphere with n holes has Euler characteristic 2 − n: no handles, no stray pieces.
  EXPECT_EQ(t.euler_characteristic, 2 - loops);
}

TEST_P(Garment, LabelsCoverEveryVertexWithTheExpectedParts) {
  const TriangleMesh& g = garment();
  ASSERT_EQ(g.labels.size(), g.num_vertices());
  ASSERT_EQ(g.label_names, garment_part_names());
  std::set<int> parts(g.labels.data(), g.labels.data() + g.labels.size());
  using P = GarmentPart;
  std::set<int> expected;
  switch (GetParam()) {
    case GarmentKind::tshirt: expected = {int(P::body), int(P::sleeve_left), int(P::sleeve_right)}; break;
    case GarmentKind::trousers: expected = {int(P::body), int(P::leg_left), int(P::leg_right)}; break;
    case GarmentKind::skirt: expected = {int(P::skirt)}; break;
  }
  EXPECT_EQ(parts, expected);
  // Left parts are on the character's left (+X).
  for (int i = 0; i < g.num_vertices(); ++i) {
    const int l = g.labels(i);
    if (l == int(P::sleeve_left) || l == int(P::leg_left)) {
      ASSERT_GT(g.V(i, 0), 0.0);
    }
    if (l == int(P::sleeve_right) || l == int(P::leg_right)) {
      ASSERT_LT(g.V(i, 0), 0.0);
    }
  }
}

TEST_P(Garment, RestsOutsideTheBodyWithNormalsPointingAway) {
  const auto& scene = test::DefaultScene::get();
  const TriangleMesh& g = garment();
  const double ease = scene.garment_options.ease;
  const Eigen::MatrixX3d N = vertex_normals(g.V, g.F);
  int away = 0;
  double closest = 1e9;
  for (int i = 0; i < g.num_vertices(); ++i) {
    const Eigen::Vector3d p = g.V.row(i).transpose();
    closest = std::min(closest, scene.body.value(p));
    // The body field grows along the garment normal.
    away += scene.body.value(p + 1e-3 * N.row(i).transpose()) > scene.body.value(p);
    // Independent of the field: no garment vertex is inside the body mesh.
    if (i % 7 == 0) {
      ASSERT_LT(test::winding_number(scene.mannequin, p), 0.5) << "vertex " << i;
    }
  }
  EXPECT_GT(closest, 0.3 * ease);
  EXPECT_GT(away, 0.97 * g.num_vertices());
}

INSTANTIATE_TEST_SUITE_P(All, Garment, ::testing::ValuesIn(all_garment_kinds()),
                         [](const auto& info) { return to_string(info.param); });

TEST(Garments, BadOptionsAndNamesAreRejected) {
  const BodyShape& body = test::DefaultScene::get().body;
  GarmentOptions o;
  o.ease = -0.01;
  EXPECT_THROW(make_garment(body, GarmentKind::skirt, o), InputError);
  EXPECT_THROW(parse_garment_kind("hat"), InputError);
  EXPECT_EQ(parse_garment_kind("t-shirt"), GarmentKind::tshirt);
}

// The scene across sizes and poses: every garment keeps its topology (make_garment checks it and
// throws otherwise), and no garment vertex is inside the body field.
TEST(Garments, FitBodiesOfOtherSizesAndPoses) {
  struct Config {
    double height, girth;
    Pose pose;
  };
  for (const Config& c : {Config{1.6, 0.8, Pose::t_pose}, Config{1.9, 1.3, Pose::a_pose},
                          Config{1.2, 1.0, Pose::a_pose}}) {
    MannequinOptions o;
    o.height = c.height;
    o.girth = c.girth;
    o.pose = c.pose;
    o.edge_length = 0.03;
    const BodyShape body(o);
    GarmentOptions g;
    g.edge_length = 0.03;
    for (GarmentKind kind : all_garment_kinds()) {
      TriangleMesh m;
      ASSERT_NO_THROW(m = make_garment(body, kind, g)) << to_string(kind) << " " << c.height;
      double closest = 1e9;
      for (int i = 0; i < m.num_vertices(); ++i) closest = std::min(closest, body.value(m.V.row(i).transpose()));
      EXPECT_GT(closest, 0.3 * g.ease) << to_string(kind) << " " << c.height;
    }
  }
}

TEST(Garments, TooMuchEaseOnAThinChildIsReportedNotReturned) {
  MannequinOptions o;
  o.height = 1.0;
  o.girth = 0.6;
  o.edge_length = 0.03;
  GarmentOptions g;
  g.edge_length = 0.03;  // default ease 1.5 cm: the offset thighs fuse into a handle
  try {
    make_garment(BodyShape(o), GarmentKind::trousers, g);
    FAIL() << "fused trouser legs were returned";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ease"), std::string::npos) << e.what();
  }
}
