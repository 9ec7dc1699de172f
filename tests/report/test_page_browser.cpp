// report.html in a browser: the demo's page, a segmentation's, a failed simulation's and a failed
// dressing's are opened in headless Chromium (software WebGL). Each must load with no script error
// (counted by the page and read from the console log); the demo's must show a shaded 3D view (many
// distinct colours over a large part of the view in a screenshot) and draw its first frame within
// 2 s of navigation. Skipped, with the reason, when no Chromium is installed.
#include <gtest/gtest.h>

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>

#include "dresskit/dressing/outputs.h"
#include "dresskit/mesh/io.h"
#include "mannequin/mannequin_fixture.h"
#include "report/browser.h"
#include "test_data.h"
#include "tools/cli_run.h"

using namespace dresskit;
using namespace dresskit::dressing;
using namespace dresskit::mesh;
namespace browser = dresskit::test::browser;

namespace {

#define DRESSKIT_REQUIRE_CHROMIUM(chromium)                                                        \
  const std::string chromium = browser::find_chromium();                                           \
  if (chromium.empty())                                                                            \
  GTEST_SKIP() << "no Chromium found (chromium, chromium-browser or google-chrome on PATH, or "    \
                  "DRESSKIT_CHROMIUM): install Debian's chromium (scripts/install-deps) to check " \
                  "report.html "                                                                   \
                  "in a browser"

/// Loads the page and checks that it rendered with no script error.
browser::Load load_without_errors(const std::string& chromium, const std::string& page,
                                  const test::TempDir& dir, const std::string& rendered = "yes") {
  const browser::Load r = browser::load(chromium, page, dir.path().string());
  EXPECT_EQ(r.code, 0) << "chromium --dump-dom " << page << " (124: timed out)\n" << r.log;
  EXPECT_EQ(r.rendered, rendered) << r.log;
  EXPECT_EQ(r.errors, 0) << r.dom.substr(0, 2000);
  for (const std::string& line : r.console_errors) ADD_FAILURE() << "console: " << line;
  return r;
}

// The page has a section of each title.
void expect_sections(const std::string& dom, const std::vector<std::string>& titles) {
  for (const std::string& t : titles) EXPECT_NE(dom.find("<h2>" + t + "</h2>"), std::string::npos) << t;
}

}  // namespace

TEST(ReportBrowser, TheDemosPageShowsTheDressedMannequinShadedWithNoScriptError) {
  DRESSKIT_REQUIRE_CHROMIUM(chromium);
  test::TempDir dir;
  const test::cli::CliRun run = test::cli::run(dir, "demo -o " + dir.file("demo"));
  ASSERT_EQ(run.code, 0) << run.err;
  const std::string page = dir.file("demo/report.html");
  ASSERT_TRUE(std::filesystem::exists(page));
  const double megabytes = static_cast<double>(std::filesystem::file_size(page)) / 1e6;

  const browser::Load load = load_without_errors(chromium, page, dir);
  EXPECT_NE(load.dom.find("demo: mannequin in trousers, tshirt"), std::string::npos);
  expect_sections(load.dom, {"Stages", "Time per stage", "Layer gaps", "Elastic energy over the settle",
                             "Largest strain over the settle"});
  for (const char* toggle :
       {">mannequin<", ">trousers<", ">tshirt<", ">parts<", ">distance to the body<", ">strain<"})
    EXPECT_NE(load.dom.find(toggle), std::string::npos) << toggle;
  EXPECT_GT(load.load_ms, 0.0);
  EXPECT_LT(load.load_ms, 2000.0) << "first frame drawn this long after navigation";
  std::cout << "demo report.html: " << megabytes << " MB, first frame " << load.load_ms
            << " ms after navigation\n";

  const std::string png = dir.file("demo.png");
  ASSERT_EQ(browser::screenshot(chromium, page, png, dir.path().string()), 0)
      << browser::slurp(dir.file("shot.log"));
  const browser::Image image = browser::read_png(png);
  ASSERT_EQ(image.width, 1280);
  ASSERT_GE(image.height, 700);
  // The 3D view, right of the panel and below the heading: a shaded mannequin and garments.
  const browser::Colours view = browser::colours(image, 300, 90, image.width, 600);
  std::cout << "screenshot: " << view.distinct << " distinct colours, " << 100.0 * view.covered
            << " % of the view not background\n";
  EXPECT_GE(view.distinct, 500);
  EXPECT_GE(view.covered, 0.08);
}

TEST(ReportBrowser, ASegmentationsPageShowsItsPartsWithNoScriptError) {
  DRESSKIT_REQUIRE_CHROMIUM(chromium);
  test::TempDir dir;
  save_mesh(test::DefaultScene::get().mannequin, dir.file("mannequin.obj"));
  const test::cli::CliRun run =
      test::cli::run(dir, "segment " + dir.file("mannequin.obj") + " -o " + dir.file("seg"));
  ASSERT_EQ(run.code, 0) << run.err;
  const browser::Load load = load_without_errors(chromium, dir.file("seg/report.html"), dir);
  expect_sections(load.dom, {"Parts", "Spectrum"});
}

// A simulation that blows up: its page says what failed and shows the cloth at the last good state.
TEST(ReportBrowser, AFailedSimulationsPageSaysWhatFailedAndShowsTheLastGoodState) {
  DRESSKIT_REQUIRE_CHROMIUM(chromium);
  test::TempDir dir;
  test::cli::write(dir.file("stiff.json"),
                   R"({"cloth": {"grid": {"size": [0.5, 0.5], "resolution": [8, 8]},
    "fabric": "11oz-black-denim", "pins": [[0, 7], [7, 7]]},
    "colliders": [{"type": "sphere", "center": [0, -0.4, 0], "radius": 0.2}],
    "simulation": {"integrator": "symplectic", "dt": 0.04, "adaptive": false, "strain_limiting": false,
                   "duration": 1.0}})");
  const test::cli::CliRun run =
      test::cli::run(dir, "simulate " + dir.file("stiff.json") + " -o " + dir.file("out"));
  ASSERT_EQ(run.code, 4) << run.err;
  const browser::Load load = load_without_errors(chromium, dir.file("out/report.html"), dir);
  EXPECT_NE(load.dom.find("What failed:"), std::string::npos);
  EXPECT_NE(load.dom.find("blow-up"), std::string::npos);
  EXPECT_NE(load.dom.find(">last good state<"), std::string::npos);
  expect_sections(load.dom, {"Elastic energy over time"});
}

// Dressing whose settling failed: the page alone, saying so, with the garments placed and where
// settling stopped (the failure is made here: a settle that blows up on purpose is not at hand).
TEST(ReportBrowser, AFailedDressingsPageSaysWhatFailedAndShowsTheLastGoodState) {
  DRESSKIT_REQUIRE_CHROMIUM(chromium);
  const test::DefaultScene& scene = test::DefaultScene::get();
  DressOptions options;
  options.settle_seconds = 0.05;
  const std::size_t trousers = 2;  // all_garment_kinds(): tshirt, skirt, trousers
  DressResult r =
      dress(MeshFile::given("mannequin", scene.mannequin),
            {{MeshFile::given("trousers", scene.garments[trousers]), "11oz-black-denim"}}, options);
  ASSERT_TRUE(r.settled);
  r.settle.ok = false;
  r.settle.failure = "non-finite position of particle 12 at t = 0.05 s";
  r.settle.stopped_reason = "failed: " + r.settle.failure;
  test::TempDir dir;
  write_dress_failure_page(dir.path().string(), r);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
  const browser::Load load = load_without_errors(chromium, dir.file("report.html"), dir);
  EXPECT_NE(load.dom.find("What failed:</strong> settling stopped after"), std::string::npos);
  EXPECT_NE(load.dom.find("non-finite position of particle 12"), std::string::npos);
  EXPECT_NE(load.dom.find(">last good state<"), std::string::npos);
  EXPECT_NE(load.dom.find(">placed<"), std::string::npos);
}
