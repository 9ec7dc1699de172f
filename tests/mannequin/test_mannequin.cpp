#include <gtest/gtest.h>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"
#include "dresskit/testing/expect.h"
#include "mannequin_fixture.h"

using namespace dresskit::mannequin;

using namespace dresskit;
using namespace dresskit::mesh;

TEST(Mannequin, ClosedManifoldOutwardOneComponent) {
  const TriangleMesh& m = test::DefaultScene::get().mannequin;
  const TopologyReport t = analyse_topology(m);
  test::expect_closed_outward(t);
  EXPECT_EQ(t.euler_characteristic, 2);  // a sphere's topology: no handles
  EXPECT_EQ(t.num_degenerate_faces, 0);
  // An adult's volume is about 0.06–0.08 m³ and skin area about 1.6–2.0 m².
  test::expect_between(t.signed_volume, 0.045, 0.09, "volume [m³]");
  test::expect_between(t.area, 1.4, 2.2, "area [m²]");
}

TEST(Mannequin, SizeFollowsTheOptions) {
  const auto& scene = test::DefaultScene::get();
  const Eigen::AlignedBox3d box = bounding_box(scene.mannequin);
  const double H = scene.body.options().height;
  EXPECT_NEAR(box.max().y(), H, 0.01);
  EXPECT_NEAR(box.min().y(), 0.0, 0.015);
  // Vertices lie on the implicit surface.
  for (int i = 0; i < scene.mannequin.num_vertices(); ++i) {
    ASSERT_LT(std::abs(scene.body.value(scene.mannequin.V.row(i).transpose())), 1e-4) << i;
  }
}

TEST(Mannequin, LabelsCoverEveryVertexAndSitWhereThePartsAre) {
  const auto& scene = test::DefaultScene::get();
  const TriangleMesh& m = scene.mannequin;
  const Skeleton& s = scene.body.skeleton();
  ASSERT_EQ(m.labels.size(), m.num_vertices());
  ASSERT_EQ(m.label_names, body_part_names());
  std::vector<int> count(6, 0);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const int l = m.labels(i);
    ASSERT_GE(l, 0);
    ASSERT_LT(l, 6);
    ++count[l];
    const Eigen::Vector3d p = m.V.row(i).transpose();
    switch (static_cast<BodyPart>(l)) {
      case BodyPart::head_neck: EXPECT_GT(p.y(), s.neck_base.y() - 0.03); break;
      case BodyPart::arm_left: EXPECT_GT(p.x(), s.shoulder[0].x() - 0.06); break;
      case BodyPart::arm_right: EXPECT_LT(p.x(), s.shoulder[1].x() + 0.06); break;
      case BodyPart::leg_left: EXPECT_GT(p.x(), -0.02); EXPECT_LT(p.y(), s.hip[0].y() + 0.1); break;
      case BodyPart::leg_right: EXPECT_LT(p.x(), 0.02); EXPECT_LT(p.y(), s.hip[1].y() + 0.1); break;
      case BodyPart::torso: EXPECT_LT(p.y(), s.neck_base.y() + 0.08); break;
    }
  }
  for (int l = 0; l < 6; ++l) EXPECT_GT(count[l], 200) << body_part_names()[l];
  // Left and right are mirror images: similar counts.
  EXPECT_NEAR(count[2], count[3], 0.05 * count[2]);
  EXPECT_NEAR(count[4], count[5], 0.05 * count[4]);
}

TEST(Mannequin, TPoseIsWiderAndGirthScalesTheWaist) {
  MannequinOptions t_pose;
  t_pose.pose = Pose::t_pose;
  t_pose.edge_length = 0.03;
  MannequinOptions a_pose = t_pose;
  a_pose.pose = Pose::a_pose;
  const TriangleMesh t = make_mannequin(BodyShape(t_pose));
  const TriangleMesh a = make_mannequin(BodyShape(a_pose));
  EXPECT_GT(bounding_box(t).sizes().x(), 1.5);  // arm span ≈ height for the T-pose
  EXPECT_LT(bounding_box(a).sizes().x(), 1.35);
  EXPECT_TRUE(analyse_topology(t).closed);

  MannequinOptions big = a_pose;
  big.girth = 1.3;
  const BodyShape thin(a_pose), wide(big);
  const Eigen::Vector3d probe(0, thin.skeleton().waist_y, 0);
  // Half-width at the waist: march outwards along +X to the surface.
  auto half_width = [&](const BodyShape& b) {
    double x = 0;
    while (b.value(probe + Eigen::Vector3d(x, 0, 0)) < 0) x += 1e-4;
    return x;
  };
  EXPECT_NEAR(half_width(wide) / half_width(thin), 1.3, 0.05);
}

TEST(Mannequin, OptionsOutOfRangeAreRejected) {
  MannequinOptions o;
  o.height = 0.2;
  EXPECT_THROW(BodyShape{o}, InputError);
  o = {};
  o.girth = std::nan("");
  EXPECT_THROW(BodyShape{o}, InputError);
  o = {};
  o.edge_length = 0.0;
  EXPECT_THROW(BodyShape{o}, InputError);
  EXPECT_THROW(parse_pose("x-pose"), InputError);
}
