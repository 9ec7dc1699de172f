// report.html as text: self-contained (three.js and the viewer inside, nothing fetched), the meshes
// decoded back exactly as float32, text escaped, no NaN, bad meshes refused, and the size of a
// 50k-triangle scene.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>

#include "dresskit/mesh/errors.h"
#include "dresskit/report/page.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::report;
using json = nlohmann::json;

namespace {

std::vector<unsigned char> unbase64(const std::string& text) {
  std::vector<unsigned char> out;
  int bits = 0;
  std::uint32_t value = 0;  // unsigned: the bits shifted out of its top wrap away
  for (char c : text) {
    const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = std::strchr(digits, c);
    if (c == '=' || !at) break;
    value = (value << 6) | static_cast<std::uint32_t>(at - digits);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((value >> bits) & 0xff));
    }
  }
  return out;
}

template <typename T>
std::vector<T> decode(const std::string& text) {
  const std::vector<unsigned char> bytes = unbase64(text);
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

/// The page's embedded data, as the viewer reads it.
json page_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"dresskit-data\">";
  const std::size_t a = html.find(open);
  const std::size_t b = html.find("</script>", a);
  if (a == std::string::npos || b == std::string::npos) return json();
  return json::parse(html.substr(a + open.size(), b - a - open.size()));
}

/// A grid of n × n vertices in the XY plane, two triangles per cell.
ReportMesh grid(const std::string& name, int n, double size) {
  ReportMesh m;
  m.name = name;
  m.role = "garment";
  m.V.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      m.V.row(i * n + j) << size * j / (n - 1), size * i / (n - 1), 0.1 * std::sin(i + j);
  m.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j;
      m.F.row(f++) << a, a + 1, a + n;
      m.F.row(f++) << a + 1, a + n + 1, a + n;
    }
  return m;
}

}  // namespace

TEST(ReportPage, HoldsThreeJsTheViewerAndTheMeshesExactly) {
  ReportPage page;
  page.title = "dress: body in <shirt> & \"trousers\"";
  page.command = "dress";
  ReportMesh body = grid("body", 5, 1.0);
  body.role = "body";
  body.labels = Eigen::VectorXi::LinSpaced(25, -1, 23).unaryExpr([](int v) { return v % 3; });
  body.label_names = {"torso", "arm_left", "arm_right"};
  ReportMesh shirt = grid("shirt</script><!--", 4, 0.5);
  Eigen::MatrixX3d dressed = shirt.V;
  dressed.col(2).array() += 0.01;
  shirt.shapes = {{"placed", shirt.V}, {"dressed", dressed}};
  Eigen::VectorXd strain = Eigen::VectorXd::LinSpaced(16, 0.0, 0.15);
  strain(3) = std::nan("");
  shirt.fields.push_back({"strain", "dressed", "", strain, 0.0, 0.1, false});
  page.meshes = {body, shirt};
  page.default_shape = "dressed";
  page.sections.push_back(
      ReportSection::table_of("Stages", {"stage", "seconds"}, {{"load", "0.5"}, {"<b>", "1"}}));
  page.sections.push_back(
      ReportSection::bars_of("Time per stage", {"load", "settle"}, {0.5, 2.0}, "s"));
  page.sections.push_back(
      ReportSection::line_of("Energy", {0, 1, 2}, {3, 1, std::nan("")}, "s", "J"));
  page.report_json = "{\"note\": \"</script>\"}";
  const std::string html = report_html(page);

  // Self-contained: three.js, the orbit controls and the viewer are in the page; nothing is
  // fetched or linked from elsewhere.
  EXPECT_NE(html.find("OrbitControls"), std::string::npos);
  EXPECT_NE(html.find("WebGLRenderer"), std::string::npos);
  EXPECT_NE(html.find("dresskit-data"), std::string::npos);
  for (const char* outside : {"<script src", "<link ", "<img ", "<iframe"})
    EXPECT_EQ(html.find(outside), std::string::npos) << outside;
  // Text is escaped; only the template's own script elements end.
  EXPECT_NE(html.find("dress: body in &lt;shirt&gt; &amp; &quot;trousers&quot;"),
            std::string::npos);
  EXPECT_EQ(html.find("<shirt>"), std::string::npos);
  EXPECT_EQ(html.find("<b>"), std::string::npos);
  EXPECT_EQ(html.find("shirt</script>"), std::string::npos);
  // No NaN in what the page was given: its content and its data (three.js, after them, has isNaN).
  const std::string ours =
      html.substr(0, html.find("</script>", html.find("id=\"dresskit-data\"")));
  EXPECT_EQ(ours.find("NaN"), std::string::npos);
  EXPECT_EQ(ours.find("nan"), std::string::npos);

  const json data = page_data(html);
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["default_shape"], "dressed");
  EXPECT_EQ(data["shapes"], json({"placed", "dressed"}));
  ASSERT_EQ(data["meshes"].size(), 2u);
  const json& b = data["meshes"][0];
  EXPECT_EQ(b["name"], "body");
  EXPECT_EQ(b["vertices"], 25);
  const std::vector<float> V = decode<float>(b["shapes"][""]);
  ASSERT_EQ(V.size(), 75u);
  for (int i = 0; i < 25; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(V[3 * i + k], static_cast<float>(body.V(i, k)));
  const std::vector<std::uint32_t> F = decode<std::uint32_t>(b["faces"]);
  ASSERT_EQ(F.size(), 3u * body.F.rows());
  for (int f = 0; f < body.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(F[3 * f + k], static_cast<std::uint32_t>(body.F(f, k)));
  const std::vector<std::int16_t> labels = decode<std::int16_t>(b["labels"]);
  ASSERT_EQ(labels.size(), 25u);
  for (int i = 0; i < 25; ++i) EXPECT_EQ(labels[i], body.labels(i));
  EXPECT_EQ(data["palette"].size(), 10u);

  const json& s = data["meshes"][1];
  EXPECT_EQ(s["name"], "shirt</script><!--");  // escaped in the page, itself once parsed
  EXPECT_EQ(s["first_shape"], "placed");
  const std::vector<float> D = decode<float>(s["shapes"]["dressed"]);
  EXPECT_EQ(D[2], static_cast<float>(dressed(0, 2)));
  const std::vector<float> values = decode<float>(s["fields"][0]["values"]);
  ASSERT_EQ(values.size(), 16u);
  EXPECT_EQ(values[3], 0.0f);  // a non-finite value is drawn as the lowest
  for (float v : values) EXPECT_TRUE(std::isfinite(v));
}

TEST(ReportPage, AFailedRunSaysWhatFailedWithoutAView) {
  ReportPage page;
  page.title = "simulate: drop";
  page.failure = "blow-up at t = 0.08 s";
  page.sections.push_back(ReportSection::text_of("Why", "a stiff fabric at a long step"));
  const std::string html = report_html(page);
  EXPECT_NE(html.find("What failed:</strong> blow-up at t = 0.08 s"), std::string::npos);
  EXPECT_NE(html.find("status failed"), std::string::npos);
  EXPECT_EQ(html.find("id=\"view\""), std::string::npos);
  EXPECT_EQ(html.find("id=\"dresskit-data\""), std::string::npos);
  EXPECT_EQ(report_number(std::nan("")), "–");
  EXPECT_EQ(report_number(0.000012345), "1.23e-05");
  EXPECT_EQ(report_number(12345.6), "12346");
  EXPECT_EQ(report_number(0.5), "0.5");
}

TEST(ReportPage, RefusesMeshesWhoseArraysDisagree) {
  ReportPage page;
  ReportMesh m = grid("cloth", 3, 1.0);
  page.meshes = {m};
  EXPECT_NO_THROW(report_html(page));
  ReportMesh bad = m;
  bad.F(0, 0) = 9;
  page.meshes = {bad};
  EXPECT_THROW(report_html(page), InputError);
  bad = m;
  bad.V(4, 1) = std::nan("");
  page.meshes = {bad};
  EXPECT_THROW(report_html(page), InputError);
  bad = m;
  bad.fields.push_back({"strain", "", "", Eigen::VectorXd::Zero(4), 0.0, 1.0, false});
  page.meshes = {bad};
  EXPECT_THROW(report_html(page), InputError);
  bad = m;
  bad.shapes = {{"start", m.V}, {"end", m.V.topRows(5)}};
  page.meshes = {bad};
  EXPECT_THROW(report_html(page), InputError);
  page.meshes = {m, m};
  EXPECT_THROW(report_html(page), InputError);
  test::TempDir dir;
  page.meshes = {m};
  EXPECT_THROW(write_report_html(dir.file("missing/report.html"), page), OutputError);
}

// The size of a 50k-triangle scene (a body of 25k triangles and a garment of 25k in two shapes,
// each with two colour maps and parts): under 20 MB.
TEST(ReportPage, AFiftyThousandTriangleSceneStaysUnderTwentyMegabytes) {
  ReportPage page;
  ReportMesh body = grid("body", 113, 1.7);  // 2 × 112² = 25088 triangles
  body.role = "body";
  body.labels = Eigen::VectorXi::Zero(body.V.rows());
  body.label_names = {"torso"};
  ReportMesh garment = grid("garment", 113, 1.0);
  Eigen::MatrixX3d dressed = garment.V.array() + 0.01;
  garment.shapes = {{"placed", garment.V}, {"dressed", dressed}};
  garment.labels = Eigen::VectorXi::Zero(garment.V.rows());
  garment.label_names = {"body"};
  for (const char* shape : {"placed", "dressed"}) {
    garment.fields.push_back({"distance to the body", shape, "mm",
                              Eigen::VectorXd::Random(garment.V.rows()), -5, 20, true});
    garment.fields.push_back(
        {"strain", shape, "", Eigen::VectorXd::Random(garment.V.rows()), 0, 0.1, false});
  }
  page.meshes = {body, garment};
  const auto start = std::chrono::steady_clock::now();
  const std::string html = report_html(page);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int triangles = static_cast<int>(body.F.rows() + garment.F.rows());
  std::cout << "page of " << triangles << " triangles: " << html.size() / 1e6 << " MB, made in "
            << seconds << " s\n";
  EXPECT_GE(triangles, 50000);
  EXPECT_LT(html.size(), 20e6);
}
