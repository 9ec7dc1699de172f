// The pattern's picture: every panel and edge drawn, both sides of a stitch in the stitch's colour.
#include <gtest/gtest.h>

#include <regex>
#include <set>

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
}

}  // namespace
}  // namespace dresskit::pattern
