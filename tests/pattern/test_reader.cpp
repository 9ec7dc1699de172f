// Reading GarmentCode patterns: the shared files, units and coordinates, and bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/curves.h"
#include "dresskit/pattern/pattern.h"
#include "pattern_fixtures.h"

using namespace dresskit::pattern;

namespace dresskit::pattern {
namespace {

/// The InputError message of parsing `text`, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_pattern(text, "bad.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PatternReader, SharedPatternsInMetres) {
  DRESSKIT_REQUIRE_DATA();
  struct Expected {
    std::string file;
    int panels, stitches;
  };
  for (const Expected& x : {Expected{"gc_shirt_mean_specification.json", 8, 18},
                            Expected{"gc_hoody_mean_specification.json", 6, 12},
                            Expected{"gc_dress_pencil_specification.json", 6, 23}}) {
    const Pattern p = read_pattern(test::shared_pattern(x.file));
    EXPECT_EQ(int(p.panels.size()), x.panels) << x.file;
    EXPECT_EQ(int(p.stitches.size()), x.stitches) << x.file;
    EXPECT_DOUBLE_EQ(p.units_in_meter, 100.0);
    EXPECT_EQ(p.name, x.file.substr(0, x.file.size() - 5));
    for (const Panel& panel : p.panels) {
      // Every panel is a garment piece of 10 cm to 1.2 m across, in metres.
      const double size =
          (panel.vertices.colwise().maxCoeff() - panel.vertices.colwise().minCoeff()).maxCoeff();
      EXPECT_GT(size, 0.1) << panel.name;
      EXPECT_LT(size, 1.2) << panel.name;
      // The panels hang between the knees and the top of the head of a 1.7 m body.
      EXPECT_GT(panel.translation.y(), 0.0) << panel.name;
      EXPECT_LT(panel.translation.y(), 1.8) << panel.name;
    }
  }
  // The shirt's left front: its file's translation [cm] and first vertices, in metres.
  const Pattern shirt = read_pattern(test::shared_pattern("gc_shirt_mean_specification.json"));
  const Panel& lf = shirt.panels[shirt.panel_index("left_ftorso")];
  EXPECT_NEAR(lf.translation.y(), 0.9457103829637592, 1e-12);
  EXPECT_NEAR(lf.translation.z(), 0.25, 1e-12);
  // A sleeve is turned about z by the file's −50.483°: its plane's x axis goes along the arm.
  const Panel& sleeve = shirt.panels[shirt.panel_index("left_sleeve_b")];
  EXPECT_NEAR(sleeve.rotation()(0, 0), std::cos(-50.483 * M_PI / 180.0), 1e-9);
  EXPECT_NEAR(sleeve.rotation()(1, 0), std::sin(-50.483 * M_PI / 180.0), 1e-9);
}

TEST(PatternReader, HoodSeamsJoinStartToEnd) {
  DRESSKIT_REQUIRE_DATA();
  // The hoody's torso panels, placed by the file, meet along their seams: each stitched edge starts
  // where its partner ends (the convention the stitches follow), seen from the front.
  const Pattern p = read_pattern(test::shared_pattern("gc_hoody_mean_specification.json"));
  int checked = 0;
  for (const Stitch& s : p.stitches) {
    const Panel& a = p.panels[s.a.panel];
    const Panel& b = p.panels[s.b.panel];
    if (a.name.find("torso") == std::string::npos || b.name.find("torso") == std::string::npos)
      continue;
    const Edge& ea = a.edges[s.a.edge];
    const Edge& eb = b.edges[s.b.edge];
    // Torso panels lie in planes z = const, so compare x and y.
    const Eigen::Vector3d a0 = a.place(a.vertices.row(ea.start).transpose());
    const Eigen::Vector3d a1 = a.place(a.vertices.row(ea.end).transpose());
    const Eigen::Vector3d b0 = b.place(b.vertices.row(eb.start).transpose());
    const Eigen::Vector3d b1 = b.place(b.vertices.row(eb.end).transpose());
    EXPECT_LT((a0 - b1).head<2>().norm(), 0.03) << p.edge_name(s.a.panel, s.a.edge);
    EXPECT_LT((a1 - b0).head<2>().norm(), 0.03) << p.edge_name(s.a.panel, s.a.edge);
    EXPECT_LT((a0 - b1).head<2>().norm(), (a0 - b0).head<2>().norm())
        << p.edge_name(s.a.panel, s.a.edge);
    ++checked;
  }
  EXPECT_EQ(checked, 6);
}

TEST(PatternReader, RelativeAndAbsoluteCurvatureAgree) {
  // Relative (0.5, 0.2) on the edge (40, 0) → (40, 60): the control point is (40, 30) + 0.2 × (−60,
  // 0).
  const Pattern rel = parse_pattern(
      test::two_panel_pattern(
          R"({"endpoints": [1, 2], "curvature": {"type": "quadratic", "params": [[0.5, 0.2]]}})"),
      "rel.json");
  const Pattern abs = parse_pattern(
      test::two_panel_pattern(
          R"({"endpoints": [1, 2], "curvature": {"type": "quadratic", "params": [[28, 30]]}})",
          "[]", R"({"curvature_coords": "absolute", "units_in_meter": 100})"),
      "abs.json");
  const Edge& e = rel.panels[0].edges[1];
  ASSERT_EQ(e.kind, CurveKind::quadratic);
  EXPECT_NEAR((e.controls[0] - Eigen::Vector2d(0.28, 0.30)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(edge_length(rel.panels[0], 1), edge_length(abs.panels[0], 1), 1e-15);
  EXPECT_GT(edge_length(rel.panels[0], 1), 0.61);
}

TEST(PatternReader, UnitsFromTheFile) {
  const Pattern mm = parse_pattern(
      test::two_panel_pattern("{\"endpoints\": [1, 2]}", "[]", R"({"units_in_meter": 1000})"),
      "mm.json");
  EXPECT_NEAR(edge_length(mm.panels[0], 0), 0.04, 1e-15);
  EXPECT_NEAR(mm.panels[0].translation.y(), 0.08, 1e-15);
}

TEST(PatternReader, MissingUnitsNamed) {
  const std::string e = error_of(test::two_panel_pattern("{\"endpoints\": [1, 2]}", "[]",
                                                         R"({"curvature_coords": "relative"})"));
  EXPECT_NE(e.find("bad.json"), std::string::npos) << e;
  EXPECT_NE(e.find("units_in_meter"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
}

TEST(PatternReader, StitchToMissingPanelOrEdgeNamed) {
  const std::pair<const char*, const char*> cases[] = {
      {R"([[{"panel": "front", "edge": 1}, {"panel": "sleeve", "edge": 3}]])", "'sleeve' does not exist"},
      {R"([[{"panel": "front", "edge": 1}, {"panel": "back", "edge": 7}]])", "panel 'back' has no edge 7"}};
  for (const auto& [stitches, expected] : cases) {
    const std::string e = error_of(test::two_panel_pattern("{\"endpoints\": [1, 2]}", stitches));
    EXPECT_NE(e.find("stitch 0"), std::string::npos) << e;
    EXPECT_NE(e.find(expected), std::string::npos) << e;
  }
}

TEST(PatternReader, ZeroLengthEdgeNamed) {
  // Vertices 1 and 2 made equal: front's edge 1 has zero length.
  std::string text = test::two_panel_pattern();
  const std::string front = "\"vertices\": [[0, 0], [40, 0], [40, 60], [0, 60]]";
  text.replace(text.find(front), front.size(), "\"vertices\": [[0, 0], [40, 0], [40, 0], [0, 60]]");
  const std::string e = error_of(text);
  EXPECT_NE(e.find("panel 'front' edge 1"), std::string::npos) << e;
  EXPECT_NE(e.find("zero length"), std::string::npos) << e;
}

TEST(PatternReader, SelfIntersectingOutlineNamed) {
  // A bow tie: the front's corners 2 and 3 swapped, so edges 0 and 2 stay apart but 1 and 3 cross.
  std::string text = test::two_panel_pattern();
  const std::string front = "\"vertices\": [[0, 0], [40, 0], [40, 60], [0, 60]]";
  text.replace(text.find(front), front.size(),
               "\"vertices\": [[0, 0], [40, 0], [0, 60], [40, 60]]");
  const std::string e = error_of(text);
  EXPECT_NE(e.find("panel 'front'"), std::string::npos) << e;
  EXPECT_NE(e.find("crosses itself: edge 1 meets edge 3"), std::string::npos) << e;
}

TEST(PatternReader, CurvedEdgeCrossingItsPanelNamed) {
  // A quadratic edge 1 bulging far left through the opposite side (edge 3) of the panel.
  const std::string e = error_of(test::two_panel_pattern(
      R"({"endpoints": [1, 2], "curvature": {"type": "quadratic", "params": [[0.5, 1.5]]}})"));
  EXPECT_NE(e.find("crosses itself: edge 1 meets edge 3"), std::string::npos) << e;
}

// Numbers JSON allows but no garment has, each refused when read, naming where: a number beyond a
// double, a control point a million chords away, a panel a billion metres away, an angle of 1e300°.
TEST(PatternReader, AbsurdNumbersAreRefusedWhenRead) {
  std::string overflow = test::two_panel_pattern();
  overflow.replace(overflow.find("[-20, 80, 15]"), 13, "[-20, 1e999, 15]");
  const std::string e1 = error_of(overflow);
  EXPECT_NE(e1.find("bad.json: not valid JSON"), std::string::npos) << e1;
  const std::string e2 = error_of(test::two_panel_pattern(
      R"({"endpoints": [1, 2], "curvature": {"type": "quadratic", "params": [[0.5, 1e6]]}})"));
  EXPECT_NE(e2.find("panel 'front' edge 1"), std::string::npos) << e2;
  EXPECT_NE(e2.find("more than 10 chord lengths"), std::string::npos) << e2;
  std::string far = test::two_panel_pattern();
  far.replace(far.find("[-20, 80, 15]"), 13, "[1e14, 80, 15]");  // cm: 1e12 m
  const std::string e3 = error_of(far);
  EXPECT_NE(e3.find("panel 'front' translation"), std::string::npos) << e3;
  std::string turned = test::two_panel_pattern();
  turned.replace(turned.find("[0, 180, 0]"), 11, "[0, 1e300, 0]");
  const std::string e4 = error_of(turned);
  EXPECT_NE(e4.find("panel 'back' rotation"), std::string::npos) << e4;
  EXPECT_NE(e4.find("beyond a whole turn"), std::string::npos) << e4;
  for (const std::string& e : {e1, e2, e3, e4}) EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
}

TEST(PatternReader, UnequalStitchedEdgesWarnNamingBoth) {
  // Front edge 1 bulging by a cubic: 10 % longer than the straight back edge 3 it is sewn to.
  const Pattern p = parse_pattern(
      test::two_panel_pattern(
          R"({"endpoints": [1, 2], "curvature": {"type": "cubic", "params": [[0.3, 0.25], [0.7, 0.25]]}})"),
      "warn.json");
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_NE(p.warnings[0].find("stitch 0"), std::string::npos) << p.warnings[0];
  EXPECT_NE(p.warnings[0].find("panel 'front' edge 1"), std::string::npos) << p.warnings[0];
  EXPECT_NE(p.warnings[0].find("panel 'back' edge 3"), std::string::npos) << p.warnings[0];
  // A looser ratio accepts it.
  ReadOptions loose;
  loose.max_length_ratio = 1.5;
  EXPECT_TRUE(
      parse_pattern(
          test::two_panel_pattern(
              R"({"endpoints": [1, 2], "curvature": {"type": "cubic", "params": [[0.3, 0.25], [0.7, 0.25]]}})"),
          "warn.json", loose)
          .warnings.empty());
}

TEST(PatternReader, RepeatedStitchesAndThreeLayerSeamsAreSaid) {
  const std::string front1_back3 = R"([{"panel": "front", "edge": 1}, {"panel": "back", "edge": 3}])";
  // The same stitch twice, the second time from the other side.
  const Pattern twice = parse_pattern(
      test::two_panel_pattern("{\"endpoints\": [1, 2]}",
                              "[" + front1_back3 + R"(, [{"panel": "back", "edge": 3}, {"panel": "front", "edge": 1}]])"),
      "twice.json");
  ASSERT_EQ(twice.warnings.size(), 1u);
  EXPECT_EQ(twice.warnings[0], "twice.json: stitch 1 repeats stitch 0 (panel 'back' edge 3 to panel 'front' edge 1)");
  EXPECT_EQ(twice.stitches.size(), 2u);  // numbered as in the file
  // Front edge 1 sewn to the back's edges 3 and 1: a seam of three layers.
  const Pattern three = parse_pattern(
      test::two_panel_pattern("{\"endpoints\": [1, 2]}",
                              "[" + front1_back3 + R"(, [{"panel": "back", "edge": 1}, {"panel": "front", "edge": 1}]])"),
      "three.json");
  ASSERT_EQ(three.warnings.size(), 1u);
  EXPECT_EQ(three.warnings[0],
            "three.json: stitch 1: panel 'front' edge 1 is also sewn by stitch 0 (a seam of three layers)");
  // The shared patterns have neither.
  for (const char* f : {"gc_shirt_mean_specification.json", "gc_hoody_mean_specification.json",
                        "gc_dress_pencil_specification.json"}) {
    DRESSKIT_REQUIRE_DATA();
    for (const std::string& w : read_pattern(test::shared_pattern(f)).warnings) {
      EXPECT_EQ(w.find("repeats"), std::string::npos) << w;
      EXPECT_EQ(w.find("three layers"), std::string::npos) << w;
    }
  }
}

TEST(PatternReader, OpenOutlineAndBadEndpointNamed) {
  EXPECT_NE(
      error_of(test::two_panel_pattern("{\"endpoints\": [1, 3]}")).find("panel 'front' edge 1"),
      std::string::npos);
  EXPECT_NE(
      error_of(test::two_panel_pattern("{\"endpoints\": [1, 9]}")).find("vertex 9 does not exist"),
      std::string::npos);
  EXPECT_NE(error_of("{\"pattern\": ").find("not valid JSON"), std::string::npos);
}

}  // namespace
}  // namespace dresskit::pattern
