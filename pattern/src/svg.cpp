#include "dresskit/pattern/svg.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/curves.h"

namespace dresskit::pattern {
namespace {

// Label sizes [px]: a sans-serif character's width at font size 12 (edge labels) and 14 (panel
// names), and a line's height.
constexpr double kLabelCharWidth = 7.0, kNameCharWidth = 8.0, kLabelHeight = 14.0;

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string stitch_colour(int stitch) {
  // Hues around the colour wheel by the golden angle, so that consecutive stitches differ most.
  const double h = std::fmod(stitch * 137.50776405, 360.0) / 60.0;
  const double s = 0.85, v = stitch % 2 ? 0.62 : 0.85;
  const double c = v * s, x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (int(h)) {
    case 0:
      r = c, g = x;
      break;
    case 1:
      r = x, g = c;
      break;
    case 2:
      g = c, b = x;
      break;
    case 3:
      g = x, b = c;
      break;
    case 4:
      r = x, b = c;
      break;
    default:
      r = c, b = x;
      break;
  }
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", int(std::lround((r + m) * 255)),
                int(std::lround((g + m) * 255)), int(std::lround((b + m) * 255)));
  return text;
}

std::string pattern_svg(const Pattern& pattern, const SvgOptions& o) {
  // Each edge's stitch (−1: not stitched) and whether it is the stitch's second side.
  std::vector<std::vector<int>> stitch_of(pattern.panels.size());
  for (std::size_t p = 0; p < pattern.panels.size(); ++p)
    stitch_of[p].assign(pattern.panels[p].edges.size(), -1);
  for (std::size_t s = 0; s < pattern.stitches.size(); ++s) {
    stitch_of[pattern.stitches[s].a.panel][pattern.stitches[s].a.edge] = int(s);
    stitch_of[pattern.stitches[s].b.panel][pattern.stitches[s].b.edge] = int(s);
  }
  // Lay the panels out in rows by their bounding boxes.
  std::vector<Eigen::Vector2d> offset(pattern.panels.size());
  double x = o.gap, y = o.gap, row_height = 0.0, width = 0.0;
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    const Eigen::MatrixX2d outline = sample_outline(pattern.panels[p], o.sample_step);
    const Eigen::Vector2d lo = outline.colwise().minCoeff(), hi = outline.colwise().maxCoeff();
    const Eigen::Vector2d size = hi - lo;
    if (x > o.gap && x + size.x() > o.row_width) {
      x = o.gap;
      y += row_height + o.gap * 1.5;
      row_height = 0.0;
    }
    // Drawing coordinates: (u, v) with v downwards; panel point q goes to (x + q.x − lo.x, y + hi.y
    // − q.y).
    offset[p] = Eigen::Vector2d(x - lo.x(), y + hi.y());
    x += size.x() + o.gap;
    width = std::max(width, x);
    row_height = std::max(row_height, size.y());
  }
  const double height = y + row_height + o.gap * 1.5;
  const double k = o.pixels_per_metre;
  auto px = [&](std::size_t p, const Eigen::Vector2d& q) {
    return Eigen::Vector2d((offset[p].x() + q.x()) * k, (offset[p].y() - q.y()) * k);
  };
  std::ostringstream svg;
  svg.setf(std::ios::fixed);
  svg.precision(1);
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width * k << "\" height=\""
      << height * k << "\" viewBox=\"0 0 " << width * k << " " << height * k
      << "\" font-family=\"sans-serif\">\n";
  svg << "<title>" << escape(pattern.name) << ": " << pattern.panels.size() << " panels, "
      << pattern.stitches.size()
      << " stitches</title>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    const Panel& panel = pattern.panels[p];
    svg << "<g id=\"" << escape(panel.name) << "\">\n";
    const Eigen::MatrixX2d outline = sample_outline(panel, o.sample_step);
    svg << "<polygon fill=\"#f4f1ea\" stroke=\"none\" points=\"";
    for (Eigen::Index i = 0; i < outline.rows(); ++i) {
      const Eigen::Vector2d q = px(p, outline.row(i).transpose());
      svg << q.x() << "," << q.y() << " ";
    }
    svg << "\"/>\n";
    const double area = polygon_area(outline);
    // The labels' boxes so far [px], the panel's name at its centre first: an edge label goes
    // where it overlaps none of them.
    const Eigen::Vector2d centre = px(p, outline.colwise().mean().transpose());
    const Eigen::Vector2d name_half(0.5 * kNameCharWidth * double(panel.name.size()), 0.5 * kLabelHeight);
    std::vector<Eigen::AlignedBox2d> labels{{centre - name_half, centre + name_half}};
    for (std::size_t e = 0; e < panel.edges.size(); ++e) {
      const int s = stitch_of[p][e];
      const std::string colour = s >= 0 ? stitch_colour(s) : "#222222";
      const double length = edge_length(panel, int(e));
      const int n = std::max(1, int(std::ceil(length / o.sample_step)));
      const Eigen::MatrixX2d pts = sample_edge(panel, int(e), n);
      svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\""
          << (s >= 0 ? 3.5 : 1.5) << "\" points=\"";
      for (Eigen::Index i = 0; i < pts.rows(); ++i) {
        const Eigen::Vector2d q = px(p, pts.row(i).transpose());
        svg << q.x() << "," << q.y() << " ";
      }
      svg << "\"><title>" << escape(pattern.edge_name(int(p), int(e)));
      if (s >= 0) svg << ", stitch " << s;
      svg << "</title></polyline>\n";
      // The edge's number inside the panel beside its middle (where short edges crowd, further in
      // or further along the edge, so that labels do not overlap); a stitched edge's number also
      // names its stitch, and a dot marks the edge's start.
      const std::string label = std::to_string(e) + (s >= 0 ? " (s" + std::to_string(s) + ")" : "");
      const Eigen::Vector2d half(0.5 * kLabelCharWidth * double(label.size()) + 2.0, 0.5 * kLabelHeight);
      auto inward_at = [&](double along) {
        const Eigen::Vector2d a = edge_point(panel, int(e), along - 0.01),
                              b = edge_point(panel, int(e), along + 0.01);
        Eigen::Vector2d n(-(b - a).y(), (b - a).x());
        return Eigen::Vector2d(n * (area >= 0 ? 1.0 : -1.0) / std::max(n.norm(), 1e-12));
      };
      Eigen::Vector2d t = px(p, edge_point(panel, int(e), 0.5) + 0.025 * inward_at(0.5));
      bool placed = false;
      for (int depth = 0; depth < 10 && !placed; ++depth)
        for (const double along : {0.5, 0.3, 0.7, 0.15, 0.85}) {
          const Eigen::Vector2d q =
              px(p, edge_point(panel, int(e), along) + (0.025 + 0.03 * depth) * inward_at(along));
          const Eigen::AlignedBox2d box(q - half, q + half);
          if (std::none_of(labels.begin(), labels.end(),
                           [&](const Eigen::AlignedBox2d& l) { return l.intersects(box); })) {
            t = q, placed = true;
            break;
          }
        }
      labels.emplace_back(t - half, t + half);
      svg << "<text x=\"" << t.x() << "\" y=\"" << t.y()
          << "\" font-size=\"12\" text-anchor=\"middle\" "
          << "dominant-baseline=\"middle\" fill=\"" << colour << "\">" << label << "</text>\n";
      if (s >= 0) {
        const Eigen::Vector2d start = px(p, edge_point(panel, int(e), 0.0) + 0.012 * inward_at(0.5));
        svg << "<circle cx=\"" << start.x() << "\" cy=\"" << start.y() << "\" r=\"3\" fill=\""
            << colour << "\"/>\n";
      }
    }
    svg << "<text x=\"" << centre.x() << "\" y=\"" << centre.y()
        << "\" font-size=\"14\" text-anchor=\"middle\" fill=\"#555\">" << escape(panel.name)
        << "</text>\n</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

void write_pattern_svg(const std::string& path, const Pattern& pattern, const SvgOptions& options) {
  const std::string text = pattern_svg(pattern, options);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw OutputError(path + ": cannot be written");
  out << text;
  if (!out.flush()) throw OutputError(path + ": cannot be written");
}

}  // namespace dresskit::pattern
