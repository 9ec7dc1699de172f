// The wearer fit (alignment/wearer.h) on the procedural mannequin, whose joints and garments are
// known by construction: the rig's elbows and knees against the skeleton's, and garments made on
// one mannequin carried onto another of another height, pose or place.
#include <gtest/gtest.h>

#include <cmath>

#include "dresskit/alignment/wearer.h"
#include "dresskit/mannequin/garments.h"
#include "dresskit/mannequin/mannequin.h"
#include "dresskit/mesh/inside.h"
#include "dresskit/testing/errors.h"

using namespace dresskit;
using namespace dresskit::alignment;
using namespace dresskit::mannequin;
using namespace dresskit::mesh;

namespace {

MannequinOptions coarse(double height = 1.75, Pose pose = Pose::a_pose) {
  MannequinOptions o;
  o.edge_length = 0.03;
  o.height = height;
  o.pose = pose;
  return o;
}

TriangleMesh shirt_on(const BodyShape& shape) {
  GarmentOptions o;
  o.edge_length = 0.03;
  return make_garment(shape, GarmentKind::tshirt, o);
}

int bone(const BodyRig& rig, const std::string& name) {
  for (std::size_t b = 0; b < rig.bones.size(); ++b)
    if (rig.bones[b] == name) return static_cast<int>(b);
  return -1;
}

/// Mean distance of the points to the body's surface, and how many lie deeper than 1 cm inside.
std::pair<double, int> against_body(const Eigen::MatrixX3d& V, const TriangleMesh& body) {
  const InsideTest inside(body);
  double sum = 0.0;
  int deep = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const double d = inside.signed_distance(V.row(i).transpose());
    sum += std::abs(d);
    deep += d < -0.01;
  }
  return {sum / static_cast<double>(V.rows()), deep};
}

}  // namespace

TEST(BodyPartKind, ReadsTheNamesOfSegmentationAndLabelFiles) {
  EXPECT_EQ(body_part_kind("arm_left"), BodyPartKind::arm_left);
  EXPECT_EQ(body_part_kind("left_arm"), BodyPartKind::arm_left);
  EXPECT_EQ(body_part_kind("right_leg"), BodyPartKind::leg_right);
  EXPECT_EQ(body_part_kind("head_neck"), BodyPartKind::head);
  EXPECT_EQ(body_part_kind("body"), BodyPartKind::torso);
  EXPECT_EQ(body_part_kind("face_internal"), BodyPartKind::torso);
}

// Elbows and knees where the mannequin's skeleton has them; weights that sum to one.
TEST(RigBody, SplitsLimbsAtTheSkeletonsElbowsAndKnees) {
  const BodyShape shape(coarse());
  const TriangleMesh body = make_mannequin(shape);
  const BodyRig rig = rig_body(body);
  ASSERT_EQ(rig.bones.size(), 10u);
  const Skeleton& s = shape.skeleton();
  // index 0 = left (+X) in the skeleton, as arm_left in the rig.
  EXPECT_LT((rig.joint[bone(rig, "arm_left_lower")] - s.elbow[0]).norm(), 0.05);
  EXPECT_LT((rig.joint[bone(rig, "arm_right_lower")] - s.elbow[1]).norm(), 0.05);
  EXPECT_LT((rig.joint[bone(rig, "leg_left_lower")] - s.knee[0]).norm(), 0.06);
  EXPECT_LT((rig.joint[bone(rig, "leg_right_lower")] - s.knee[1]).norm(), 0.06);
  EXPECT_LT((rig.joint[bone(rig, "arm_left_upper")] - s.shoulder[0]).norm(), 0.08);
  for (Eigen::Index v = 0; v < body.V.rows(); ++v) ASSERT_NEAR(rig.influence_weight.row(v).sum(), 1.0, 1e-9);
  TriangleMesh trunk = body;
  trunk.labels.setZero();
  EXPECT_NE(test::input_error_of([&] { rig_body(trunk); }).find("no arm or leg"), std::string::npos);
}

// A garment on the body it was made on: its wearer is the body itself and carrying moves nothing.
TEST(FitWearer, AGarmentOnItsOwnBodyStaysWhereItIs) {
  const BodyShape shape(coarse());
  const TriangleMesh body = make_mannequin(shape), shirt = shirt_on(shape);
  const BodyRig rig = rig_body(body);
  const WearerFit fit = fit_wearer(rig, body, shirt.V);
  EXPECT_NEAR(fit.scale, 1.0, 0.03);
  const CarriedGarment carried = carry_garment(rig, fit, shirt);
  EXPECT_LT(carried.mean_move, 0.005);
  // The shirt's parts named from the body parts they lie over.
  int sleeves = 0;
  for (Eigen::Index v = 0; v < carried.labels.size(); ++v)
    sleeves += carried.label_names[carried.labels(v)].rfind("sleeve", 0) == 0;
  EXPECT_GT(sleeves, carried.labels.size() / 10);
  EXPECT_EQ(std::count(carried.label_names.begin(), carried.label_names.end(), "leg_left"), 0);
}

// A shirt 8 dm above its body is found there and carried back down onto it.
TEST(FitWearer, FindsAGarmentFarFromTheBodyAndCarriesItBack) {
  const BodyShape shape(coarse());
  const TriangleMesh body = make_mannequin(shape), shirt = shirt_on(shape);
  TriangleMesh moved = shirt;
  moved.V.col(1).array() += 0.8;
  const BodyRig rig = rig_body(body);
  const WearerFit fit = fit_wearer(rig, body, moved.V);
  const CarriedGarment carried = carry_garment(rig, fit, moved);
  EXPECT_LT((carried.V - shirt.V).rowwise().norm().mean(), 0.01);
}

// A shirt made for a person of 1.75 m on one of 1.45 m: the wearer is that much larger, and the
// shirt carried onto the smaller body lies around it.
TEST(FitWearer, RecoversTheWearersSize) {
  const BodyShape tall(coarse(1.75)), small(coarse(1.45));
  const TriangleMesh body = make_mannequin(small), shirt = shirt_on(tall);
  const BodyRig rig = rig_body(body);
  const WearerFit fit = fit_wearer(rig, body, shirt.V);
  EXPECT_NEAR(fit.scale, 1.75 / 1.45, 0.06);
  const CarriedGarment carried = carry_garment(rig, fit, shirt);
  const auto [mean, deep] = against_body(carried.V, body);
  EXPECT_LT(mean, 0.035);
  EXPECT_LT(deep, carried.V.rows() / 50);
}

// A shirt made for the A-pose on a body in T-pose: the wearer's arms are turned down by about the
// 45° between the poses, and the carried sleeves lie around the horizontal arms.
TEST(FitWearer, TurnsTheArmsFromOnePoseToAnother) {
  const BodyShape a_pose(coarse()), t_pose(coarse(1.75, Pose::t_pose));
  const TriangleMesh body = make_mannequin(t_pose), shirt = shirt_on(a_pose);
  const BodyRig rig = rig_body(body);
  // With the default turn prior the short sleeves turn the upper arms by about 34°; with a weak
  // one, the data's 45°.
  WearerFitOptions o;
  o.turn_prior = 0.02;
  const WearerFit fit = fit_wearer(rig, body, shirt.V, o);
  const WearerFit held = fit_wearer(rig, body, shirt.V);
  for (const char* arm : {"arm_left_upper", "arm_right_upper"}) {
    EXPECT_NEAR(Eigen::AngleAxisd(held.turn[bone(rig, arm)]).angle() * 180.0 / M_PI, 34.0, 5.0) << arm;
    const double turn = Eigen::AngleAxisd(fit.turn[bone(rig, arm)]).angle() * 180.0 / M_PI;
    EXPECT_NEAR(turn, 45.0, 10.0) << arm;
  }
  const CarriedGarment carried = carry_garment(rig, fit, shirt);
  const auto [mean, deep] = against_body(carried.V, body);
  EXPECT_LT(mean, 0.035);
  EXPECT_LT(deep, carried.V.rows() / 50);
}
