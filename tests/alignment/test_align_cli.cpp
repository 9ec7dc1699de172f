// dress-a-mesh align end to end: the transform in result.json, units, the placement's outputs, and
// bad input (exit 2, one line naming the file, nothing written).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "dresskit/alignment/icp.h"
#include "dresskit/mesh/io.h"
#include "mannequin/mannequin_fixture.h"
#include "test_data.h"
#include "tools/cli_run.h"

using namespace dresskit;
using namespace dresskit::alignment;
using namespace dresskit::mesh;
using namespace dresskit::test::cli;

TEST(AlignCli, RigidRecoversAKnownTransformAcrossUnits) {
  test::TempDir dir;
  TriangleMesh target = test::DefaultScene::get().mannequin;
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  truth.block<3, 3>(0, 0) =
      Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  truth.block<3, 1>(0, 3) = Eigen::Vector3d(0.1, -0.05, 0.2);
  TriangleMesh source = target;
  source.V = transform_points(truth.inverse(), target.V) * 100.0;  // in centimetres
  source.N.resize(0, 3);
  save_mesh(source, dir.file("source.obj"));
  save_mesh(target, dir.file("target.obj"));

  // Without units the 100× size difference is refused with the measured ratio.
  CliRun r = run(dir, "align " + dir.file("source.obj") + " " + dir.file("target.obj") +
                          " --rigid -o " + dir.file("out"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  const std::size_t at = r.err.find("factor of ");
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_NEAR(std::stod(r.err.substr(at + 10)), 100.0, 10.0)
      << r.err;  // bounding boxes of a rotated copy
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));

  r = run(dir, "align " + dir.file("source.obj") + " " + dir.file("target.obj") +
                   " --rigid --source-units cm -o " + dir.file("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir.file("out/result.json")));
  Eigen::Matrix4d T;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) T(i, k) = j["transform"][i][k];
  const Eigen::Matrix3d D = T.block<3, 3>(0, 0) * truth.block<3, 3>(0, 0).transpose();
  EXPECT_LT(std::acos(std::min(1.0, (D.trace() - 1) / 2)) * 180 / M_PI, 0.5)
      << 2.0 * 180 / M_PI << "° start";
  EXPECT_LT((T.block<3, 1>(0, 3) - truth.block<3, 1>(0, 3)).norm(), 0.005);
  EXPECT_GT(j["fitness"].get<double>(), 0.95);
  for (const char* key : {"rmse", "iterations", "seconds"}) EXPECT_TRUE(j.contains(key)) << key;
  const TriangleMesh aligned = load_mesh(dir.file("out/aligned.obj"));
  ASSERT_EQ(aligned.num_vertices(), target.num_vertices());
  EXPECT_LT((aligned.V - target.V).rowwise().norm().maxCoeff(), 0.01);
}

TEST(AlignCli, BadInputExits2WithOneLineAndNoOutput) {
  test::TempDir dir;
  save_mesh(test::DefaultScene::get().mannequin, dir.file("body.obj"));
  write(dir.file("nan.obj"), "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n");
  write(dir.file("tiny.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  for (const std::string bad : {"nan.obj", "tiny.obj"}) {
    const CliRun r = run(dir, "align " + dir.file(bad) + " " + dir.file("body.obj") +
                                  " --rigid --units m -o " + dir.file("out"));
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << bad;
  }
  // Placement without labels names the missing option.
  const CliRun r = run(
      dir, "align " + dir.file("body.obj") + " " + dir.file("body.obj") + " -o " + dir.file("out"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--garment-labels"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

TEST(AlignCli, PlacementWritesPosedGarmentAndMatches) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  const std::string d = test::data_dir();
  const CliRun r = run(dir, "align " + d + "/garments/mh_female_casualsuit01.obj " + d +
                                "/bodies/mh_girl_child_11y.obj --units dm --garment-labels " + d +
                                "/labels/mh_clothes_part_labels.json --body-labels " + d +
                                "/labels/mh_body_part_labels.json -o " + dir.file("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir.file("out/result.json")));
  EXPECT_EQ(j["matches"].size(), 6u);
  EXPECT_EQ(j["parts"].size(), 6u);
  EXPECT_TRUE(j["unmatched_garment_parts"].empty());
  EXPECT_EQ(j["layer_pieces"].size(), 2u);  // the casualsuit: t-shirt over jeans
  EXPECT_GT(j["layer_pushed_vertices"].get<int>(), 0);
  const TriangleMesh posed = load_mesh(dir.file("out/posed.obj"));
  EXPECT_EQ(posed.num_vertices(), 2197);
  EXPECT_LT(posed.V.col(1).maxCoeff(), 1.3);  // metres, on a 1.27 m child
}

// segment's labels.json is a labels file for align: the child and the casualsuit segmented, then
// placed with those labels, every garment part matched.
TEST(AlignCli, PlacementReadsSegmentsLabels) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  const std::string d = test::data_dir();
  const std::string garment = d + "/garments/mh_female_casualsuit01.obj", body = d + "/bodies/mh_girl_child_11y.obj";
  ASSERT_EQ(run(dir, "segment " + garment + " --units dm -o " + dir.file("garment")).code, 0);
  ASSERT_EQ(run(dir, "segment " + body + " --units dm -o " + dir.file("body")).code, 0);
  const CliRun r = run(dir, "align " + garment + " " + body + " --units dm --garment-labels " +
                                dir.file("garment/labels.json") + " --body-labels " + dir.file("body/labels.json") +
                                " -o " + dir.file("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir.file("out/result.json")));
  const auto segmented = nlohmann::json::parse(slurp(dir.file("garment/labels.json")));
  EXPECT_EQ(j["matches"].size(), segmented["part_names"].size());
  EXPECT_TRUE(j["unmatched_garment_parts"].empty());
  EXPECT_EQ(load_mesh(dir.file("out/posed.obj")).num_vertices(), 2197);
}

// An output that would replace an input is refused before any work: the source named
// aligned.obj in the output folder stays as it was, and no result.json appears beside it.
TEST(AlignCli, RefusesToOverwriteItsInput) {
  test::TempDir dir;
  const TriangleMesh body = test::DefaultScene::get().mannequin;
  save_mesh(body, dir.file("aligned.obj"));
  save_mesh(body, dir.file("target.obj"));
  const std::string before = slurp(dir.file("aligned.obj"));
  const CliRun r = run(dir, "align " + dir.file("aligned.obj") + " " + dir.file("target.obj") + " --rigid -o " +
                                dir.path().string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("aligned.obj: an input named as an output the run writes into"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir.file("aligned.obj")), before);
  EXPECT_FALSE(std::filesystem::exists(dir.file("result.json")));
}
