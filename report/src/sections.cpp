#include "sections.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace dresskit::report {

std::string report_number(double value, int digits) {
  if (!std::isfinite(value)) return "–";
  char text[64];
  const double size = std::abs(value);
  if (size != 0.0 && (size >= 1e7 || size < 1e-4))
    std::snprintf(text, sizeof text, "%.*e", std::max(0, digits - 1), value);
  else if (size >= std::pow(10.0, digits))
    std::snprintf(text, sizeof text, "%.0f", value);
  else
    std::snprintf(text, sizeof text, "%.*g", std::max(1, digits), value);
  return text;
}

namespace {
ReportSection section(ReportSection::Kind kind, std::string title, std::string text) {
  ReportSection s;
  s.kind = kind;
  s.title = std::move(title);
  s.text = std::move(text);
  return s;
}
}  // namespace

ReportSection ReportSection::table_of(std::string title, std::vector<std::string> columns,
                                      std::vector<std::vector<std::string>> rows,
                                      std::string note) {
  ReportSection s = section(Kind::table, std::move(title), std::move(note));
  s.columns = std::move(columns);
  s.rows = std::move(rows);
  return s;
}

ReportSection ReportSection::bars_of(std::string title, std::vector<std::string> labels,
                                     std::vector<double> values, std::string unit,
                                     std::string note) {
  ReportSection s = section(Kind::bars, std::move(title), std::move(note));
  s.labels = std::move(labels);
  s.values = std::move(values);
  s.unit = std::move(unit);
  return s;
}

ReportSection ReportSection::line_of(std::string title, std::vector<double> x,
                                     std::vector<double> y, std::string x_unit, std::string unit,
                                     std::string note) {
  ReportSection s = section(Kind::line, std::move(title), std::move(note));
  s.x = std::move(x);
  s.values = std::move(y);
  s.x_unit = std::move(x_unit);
  s.unit = std::move(unit);
  return s;
}

ReportSection ReportSection::text_of(std::string title, std::string text) {
  return section(Kind::text, std::move(title), std::move(text));
}

}  // namespace dresskit::report

namespace dresskit::report::detail {
namespace {

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b, c, d);
  return text;
}

/// A cell that is a number, possibly with a short unit after it ("0.5", "12 %", "3 mm"), is
/// right-aligned.
bool numeric(const std::string& cell) {
  if (cell.empty()) return false;
  char* end = nullptr;
  std::strtod(cell.c_str(), &end);
  if (end == cell.c_str()) return false;
  const std::string rest(end);
  return rest.empty() || rest == "%" ||
         (rest.size() <= 4 && rest[0] == ' ' && rest.find(' ', 1) == std::string::npos);
}

std::string table_html(const ReportSection& s) {
  std::string out = "<table>\n<thead><tr>";
  for (const std::string& c : s.columns) out += "<th>" + escape_html(c) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : s.rows) {
    out += "<tr>";
    for (const std::string& cell : row)
      out += (numeric(cell) ? "<td class=\"num\">" : "<td>") + escape_html(cell) + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

/// Horizontal bars, one per label, each with its value written after it.
std::string bars_html(const ReportSection& s) {
  const std::size_t n = std::min(s.labels.size(), s.values.size());
  double top = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(s.values[i])) top = std::max(top, s.values[i]);
  const double label_width = 150.0, bar_width = 380.0, row = 20.0;
  const double height = row * static_cast<double>(n) + 6.0;
  std::string out = "<svg class=\"bars\" width=\"" +
                    format("%.0f", label_width + bar_width + 90.0) + "\" height=\"" +
                    format("%.0f", height) + "\" role=\"img\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    const double v = std::isfinite(s.values[i]) ? std::max(0.0, s.values[i]) : 0.0;
    const double y = row * static_cast<double>(i) + 3.0;
    const double w = top > 0.0 ? bar_width * v / top : 0.0;
    out += "<text x=\"" + format("%.0f", label_width - 6.0) + "\" y=\"" + format("%.1f", y + 13.0) +
           "\" text-anchor=\"end\">" + escape_html(s.labels[i]) + "</text>";
    out += "<rect x=\"" + format("%.0f", label_width) + "\" y=\"" + format("%.1f", y + 2.0) +
           "\" width=\"" + format("%.1f", std::max(w, 0.5)) + "\" height=\"14\" fill=\"#4477aa\"/>";
    out += "<text x=\"" + format("%.1f", label_width + w + 5.0) + "\" y=\"" +
           format("%.1f", y + 13.0) + "\">" +
           escape_html(report_number(s.values[i]) + (s.unit.empty() ? "" : " " + s.unit)) +
           "</text>\n";
  }
  return out + "</svg>\n";
}

/// y over x with the ends of both axes labelled.
std::string line_html(const ReportSection& s) {
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < std::min(s.x.size(), s.values.size()); ++i)
    if (std::isfinite(s.x[i]) && std::isfinite(s.values[i]))
      points.emplace_back(s.x[i], s.values[i]);
  if (points.size() < 2) return "<p class=\"note\">Fewer than two points to plot.</p>\n";
  double x0 = points.front().first, x1 = x0, y0 = points.front().second, y1 = y0;
  for (const auto& [x, y] : points) {
    x0 = std::min(x0, x), x1 = std::max(x1, x);
    y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  if (x1 == x0) x1 = x0 + 1.0;
  if (y1 == y0) y1 = y0 + 1.0;
  const double left = 70.0, top = 10.0, width = 520.0, height = 180.0;
  std::string path;
  for (const auto& [x, y] : points) {
    path += format("%.1f,%.1f ", left + width * (x - x0) / (x1 - x0),
                   top + height * (1.0 - (y - y0) / (y1 - y0)));
  }
  std::string out = "<svg class=\"line\" width=\"" + format("%.0f", left + width + 20.0) +
                    "\" height=\"" + format("%.0f", top + height + 34.0) + "\" role=\"img\">\n";
  out += format(
      "<rect x=\"%.0f\" y=\"%.0f\" width=\"%.0f\" height=\"%.0f\" fill=\"none\" "
      "stroke=\"#ccd\"/>\n",
      left, top, width, height);
  out +=
      "<polyline fill=\"none\" stroke=\"#4477aa\" stroke-width=\"1.5\" points=\"" + path + "\"/>\n";
  const std::string yu = s.unit.empty() ? "" : " " + escape_html(s.unit);
  const std::string xu = s.x_unit.empty() ? "" : " " + escape_html(s.x_unit);
  out += format("<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"end\">", left - 4.0, top + 10.0) +
         escape_html(report_number(y1)) + yu + "</text>\n";
  out += format("<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"end\">", left - 4.0, top + height) +
         escape_html(report_number(y0)) + yu + "</text>\n";
  out += format("<text x=\"%.0f\" y=\"%.0f\">", left, top + height + 16.0) +
         escape_html(report_number(x0)) + xu + "</text>\n";
  out += format("<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"end\">", left + width,
                top + height + 16.0) +
         escape_html(report_number(x1)) + xu + "</text>\n";
  return out + "</svg>\n";
}

}  // namespace

std::string escape_html(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string section_html(const ReportSection& s) {
  std::string out = "<section>\n<h2>" + escape_html(s.title) + "</h2>\n";
  switch (s.kind) {
    case ReportSection::Kind::table:
      out += table_html(s);
      break;
    case ReportSection::Kind::bars:
      out += bars_html(s);
      break;
    case ReportSection::Kind::line:
      out += line_html(s);
      break;
    case ReportSection::Kind::text:
      return out + "<p>" + escape_html(s.text) + "</p>\n</section>\n";
  }
  if (!s.text.empty()) out += "<p class=\"note\">" + escape_html(s.text) + "</p>\n";
  return out + "</section>\n";
}

}  // namespace dresskit::report::detail
