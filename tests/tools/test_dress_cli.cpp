// dress-a-mesh dress end to end: the outputs and the report of a run with only the meshes and their
// units, and bad input (exit 2, one error line naming the file or option; nothing written, or
// report.html alone where a stage refused).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dresskit/mesh/io.h"
#include "test_data.h"
#include "tools/cli_run.h"

using namespace dresskit;
using namespace dresskit::mesh;
using namespace dresskit::test::cli;

namespace {
std::string data(const std::string& path) { return test::data_dir() + "/" + path; }
int error_lines(const std::string& err) {
  int n = 0;
  for (std::size_t at = err.find("dress-a-mesh: "); at != std::string::npos; at = err.find("dress-a-mesh: ", at + 1)) ++n;
  return n;
}
const std::string kChild = "bodies/mh_girl_child_11y.obj", kOutfit = "garments/mh_female_casualsuit01.obj";
}  // namespace

TEST(DressCli, WritesTheDressedOutfitAndAReportOfEveryStage) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  const CliRun r = run(dir, "dress " + data(kChild) + " " + data(kOutfit) + " --units dm --quality fast --json -o " +
                                dir.file("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto report = nlohmann::json::parse(r.out);  // stdout holds the report and nothing else
  EXPECT_EQ(report, nlohmann::json::parse(slurp(dir.file("out/report.json"))));
  std::vector<std::string> names;
  for (const auto& s : report["stages"]) {
    names.push_back(s["name"]);
    EXPECT_FALSE(s["reason"].get<std::string>().empty()) << s["name"];
    EXPECT_GE(s["seconds"].get<double>(), 0.0);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"load", "clean", "units", "segmentation", "wearer", "layers", "placement",
                                             "thickness", "grading", "settle", "padding", "write"}));
  const auto& g = report["garments"][0];
  EXPECT_EQ(g["vertices_inside_body_2mm"]["dressed"], 0);
  EXPECT_LE(g["crossings"]["dressed"].get<int>(), g["crossings"]["authored"].get<int>());
  // The dressed garment in the file's own vertex order and units (dm): as many vertices as the
  // file, on the child (1.27 m tall, feet at about -6.7 dm in MakeHuman's frame).
  LoadOptions dm;
  dm.units = Units::parse("dm");
  const TriangleMesh source = load_mesh(data(kOutfit), dm);
  const TriangleMesh dressed = load_mesh(dir.file("out/mh_female_casualsuit01.dressed.obj"), dm);
  ASSERT_EQ(dressed.num_vertices(), source.num_vertices());
  EXPECT_TRUE(dressed.V.allFinite());
  EXPECT_LT(dressed.V.col(1).maxCoeff() - dressed.V.col(1).minCoeff(), 1.2);  // metres after loading as dm
  // With the file's quads and texture coordinates (a textured garment stays textured).
  EXPECT_EQ(dressed.quads.rows(), source.quads.rows());
  ASSERT_EQ(dressed.UV.rows(), source.UV.rows());
  // The same polygons: the reader starts a quad at the corner its diagonal leaves from, which it
  // picks by shape, so a quad folded in the drape may be read back from another corner.
  const auto from_least_corner = [](Eigen::MatrixXi quads) {
    for (Eigen::Index q = 0; q < quads.rows(); ++q) {
      Eigen::Index first = 0;
      quads.row(q).minCoeff(&first);
      const Eigen::RowVectorXi row = quads.row(q);
      for (int k = 0; k < 4; ++k) quads(q, k) = row((first + k) % 4);
    }
    return quads;
  };
  EXPECT_EQ(from_least_corner(dressed.quads), from_least_corner(source.quads));
  EXPECT_EQ(dressed.UV, source.UV);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/mh_female_casualsuit01.placed.obj")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/dressed.glb")));
}

namespace {
// The names in a run's output folder, hidden ones left out, sorted.
std::vector<std::string> written(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(folder))
    if (e.path().filename().string()[0] != '.') names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}
}  // namespace

// Bad input refused before any work writes nothing; one that a stage refuses after reading the
// meshes writes report.html alone, showing what was tried, and says so on its line.
TEST(DressCli, BadInputExits2WithOneLineAndNoOutput) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  // A forgotten --units dm: the body would be 12.7 m tall.
  CliRun r = run(dir, "dress " + data(kChild) + " " + data(kOutfit) + " --garment-units dm -o " + dir.file("a"));
  EXPECT_EQ(r.code, 2);
  // The stages that ran print their line; the error is one line of its own, the last.
  EXPECT_EQ(error_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("dress-a-mesh: "), r.err.rfind('\n', r.err.size() - 2) + 1) << r.err;
  EXPECT_NE(r.err.find("mh_girl_child_11y.obj"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--body-units dm"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(only " + dir.file("a") + "/report.html written: what was tried)\n"), std::string::npos) << r.err;
  EXPECT_EQ(written(dir.file("a")), std::vector<std::string>{"report.html"});
  r = run(dir, "dress " + data(kChild) + " " + data(kOutfit) + " --units dm --layers sideways -o " + dir.file("b"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--layers"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("b")));
  r = run(dir, "dress " + data(kChild) + " " + data(kOutfit) + " --units dm --padding thick -o " + dir.file("p"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--padding: 'thick'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("p")));
  r = run(dir, "dress " + data(kChild) + " " + data(kOutfit) + " --units dm --fabric moon-silk -o " + dir.file("c"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("moon-silk"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("c")));
  // Given before the inputs, --fabric takes one value: the body and garment stay the inputs (the
  // run gets as far as checking --padding).
  r = run(dir, "dress --fabric gray-interlock " + data(kChild) + " " + data(kOutfit) + " --units dm --padding thick -o " +
                   dir.file("c"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--padding: 'thick'"), std::string::npos) << r.err;
  // A body given as the garment: closed, no opening for a body to pass through.
  r = run(dir, "dress " + data(kChild) + " " + data("bodies/mh_man_young_average.obj") + " --units dm -o " + dir.file("d"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(error_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("mh_man_young_average.obj: its largest piece (26756 faces) is closed, with no opening"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(written(dir.file("d")), std::vector<std::string>{"report.html"});
  // A bad unit is named with the option that gave it.
  r = run(dir, "dress " + data(kChild) + " " + data(kOutfit) + " --units dm --garment-units furlongs -o " +
                   dir.file("e"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--garment-units: 'furlongs' is not m, dm, cm, mm"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("e")));
}

// An output folder that is one of the inputs, a file, or under a file: refused before any work, the input
// untouched. An option for the patterns' body with no pattern among the garments: a warning.
TEST(DressCli, AnOutputThatIsAnInputIsRefusedBeforeAnyWork) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  const std::string garment = dir.file("outfit.obj");
  std::filesystem::copy_file(data(kOutfit), garment);
  const auto size = std::filesystem::file_size(garment);
  CliRun r = run(dir, "dress " + data(kChild) + " " + garment + " --units dm -o " + garment);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(error_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(garment + ": the output folder is an input"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("dress: load"), std::string::npos) << r.err;  // no stage ran
  EXPECT_EQ(std::filesystem::file_size(garment), size);
  const std::string file = dir.file("a_file");
  std::ofstream(file) << "not a folder\n";
  r = run(dir, "dress " + data(kChild) + " " + garment + " --units dm -o " + file);
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find(file + ": exists and is not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("dress: load"), std::string::npos) << r.err;
  r = run(dir, "dress " + data(kChild) + " " + garment + " --units dm -o " + file + "/sub/out");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find(file + "/sub/out: cannot be made: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a_file is not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("dress: load"), std::string::npos) << r.err;
  // A folder in which nothing can be made (for root too): said before any work.
  r = run(dir, "dress " + data(kChild) + " " + garment + " --units dm -o /proc/dresskit-out");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("/proc/dresskit-out: cannot be written: no folder can be made in /proc"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("dress: load"), std::string::npos) << r.err;
  r = run(dir, "dress " + data(kChild) + " " + garment + " --units dm --no-settle --pattern-body " + data(kChild) +
                   " -o " + dir.file("out"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --pattern-body " + data(kChild) + ": no garment is a sewing pattern (.json); not used"),
            std::string::npos)
      << r.err;
}
