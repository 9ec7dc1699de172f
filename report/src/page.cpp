#include "dresskit/report/page.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/triangle_mesh.h"
#include "page_template.h"
#include "sections.h"

using namespace dresskit::mesh;

namespace dresskit::report {
using json = nlohmann::json;
namespace {

using detail::escape_html;

std::string base64(const void* data, std::size_t size) {
  static const char* const digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t v = (b[i] << 16) | (b[i + 1] << 8) | b[i + 2];
    for (int k = 18; k >= 0; k -= 6) out += digits[(v >> k) & 63];
  }
  if (i < size) {
    const std::uint32_t v = (b[i] << 16) | (i + 1 < size ? b[i + 1] << 8 : 0);
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < size ? digits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

/// Arrays as the page reads them: little-endian bytes of float32, uint32 or int16, in base64.
template <typename T, typename Source>
std::string typed_base64(const Source& values, std::size_t count) {
  std::vector<T> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i] = static_cast<T>(values(static_cast<Eigen::Index>(i)));
  static_assert(sizeof(float) == 4, "float32 expected");
  std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  if (first != 1) {  // a big-endian host: swap every value's bytes
    for (T& v : out) {
      unsigned char* p = reinterpret_cast<unsigned char*>(&v);
      for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(p[k], p[sizeof(T) - 1 - k]);
    }
  }
  return base64(out.data(), out.size() * sizeof(T));
}

std::string positions_base64(const Eigen::MatrixX3d& V) {
  const Eigen::Index n = V.rows();
  return typed_base64<float>([&](Eigen::Index i) { return V(i / 3, i % 3); },
                             static_cast<std::size_t>(3 * n));
}

void check_positions(const ReportMesh& m, const Eigen::MatrixX3d& V, Eigen::Index n,
                     const std::string& shape) {
  if (V.rows() != n)
    throw InputError("report page: mesh '" + m.name + "' shape '" + shape + "' has " +
                     std::to_string(V.rows()) + " vertices, its first " + std::to_string(n));
  if (!V.allFinite())
    throw InputError("report page: mesh '" + m.name + "' shape '" + shape + "' is not finite");
}

json mesh_json(const ReportMesh& m) {
  const Eigen::Index n = m.shapes.empty() ? m.V.rows() : m.shapes.front().V.rows();
  json shapes = json::object();
  std::string first;
  if (m.shapes.empty()) {
    check_positions(m, m.V, n, "");
    shapes[""] = positions_base64(m.V);
  } else {
    first = m.shapes.front().name;
    for (const ReportShape& s : m.shapes) {
      check_positions(m, s.V, n, s.name);
      shapes[s.name] = positions_base64(s.V);
    }
  }
  if (m.F.size() > 0 && (m.F.minCoeff() < 0 || m.F.maxCoeff() >= n))
    throw InputError("report page: mesh '" + m.name + "' has a face index out of range");
  if (m.labels.size() != 0 && m.labels.size() != n)
    throw InputError("report page: mesh '" + m.name + "' has " + std::to_string(m.labels.size()) +
                     " labels for " + std::to_string(n) + " vertices");
  json fields = json::array();
  for (const ReportField& f : m.fields) {
    if (f.values.size() != n)
      throw InputError("report page: field '" + f.name + "' of mesh '" + m.name + "' has " +
                       std::to_string(f.values.size()) + " values for " + std::to_string(n) +
                       " vertices");
    const bool known =
        m.shapes.empty() || std::any_of(m.shapes.begin(), m.shapes.end(),
                                        [&](const ReportShape& s) { return s.name == f.shape; });
    if (!known)
      throw InputError("report page: field '" + f.name + "' of mesh '" + m.name +
                       "' names no shape of it");
    const double low = std::isfinite(f.low) ? f.low : 0.0;
    const double high = std::isfinite(f.high) && f.high != low ? f.high : low + 1.0;
    const Eigen::VectorXd values =
        f.values.unaryExpr([low](double v) { return std::isfinite(v) ? v : low; });
    fields.push_back({{"name", f.name},
                      {"shape", m.shapes.empty() ? "" : f.shape},
                      {"unit", f.unit},
                      {"low", low},
                      {"high", high},
                      {"diverging", f.diverging},
                      {"values", typed_base64<float>(values, static_cast<std::size_t>(n))}});
  }
  const Eigen::MatrixX3i F = m.F;
  json out = {{"name", m.name},
              {"role", m.role},
              {"vertices", n},
              {"triangles", F.rows()},
              {"faces", typed_base64<std::uint32_t>([&](Eigen::Index i) { return F(i / 3, i % 3); },
                                                    static_cast<std::size_t>(3 * F.rows()))},
              {"first_shape", first},
              {"shapes", shapes},
              {"fields", fields}};
  if (m.labels.size() == n && n > 0) {
    out["labels"] = typed_base64<std::int16_t>(m.labels, static_cast<std::size_t>(n));
    out["label_names"] = m.label_names;
  } else {
    out["labels"] = nullptr;
    out["label_names"] = json::array();
  }
  return out;
}

/// The page's data: the meshes and the colours of parts (the palette of mesh/triangle_mesh.h's
/// label_colour, as every PLY and GLB of the toolkit colours them).
std::string data_json(const ReportPage& page) {
  json meshes = json::array();
  std::vector<std::string> shapes;
  std::set<std::string> names;
  for (const ReportMesh& m : page.meshes) {
    if (!names.insert(m.name).second)
      throw InputError("report page: two meshes named '" + m.name + "'");
    meshes.push_back(mesh_json(m));
    for (const ReportShape& s : m.shapes)
      if (std::find(shapes.begin(), shapes.end(), s.name) == shapes.end()) shapes.push_back(s.name);
  }
  json palette = json::array();
  for (int k = 0; k < 10; ++k) {
    const Eigen::Vector3i c = label_colour(k);
    palette.push_back({c(0), c(1), c(2)});
  }
  const Eigen::Vector3i grey = label_colour(-1);
  std::string shown = page.default_shape;
  if (std::find(shapes.begin(), shapes.end(), shown) == shapes.end())
    shown = shapes.empty() ? "" : shapes.front();
  const json data = {{"meshes", meshes},
                     {"shapes", shapes},
                     {"default_shape", shown},
                     {"palette", palette},
                     {"unlabelled", {grey(0), grey(1), grey(2)}}};
  // In a script element, "</script" would end it early and "<!--" change how it is read: every
  // "<" (only ever inside a JSON string here) is written as its escape.
  const std::string text = data.dump();
  std::string out;
  out.reserve(text.size());
  for (char c : text) out += c == '<' ? std::string("\\u003c") : std::string(1, c);
  return out;
}

std::string content_html(const ReportPage& page) {
  const bool failed = !page.failure.empty();
  std::string out = "<header>\n<h1>" + escape_html(page.title) + "<span class=\"status" +
                    (failed ? " failed\">failed" : "\">done") + "</span></h1>\n";
  if (!page.summary.empty()) out += "<p class=\"summary\">" + escape_html(page.summary) + "</p>\n";
  out += "</header>\n";
  if (failed)
    out += "<div class=\"failure\"><strong>What failed:</strong> " + escape_html(page.failure) +
           "</div>\n";
  if (!page.meshes.empty()) {
    out +=
        "<div id=\"view\"><noscript><p id=\"noview\">The 3D view needs JavaScript; the figures "
        "below are "
        "complete.</p></noscript></div>\n";
  }
  out += "<div id=\"errors\" hidden></div>\n<main>\n";
  if (!page.notes.empty()) {
    out += "<ul class=\"notes\">\n";
    for (const std::string& note : page.notes) out += "<li>" + escape_html(note) + "</li>\n";
    out += "</ul>\n";
  }
  for (const ReportSection& s : page.sections) out += detail::section_html(s);
  if (!page.report_json.empty()) {
    out +=
        "<section>\n<h2>report.json</h2>\n<details><summary>The run's report as "
        "JSON</summary><pre>" +
        escape_html(page.report_json) + "</pre></details>\n</section>\n";
  }
  out += "<p class=\"note\">Written by dresskit's " +
         escape_html(page.command.empty() ? "dress-a-mesh" : page.command) +
         "; everything on this page is in this one file.</p>\n</main>";
  return out;
}

/// Replaces the template's markers in the order they stand in it, each searched for after the text
/// put in for the one before, so that no text put in is taken for a marker.
std::string fill(const std::string& page,
                 const std::vector<std::pair<std::string, std::string>>& markers) {
  std::string out;
  std::size_t from = 0;
  for (const auto& [marker, with] : markers) {
    const std::size_t at = page.find(marker, from);
    if (at == std::string::npos)
      throw std::logic_error("report page: the template has no " + marker);
    out.append(page, from, at - from);
    out += with;
    from = at + marker.size();
  }
  out.append(page, from, std::string::npos);
  return out;
}

}  // namespace

std::string report_html(const ReportPage& page) {
  const std::string data = page.meshes.empty()
                               ? ""
                               : "<script type=\"application/json\" id=\"dresskit-data\">" +
                                     data_json(page) + "</script>";
  return fill(detail::page_template(), {{"<!--title-->", escape_html(page.title)},
                                               {"<!--content-->", content_html(page)},
                                               {"<!--data-->", data}});
}

void write_report_html(const std::string& path, const ReportPage& page) {
  write_file_atomically(path, report_html(page));
}

Eigen::VectorXd vertex_strain(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& rest,
                              const Eigen::MatrixX3i& F) {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(V.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      const double r = (rest.row(a) - rest.row(b)).norm();
      if (!(r > 0.0)) continue;
      const double e = (V.row(a) - V.row(b)).norm() / r - 1.0;
      s(a) = std::max(s(a), e), s(b) = std::max(s(b), e);
    }
  return s;
}

}  // namespace dresskit::report
