// Cutting panels into triangles: matching stitch points, areas, orientation, placement in 3D.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "dresskit/pattern/curves.h"
#include "dresskit/pattern/cut.h"
#include "pattern_fixtures.h"

using namespace dresskit::pattern;

namespace dresskit::pattern {
namespace {

double area2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

TEST(PatternCut, SharedPatternsStitchesMatchAndAreasHold) {
  DRESSKIT_REQUIRE_DATA();
  for (const std::string& file : test::shared_patterns()) {
    const Pattern p = read_pattern(test::shared_pattern(file));
    CutOptions o;
    o.edge_length = 0.02;
    const CutPattern cut = cut_pattern(p, o);
    // Both edges of every stitch have the same number of points, each point on its curve at equal
    // steps of arc length, and the pairs join start to end.
    for (std::size_t s = 0; s < p.stitches.size(); ++s) {
      const Stitch& st = p.stitches[s];
      const auto& a = cut.edge_vertices[st.a.panel][st.a.edge];
      const auto& b = cut.edge_vertices[st.b.panel][st.b.edge];
      ASSERT_EQ(a.size(), b.size()) << file << " stitch " << s;
      EXPECT_GE(a.size(), 2u);
      for (const auto* side : {&st.a, &st.b}) {
        const auto& vs = cut.edge_vertices[side->panel][side->edge];
        const Eigen::MatrixX2d expect =
            sample_edge(p.panels[side->panel], side->edge, int(vs.size()) - 1);
        for (std::size_t i = 0; i < vs.size(); ++i)
          EXPECT_NEAR((cut.flat.row(vs[i]) - expect.row(i)).norm(), 0.0, 1e-12)
              << file << " " << p.edge_name(side->panel, side->edge);
        // Pieces no longer than the edge length (the finer of two stitched edges sets the count).
        const double length = edge_length(p.panels[side->panel], side->edge);
        EXPECT_LE(length / double(vs.size() - 1), o.edge_length * (1 + 1e-9))
            << p.edge_name(side->panel, side->edge);
      }
    }
    int pairs_expected = 0;
    for (const Stitch& st : p.stitches) {
      const auto& a = cut.edge_vertices[st.a.panel][st.a.edge];
      const auto& b = cut.edge_vertices[st.b.panel][st.b.edge];
      for (std::size_t i = 0; i < a.size(); ++i) pairs_expected += a[i] != b[a.size() - 1 - i];
    }
    EXPECT_EQ(int(cut.stitch_pairs.size()), pairs_expected) << file;
    for (std::size_t k = 0; k < cut.stitch_pairs.size(); ++k) {
      const Stitch& st = p.stitches[cut.stitch_of_pair[k]];
      EXPECT_EQ(cut.panel_of_vertex[cut.stitch_pairs[k][0]], st.a.panel);
      EXPECT_EQ(cut.panel_of_vertex[cut.stitch_pairs[k][1]], st.b.panel);
    }
    for (int i = 0; i < int(p.panels.size()); ++i) {
      // The triangles cover the panel: their area is the curves' enclosed area within 0.5 % (the
      // outline's chords cut off a little of every curve).
      EXPECT_NEAR(cut.triangle_area[i], cut.outline_area[i], 0.005 * cut.outline_area[i])
          << file << " " << p.panels[i].name;
      // The same area recomputed from the triangles placed in 3D: placing is a rigid motion.
      double placed = 0.0, flat_signed = 0.0;
      int faces = 0, vertices = 0;
      std::map<std::pair<int, int>, int> edge_use;
      for (Eigen::Index f = 0; f < cut.faces.rows(); ++f) {
        if (cut.panel_of_face[f] != i) continue;
        ++faces;
        const Eigen::Vector3d a = cut.placed.row(cut.faces(f, 0)),
                              b = cut.placed.row(cut.faces(f, 1)),
                              c = cut.placed.row(cut.faces(f, 2));
        placed += 0.5 * (b - a).cross(c - a).norm();
        const double s = area2(cut.flat.row(cut.faces(f, 0)), cut.flat.row(cut.faces(f, 1)),
                               cut.flat.row(cut.faces(f, 2)));
        // Every face turns as the panel's outline turns.
        EXPECT_GT(s * polygon_area(sample_outline(p.panels[i], 0.01)), 0.0) << p.panels[i].name;
        flat_signed += s;
        for (int k = 0; k < 3; ++k) {
          const int u = cut.faces(f, k), v = cut.faces(f, (k + 1) % 3);
          ++edge_use[{std::min(u, v), std::max(u, v)}];
          // No triangle edge much longer than asked (CGAL's size bound is on the circumradius).
          EXPECT_LT((cut.flat.row(u) - cut.flat.row(v)).norm(), 2.0 * o.edge_length);
        }
      }
      for (Eigen::Index v = 0; v < cut.flat.rows(); ++v) vertices += cut.panel_of_vertex[v] == i;
      EXPECT_NEAR(placed, cut.triangle_area[i], 1e-9) << p.panels[i].name;
      EXPECT_NEAR(std::abs(flat_signed), cut.triangle_area[i], 1e-9) << p.panels[i].name;
      // A disc: V − E + F = 1, every edge used once (outline) or twice (inside), and the outline's
      // edges are exactly the resampled outline.
      int boundary = 0;
      for (const auto& [e, n] : edge_use) {
        EXPECT_LE(n, 2);
        boundary += n == 1;
      }
      int outline_points = 0;
      for (const auto& vs : cut.edge_vertices[i]) outline_points += int(vs.size()) - 1;
      EXPECT_EQ(boundary, outline_points) << p.panels[i].name;
      EXPECT_EQ(vertices - int(edge_use.size()) + faces, 1) << p.panels[i].name;
    }
  }
}

TEST(PatternCut, EdgeLengthSetsTheResolution) {
  const Pattern p = parse_pattern(test::two_panel_pattern(), "two.json");
  CutOptions coarse, fine;
  coarse.edge_length = 0.04;
  fine.edge_length = 0.01;
  const CutPattern a = cut_pattern(p, coarse), b = cut_pattern(p, fine);
  // 0.4 × 0.6 m: the 60 cm sides in 15 and 60 pieces.
  EXPECT_EQ(a.edge_vertices[0][1].size(), 16u);
  EXPECT_EQ(b.edge_vertices[0][1].size(), 61u);
  // Triangles scale as 1 / h²: 16 times as many within a quarter.
  const double ratio = double(b.faces.rows()) / double(a.faces.rows());
  EXPECT_GT(ratio, 12.0);
  EXPECT_LT(ratio, 20.0);
  for (const CutPattern* c : {&a, &b}) {
    EXPECT_NEAR(c->triangle_area[0], 0.24, 1e-12);  // straight outline: exact
    EXPECT_NEAR(c->triangle_area[1], 0.24, 1e-12);
  }
  // The back is turned half a turn about y at x = +0.2: its corner (0, 0) is at (0.2, 0.8, −0.15).
  const int corner = b.edge_vertices[1][0][0];
  EXPECT_NEAR((b.placed.row(corner) - Eigen::RowVector3d(0.2, 0.8, -0.15)).norm(), 0.0, 1e-12);
}

TEST(PatternCut, StitchedEdgesOfDifferentLengthsShareOneCount) {
  // Front edge 1 curved (longer) is sewn to the straight back edge 3: both get the curve's count.
  const Pattern p = parse_pattern(
      test::two_panel_pattern(
          R"({"endpoints": [1, 2], "curvature": {"type": "quadratic", "params": [[0.5, 0.3]]}})"),
      "curved.json", ReadOptions{2.0, 1e-5});
  const auto counts = edge_piece_counts(p, 0.02);
  const int curved = int(std::ceil(edge_length(p.panels[0], 1) / 0.02));
  EXPECT_GT(curved, 30);
  EXPECT_EQ(counts[0][1], curved);
  EXPECT_EQ(counts[1][3], curved);
  EXPECT_EQ(counts[1][1], 30);  // the other seam: two straight 60 cm edges
}

}  // namespace
}  // namespace dresskit::pattern
