// The pattern's picture: every panel and edge drawn, both sides of a stitch in the stitch's colour.
#include <gtest/gtest.h>

#include <array>
#include <regex>
#include <set>
#include <vector>

#include "dresskit/pattern/svg.h"
#include "pattern_fixtures.h"

using namespace dresskit::pattern;

namespace dresskit::pattern {
namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(PatternSvg, PanelsEdgesAndStitchColours) {
  DRESSKIT_REQUIRE_DATA();
  const Pattern p = read_pattern(test::shared_pattern("gc_dress_pencil_specification.json"));
  const std::string svg = pattern_svg(p);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(count(svg, "<g id="), int(p.panels.size()));
  int edges = 0;
  for (const Panel& panel : p.panels) {
    edges += int(panel.edges.size());
    EXPECT_NE(svg.find("<g id=\"" + panel.name + "\">"), std::string::npos) << panel.name;
  }
  EXPECT_EQ(count(svg, "<polyline"), edges);
  // Every stitch's colour is on exactly its two edges (stroke), its two labels and its two start
  // dots.
  std::set<std::string> colours;
  for (std::size_t s = 0; s < p.stitches.size(); ++s) {
    const std::string c = stitch_colour(int(s));
    colours.insert(c);
    EXPECT_EQ(count(svg, "stroke=\"" + c + "\""), 2) << "stitch " << s;
    EXPECT_EQ(count(svg, "fill=\"" + c + "\">"), 2) << "stitch " << s;  // its two edge numbers
    EXPECT_EQ(count(svg, "(s" + std::to_string(s) + ")"), 2) << "stitch " << s;
  }
  EXPECT_EQ(colours.size(), p.stitches.size()) << "one colour per stitch";
  // Titles name each edge: "panel 'skirt_back' edge 4, stitch 0".
  EXPECT_NE(svg.find("panel 'skirt_back' edge 4, stitch 0"), std::string::npos);
  // Every coordinate lies within the picture's size.
  const std::regex size_re("width=\"([0-9.]+)\" height=\"([0-9.]+)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, size_re));
  const double w = std::stod(m[1]), h = std::stod(m[2]);
  const std::regex point_re("(-?[0-9]+\\.[0-9]),(-?[0-9]+\\.[0-9]) ");
  int points = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), point_re);
       it != std::sregex_iterator(); ++it, ++points) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    ASSERT_GE(x, 0.0);
    ASSERT_LE(x, w);
    ASSERT_GE(y, 0.0);
    ASSERT_LE(y, h);
  }
  EXPECT_GT(points, 1000);
  // The edge labels of a panel do not overlap (the pencil dress's waist corners have edges of
  // 1.1–1.5 cm side by side): boxes of 7 px per character and 14 px high around each label's centre.
  const std::regex label_re("<text x=\"([0-9.]+)\" y=\"([0-9.]+)\" font-size=\"12\"[^>]*>([^<]*)</text>");
  int labels = 0, overlaps = 0;
  for (std::size_t open = svg.find("<g id="); open != std::string::npos; open = svg.find("<g id=", open + 1)) {
    const std::string group = svg.substr(open, svg.find("</g>", open) - open);
    // Only the text elements: the polylines' long point lists are no business of the regex.
    std::string texts;
    for (std::size_t t = group.find("<text"); t != std::string::npos; t = group.find("<text", t + 1))
      texts += group.substr(t, group.find("</text>", t) + 7 - t);
    std::vector<std::array<double, 4>> boxes;
    for (auto t = std::sregex_iterator(texts.begin(), texts.end(), label_re); t != std::sregex_iterator(); ++t) {
      const double x = std::stod((*t)[1]), y = std::stod((*t)[2]), half = 3.5 * double((*t)[3].length());
      const std::array<double, 4> box{x - half, x + half, y - 7.0, y + 7.0};
      for (const auto& b : boxes)
        overlaps += box[0] < b[1] && b[0] < box[1] && box[2] < b[3] && b[2] < box[3];
      boxes.push_back(box);
      ++labels;
    }
  }
  EXPECT_EQ(labels, edges);
  EXPECT_EQ(overlaps, 0);
}

}  // namespace
}  // namespace dresskit::pattern
