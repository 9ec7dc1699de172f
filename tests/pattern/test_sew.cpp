// Sewing on its own: two rectangles either side of a box are drawn shut around it and welded; a
// step limit leaves pairs open and unwelded; panels placed inside the body are refused.
#include <gtest/gtest.h>

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

TEST(PatternSew, TwoPanelsAroundABoxAreDrawnShutAndWelded) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  const SewResult r = sew_pattern(p, cut, box_between_panels());
  EXPECT_TRUE(r.closed) << r.stopped;
  EXPECT_EQ(r.method, "drawn");
  EXPECT_EQ(r.stopped, "closed");
  EXPECT_EQ(r.closed_pairs, r.stitch_pairs);
  EXPECT_EQ(r.stitch_pairs, 2 * 16);  // both 60 cm sides in 15 pieces
  EXPECT_LE(r.max_gap, 0.002);
  // Each pair welded into one vertex; the box inside the tube, none of the garment in the box.
  EXPECT_EQ(r.garment.V.rows(), cut.placed.rows() - r.stitch_pairs);
  for (Eigen::Index v = 0; v < r.garment.V.rows(); ++v) {
    const Eigen::Vector3d x = r.garment.V.row(v).transpose() - Eigen::Vector3d(0, 1.1, 0);
    EXPECT_GT(x.cwiseAbs().maxCoeff(), 0.1) << v;
  }
}

TEST(PatternSew, AStepLimitLeavesPairsOpenAndUnwelded) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  SewOptions o;
  o.max_steps = 2;
  o.fallback_acceleration = 0.0;
  const SewResult r = sew_pattern(p, cut, box_between_panels(), o);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.stopped, "step limit");
  EXPECT_EQ(r.steps, 2);
  EXPECT_LT(r.closed_pairs, r.stitch_pairs);
  EXPECT_GT(r.max_gap, 0.2);  // 30 cm apart, drawn 0.5 m/s for 2 steps
  EXPECT_EQ(r.garment.V.rows(), cut.placed.rows() - r.closed_pairs);
}

TEST(PatternSew, PanelsPlacedInsideTheBodyAreRefused) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  const CutPattern cut = cut_pattern(p, {0.04});
  mesh::TriangleMesh big = fixtures::cube(1.0);
  big.V.col(1).array() += 1.1;
  EXPECT_THROW(
      {
        try {
          sew_pattern(p, cut, big);
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
