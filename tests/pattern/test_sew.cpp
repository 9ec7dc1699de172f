// Sewing on its own: two rectangles either side of a box are drawn shut around it and welded, also
// around a box standing elsewhere and a larger one; a step limit leaves pairs open and unwelded
// (welded where they lie within the weld gap); panels placed inside the body they are placed for
// are refused.
#include <gtest/gtest.h>

#include <algorithm>

#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/cut.h"
#include "dresskit/pattern/pattern.h"
#include "dresskit/pattern/sew.h"
#include "mesh/mesh_fixtures.h"
#include "pattern_fixtures.h"

using namespace dresskit::pattern;

namespace dresskit {
namespace {

// A 20 cm box standing between the two panels (z = ±15 cm, x from −20 to 20 cm, y 0.8–1.4 m).
mesh::TriangleMesh box_between_panels() {
  mesh::TriangleMesh box = fixtures::cube(0.2);
  box.V.col(1).array() += 1.1;
  return box;
}

// The pattern is placed for that box: it is the pattern's body. Its seams run along the box's
// whole height: all sewn at once.
SewOptions on_the_box() {
  SewOptions o;
  o.pattern_body = body_frame(box_between_panels());
  o.first_above = 0.0;
  return o;
}

// No garment vertex within `half` of the box's centre c along every axis (none in the box).
void expect_around(const SewResult& r, const Eigen::Vector3d& c, double half) {
  for (Eigen::Index v = 0; v < r.garment.V.rows(); ++v)
    EXPECT_GT((r.garment.V.row(v).transpose() - c).cwiseAbs().maxCoeff(), half) << v;
}

TEST(PatternSew, TwoPanelsAroundABoxAreDrawnShutAndWelded) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  const SewResult r = sew_pattern(p, cut, box_between_panels(), on_the_box());
  EXPECT_TRUE(r.closed) << r.stopped;
  EXPECT_EQ(r.method, "drawn");
  EXPECT_EQ(r.stopped, "closed");
  EXPECT_EQ(r.closed_pairs, r.stitch_pairs);
  EXPECT_EQ(r.stitch_pairs, 2 * 16);  // both 60 cm sides in 15 pieces
  EXPECT_LE(r.max_gap, 0.002);
  // Each pair welded into one vertex; the box inside the tube, none of the garment in the box.
  EXPECT_EQ(r.garment.V.rows(), cut.placed.rows() - r.stitch_pairs);
  expect_around(r, Eigen::Vector3d(0, 1.1, 0), 0.1);
  EXPECT_EQ(r.moved_by, Eigen::Vector3d::Zero());
}

// The same box standing 40 cm lower and 30 cm to the side: the panels follow it and close around
// it.
TEST(PatternSew, PanelsFollowABodyStandingElsewhere) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  mesh::TriangleMesh box = box_between_panels();
  box.V.rowwise() += Eigen::RowVector3d(0.3, -0.4, 0.0);
  const SewResult r = sew_pattern(p, cut, box, on_the_box());
  EXPECT_TRUE(r.closed) << r.stopped;
  EXPECT_NEAR(r.moved_by.x(), 0.3, 1e-9);
  EXPECT_NEAR(r.moved_by.y(), -0.4, 1e-9);  // same height: no scaling of the centroid's height
  EXPECT_NEAR(r.moved_by.z(), 0.0, 1e-9);
  EXPECT_EQ(r.panels_moved_out, 0);
  expect_around(r, Eigen::Vector3d(0.3, 0.7, 0), 0.1);
}

// A box 5 cm wide and 32 cm deep (the panels, 15 cm from its centre, lie in it), standing 5 cm to
// the side: each panel is moved out along its normal until 5 mm clear, then the two are sewn around
// it.
TEST(PatternSew, PanelsCarriedIntoALargerBodyAreMovedOutOfIt) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  mesh::TriangleMesh box = box_between_panels();
  box.V.col(0) *= 0.25;
  box.V.col(2) *= 1.6;
  box.V.col(0).array() += 0.05;
  const SewResult r = sew_pattern(p, cut, box, on_the_box());
  EXPECT_EQ(r.panels_moved_out, 2);
  EXPECT_TRUE(r.closed) << r.stopped;
  for (Eigen::Index v = 0; v < r.garment.V.rows(); ++v) {
    const Eigen::Vector3d x = r.garment.V.row(v).transpose() - Eigen::Vector3d(0.05, 1.1, 0);
    EXPECT_TRUE(std::abs(x.x()) > 0.025 || std::abs(x.y()) > 0.1 || std::abs(x.z()) > 0.16) << v;
  }
}

// A box's frame: the floor at its lowest point, its height, below its centre (no vertex of the box
// lies between 55 % and 70 % of its height: its whole bounding box counts).
TEST(PatternSew, BodyFrameOfABox) {
  mesh::TriangleMesh box = fixtures::cube(1.0);  // y −0.5…0.5: floor −0.5, 1 m tall
  box.V.col(2).array() += 0.25;
  const BodyFrame f = body_frame(box);
  EXPECT_NEAR(f.height, 1.0, 1e-12);
  EXPECT_NEAR(f.origin.y(), -0.5, 1e-12);
  EXPECT_NEAR(f.origin.x(), 0.0, 1e-12);
  EXPECT_NEAR(f.origin.z(), 0.25, 1e-12);
}

// Sewing on the box stopped after two steps, without the seam-force fallback: the panels still
// 20 cm or more apart.
SewOptions stopped_after_two_steps() {
  SewOptions o = on_the_box();
  o.max_steps = 2;
  o.fallback_acceleration = 0.0;
  return o;
}

TEST(PatternSew, AStepLimitLeavesPairsOpenAndUnwelded) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  const SewResult r = sew_pattern(p, cut, box_between_panels(), stopped_after_two_steps());
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.stopped, "step limit");
  EXPECT_EQ(r.steps, 2);
  EXPECT_LT(r.closed_pairs, r.stitch_pairs);
  EXPECT_GT(r.max_gap, 0.2);  // 30 cm apart, drawn 0.5 m/s for 2 steps
  EXPECT_EQ(r.welded_open, 0);  // all farther apart than the weld gap
  EXPECT_EQ(r.garment.V.rows(), cut.placed.rows() - r.closed_pairs);
}

// Pairs left open are welded where their sides lie within the weld gap, the others stay open: a
// gap between the open pairs' distances splits them.
TEST(PatternSew, PairsLeftOpenWithinTheWeldGapAreWelded) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  SewOptions o = stopped_after_two_steps();
  o.weld_gap = 0.0;
  const SewResult open = sew_pattern(p, cut, box_between_panels(), o);
  ASSERT_EQ(open.welded_open, 0);
  std::vector<double> gaps;
  for (const std::array<int, 2>& pair : cut.stitch_pairs)
    gaps.push_back((open.sewn.row(pair[0]) - open.sewn.row(pair[1])).norm());
  std::vector<double> sorted = gaps;
  std::sort(sorted.begin(), sorted.end());
  o.weld_gap = 0.5 * (sorted[sorted.size() / 2] + sorted[sorted.size() / 2 + 1]);
  ASSERT_LT(sorted[sorted.size() / 2], sorted[sorted.size() / 2 + 1]);
  const SewResult r = sew_pattern(p, cut, box_between_panels(), o);
  EXPECT_EQ(r.sewn, open.sewn);  // the same run; only the welding differs
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.closed_pairs, open.closed_pairs);
  int within = 0;
  for (double g : gaps) within += g <= o.weld_gap;
  EXPECT_EQ(r.welded_open, within);
  EXPECT_EQ(r.garment.V.rows(), cut.placed.rows() - r.closed_pairs - r.welded_open);
  for (std::size_t q = 0; q < cut.stitch_pairs.size(); ++q) {
    const bool joined = r.welded_vertex[std::size_t(cut.stitch_pairs[q][0])] ==
                        r.welded_vertex[std::size_t(cut.stitch_pairs[q][1])];
    EXPECT_EQ(joined, gaps[q] <= o.weld_gap) << q;
  }
}

// The seam-force fallback runs only where some pair is left farther open than the weld gap.
TEST(PatternSew, NoSeamForcesWhereEveryOpenPairIsWelded) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  SewOptions o = on_the_box();
  o.max_steps = 2;
  o.weld_gap = 1.0;  // the panels are 30 cm apart
  const SewResult welded = sew_pattern(p, cut, box_between_panels(), o);
  EXPECT_EQ(welded.method, "drawn");
  EXPECT_EQ(welded.steps, 2);
  EXPECT_EQ(welded.closed_pairs + welded.welded_open, welded.stitch_pairs);
  o.weld_gap = 0.1;
  const SewResult tried = sew_pattern(p, cut, box_between_panels(), o);
  EXPECT_GT(tried.steps, 2);  // both tries' steps
}

TEST(PatternSew, PanelsPlacedInsideTheBodyAreRefused) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  mesh::TriangleMesh big = fixtures::cube(1.0);
  big.V.col(1).array() += 1.1;
  EXPECT_THROW(
      {
        try {
          SewOptions o;
          o.pattern_body = body_frame(big);  // placed for this body, in it
          sew_pattern(p, cut, big, o);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("inside the body: it is placed for another body"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
}

}  // namespace
}  // namespace dresskit
