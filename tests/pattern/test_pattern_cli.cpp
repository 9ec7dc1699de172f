// `dress-a-mesh pattern` end to end: outputs, and bad input as one line, exit 2, nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "dresskit/mesh/io.h"
#include "pattern_fixtures.h"
#include "tools/cli_run.h"

using namespace dresskit::mesh;

namespace dresskit {
namespace {
using namespace dresskit::test::cli;
namespace fs = std::filesystem;

TEST(PatternCli, WritesPictureMeshesAndSummary) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  const std::string out = dir.file("shirt");
  const CliRun r = run(dir, "pattern " + test::shared_pattern("gc_shirt_mean_specification.json") +
                                " -o " + out + " --edge 0.03 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["panels"].size(), 8u);
  EXPECT_EQ(j["stitches"], 18);
  for (const char* f : {"pattern.svg", "pattern.json", "gc_shirt_mean_specification.flat.obj",
                        "gc_shirt_mean_specification.placed.obj"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  const TriangleMesh placed = load_mesh(out + "/gc_shirt_mean_specification.placed.obj");
  EXPECT_EQ(placed.num_faces(), j["triangles"].get<int>());
  // The shirt placed around the body: between the hips and the shoulders of a 1.7 m body [m].
  const Eigen::AlignedBox3d box = bounding_box(placed);
  EXPECT_GT(box.min().y(), 0.6);
  EXPECT_LT(box.max().y(), 1.6);
  double area = 0.0;
  for (const auto& panel : j["panels"]) {
    area += panel["area_m2"].get<double>();
    EXPECT_NEAR(panel["triangle_area_m2"].get<double>(), panel["area_m2"].get<double>(),
                0.005 * panel["area_m2"].get<double>());
  }
  EXPECT_GT(area, 0.5);  // a short-sleeved shirt for an adult: 0.64 m² of fabric
  EXPECT_LT(area, 0.8);
  // The flat panels, each seen from the garment's outside: every face towards +z, of the panels'
  // triangles' area.
  const TriangleMesh flat = load_mesh(out + "/gc_shirt_mean_specification.flat.obj");
  double flat_area = 0.0;
  int backwards = 0;
  for (int f = 0; f < flat.num_faces(); ++f) {
    const Eigen::Vector3d a = flat.V.row(flat.F(f, 0)), b = flat.V.row(flat.F(f, 1)), c = flat.V.row(flat.F(f, 2));
    const double z = (b - a).cross(c - a).z();
    flat_area += 0.5 * z;
    backwards += z <= 0.0;
  }
  EXPECT_EQ(backwards, 0);
  double triangles = 0.0;
  for (const auto& panel : j["panels"]) triangles += panel["triangle_area_m2"].get<double>();
  EXPECT_NEAR(flat_area, triangles, 1e-6 * triangles);
}

TEST(PatternCli, BadPatternOneLineExit2NothingWritten) {
  test::TempDir dir;
  std::string text =
      test::two_panel_pattern("{\"endpoints\": [1, 2]}",
                              R"([[{"panel": "front", "edge": 1}, {"panel": "back", "edge": 9}]])");
  write(dir.file("bad.json"), text);
  const std::string out = dir.file("out");
  const CliRun r = run(dir, "pattern " + dir.file("bad.json") + " -o " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bad.json: stitch 0: panel 'back' has no edge 9"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
  // No units: named, exit 2.
  write(dir.file("nounits.json"), test::two_panel_pattern("{\"endpoints\": [1, 2]}", "[]",
                                                          R"({"curvature_coords": "relative"})"));
  const CliRun u = run(dir, "pattern " + dir.file("nounits.json") + " -o " + out);
  EXPECT_EQ(u.code, 2);
  EXPECT_NE(u.err.find("units_in_meter"), std::string::npos) << u.err;
  EXPECT_FALSE(fs::exists(out));
  // An edge length that is no length: named by the option, exit 2.
  for (const char* edge : {"-1", "0", "nan"}) {
    const CliRun e = run(dir, "pattern " + dir.file("bad.json") + " --edge " + edge + " -o " + out);
    EXPECT_EQ(e.code, 2) << edge;
    EXPECT_NE(e.err.find("--edge: "), std::string::npos) << e.err;
    EXPECT_NE(e.err.find("is not a positive length"), std::string::npos) << e.err;
  }
  EXPECT_FALSE(fs::exists(out));
  // The pattern given as the output folder: refused as dress refuses it, the file untouched.
  const auto size = fs::file_size(dir.file("nounits.json"));
  const CliRun same = run(dir, "pattern " + dir.file("nounits.json") + " -o " + dir.file("nounits.json"));
  EXPECT_EQ(same.code, 2);
  EXPECT_NE(same.err.find("nounits.json: the output folder is an input"), std::string::npos) << same.err;
  EXPECT_EQ(fs::file_size(dir.file("nounits.json")), size);
}

TEST(PatternCli, UnequalStitchWarnsAndStillCuts) {
  test::TempDir dir;
  write(
      dir.file("warn.json"),
      test::two_panel_pattern(
          R"({"endpoints": [1, 2], "curvature": {"type": "cubic", "params": [[0.3, 0.25], [0.7, 0.25]]}})"));
  const CliRun r = run(dir, "pattern " + dir.file("warn.json") + " -o " + dir.file("out"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("panel 'front' edge 1"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir.file("out") + "/pattern.svg"));
}

}  // namespace
}  // namespace dresskit
