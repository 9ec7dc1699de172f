// What a dressed garment got wrong, said in its warnings (dressing/src/garments.h,
// dressed_warnings): checked on garments whose counts and panel areas are set by hand, so that each
// sentence is known in advance, and none is said of a garment that went right.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "garments.h"

using namespace dresskit::dressing;
using namespace dresskit::dressing::detail;

namespace {

/// A pattern garment of two panels, 1 m² and 0.5 m² flat, dressed as given.
DressedGarment two_panels(double dressed_a, double dressed_b) {
  DressedGarment g;
  g.name = "shirt";
  g.from_pattern = true;
  g.pattern.panels = {"front", "back"};
  g.pattern.panel_area = {1.0, 0.5};
  g.pattern.panel_area_dressed = {dressed_a, dressed_b};
  return g;
}

}  // namespace

TEST(GarmentWarnings, NoneForAGarmentThatWentRight) {
  DressedGarment g = two_panels(1.029, 0.4855);  // +2.9 %, −2.9 %
  g.crossings_authored = g.crossings_dressed = 12;
  EXPECT_TRUE(dressed_warnings(g).empty());
}

TEST(GarmentWarnings, EachProblemIsOneSentenceWithItsFigures) {
  DressedGarment g = two_panels(1.185, 0.48);  // +18.5 %, −4 %
  g.crossings_authored = 5;
  g.crossings_dressed = 27;
  g.inside_dressed = 3;
  const std::vector<std::string> w = dressed_warnings(g);
  ASSERT_EQ(w.size(), 4u);
  EXPECT_EQ(w[0], "shirt crosses itself 27 times (5 as sewn)");
  EXPECT_EQ(w[1], "shirt has 3 vertices deeper than 2 mm inside the body");
  EXPECT_EQ(w[2], "shirt: panel 'front' grew by 18.5 % of its flat area");
  EXPECT_EQ(w[3], "shirt: panel 'back' shrank by 4 % of its flat area");
}

TEST(GarmentWarnings, APatternWithStitchesLeftOpenSaysHowMany) {
  DressedGarment g = two_panels(1.0, 0.5);
  g.name = "shirt";
  g.pattern.stitch_pairs = 195;
  g.pattern.sewn_pairs = 178;
  g.pattern.max_gap = 0.046127;
  const std::vector<std::string> w = dressed_warnings(g);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "shirt: 17 of 195 stitch pairs not sewn, the widest 46.1 mm open");
  g.pattern.welded_open_pairs = 5;
  EXPECT_EQ(dressed_warnings(g)[0], "shirt: 17 of 195 stitch pairs not sewn, the widest 46.1 mm open; 5 of them welded shut");
  g.pattern.welded_open_pairs = 17;
  EXPECT_EQ(dressed_warnings(g)[0], "shirt: 17 of 195 stitch pairs not sewn, the widest 46.1 mm open; welded shut");
  g.pattern.welded_open_pairs = 0;
  g.pattern.sewn_pairs = 195;
  EXPECT_TRUE(dressed_warnings(g).empty());
}

TEST(GarmentWarnings, AMeshGarmentIsComparedWithItselfAsAuthored) {
  DressedGarment g;
  g.name = "elegantsuit";
  g.crossings_authored = 43;
  g.crossings_dressed = 45;
  const std::vector<std::string> w = dressed_warnings(g);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "elegantsuit crosses itself 45 times (43 as authored)");
}

TEST(GarmentWarnings, AStalledPaddingIsSaidWithWhyAndHowFarShort) {
  DressedGarment g;
  g.name = "suit";
  g.padded = true;
  g.padding.min = 0.0159;
  g.padding.below_min = 753;
  EXPECT_TRUE(dressed_warnings(g).empty());
  const std::vector<std::string> w = dressed_warnings(g, "stalled: 50 steps in a row");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "suit: the padding stalled: 50 steps in a row; kept where it stopped, 753 vertices below its "
                  "lower limit of 15.9 mm");
}

TEST(GarmentWarnings, AnUnsettledPatternHasNoPanelAreasToJudge) {
  DressedGarment g = two_panels(0.0, 0.0);
  g.pattern.panel_area_dressed.clear();
  EXPECT_TRUE(dressed_warnings(g).empty());
}
