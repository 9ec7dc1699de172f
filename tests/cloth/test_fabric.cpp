#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "dresskit/cloth/fabric.h"
#include "dresskit/mesh/errors.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::cloth;

TEST(Fabric, TenBuiltInFabricsByName) {
  const auto names = fabric_names();
  ASSERT_EQ(names.size(), 10u);
  const Fabric denim = fabric_by_name("11oz-black-denim");
  EXPECT_EQ(denim.name, "11oz-black-denim");
  EXPECT_GT(denim.areal_density, 0.0);
  const Fabric knit = fabric_by_name("gray-interlock");
  // Denim is far stiffer than an interlock knit.
  EXPECT_GT(denim.stiffness_at_rest(0.0), 5.0 * knit.stiffness_at_rest(0.0));
  try {
    fabric_by_name("silk");
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("silk"), std::string::npos);
    EXPECT_NE(m.find("gray-interlock"), std::string::npos);  // lists the known names
  }
}

TEST(Fabric, DirectionalStiffnessFromTheTensor) {
  const Fabric f = fabric_by_name("ivory-rib-knit");
  const auto c = f.stretching.row(0);
  EXPECT_DOUBLE_EQ(f.stiffness_at_rest(0.0), c(0));
  EXPECT_NEAR(f.stiffness_at_rest(M_PI / 2), c(2), 1e-9);
  EXPECT_NEAR(f.stiffness_at_rest(M_PI / 4), (c(0) + c(2) + 2 * c(1) + 4 * c(3)) / 4, 1e-9);
  // Orthotropic symmetry.
  EXPECT_NEAR(f.stiffness_at_rest(0.3), f.stiffness_at_rest(-0.3), 1e-9);
  EXPECT_NEAR(f.stiffness_at_knee(0.3), f.stiffness_at_knee(M_PI - 0.3), 1e-9);
  // At the measured directions the knee stiffness uses that direction's own row.
  const auto r3 = f.stretching.row(3);  // 45°
  EXPECT_NEAR(f.stiffness_at_knee(M_PI / 4), (r3(0) + r3(2) + 2 * r3(1) + 4 * r3(3)) / 4, 1e-9);
}

// The built-in table against the shared data file: the transcription is exact, and the published
// values are clamped at 0 and doubled.
TEST(Fabric, BuiltInTableMatchesTheSharedDataFile) {
  DRESSKIT_REQUIRE_DATA();
  const std::string path = test::data_dir() + "/fabrics/fabrics.json";
  const auto loaded = load_fabrics(path);
  ASSERT_EQ(loaded.size(), 10u);
  std::ifstream in(path);
  const auto raw = nlohmann::json::parse(in)["fabrics"];
  for (size_t n = 0; n < loaded.size(); ++n) {
    const Fabric built_in = fabric_by_name(loaded[n].name);
    EXPECT_EQ(built_in.stretching, loaded[n].stretching) << loaded[n].name;
    EXPECT_EQ(built_in.bending, loaded[n].bending) << loaded[n].name;
    EXPECT_EQ(built_in.areal_density, raw[n]["areal_density_kg_per_m2"].get<double>());
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(built_in.stretching(i, k), 2.0 * std::max(0.0, raw[n]["stretching"][i][k].get<double>()));
      }
  }
}

TEST(Fabric, BadFabricFilesNameTheFileAndField) {
  test::TempDir dir;
  auto expect_error = [&](const std::string& text, const std::string& fragment) {
    const std::string path = dir.file("f.json");
    std::ofstream(path) << text;
    try {
      load_fabrics(path);
      FAIL() << text;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(path), std::string::npos) << m;
      EXPECT_NE(m.find(fragment), std::string::npos) << m;
    }
  };
  expect_error("{", "not valid JSON");
  expect_error("{\"fabrics\": 3}", "\"fabrics\" array");
  expect_error("{\"fabrics\": [{\"name\": \"x\", \"areal_density_kg_per_m2\": -1}]}", "must be positive");
  expect_error("{\"fabrics\": [{\"name\": \"x\", \"areal_density_kg_per_m2\": 0.2, \"stretching\": [[1]]}]}",
               "stretching");
  // A fabric whose stretching has no positive stiffness along the warp, or a negative bending value.
  auto fabric = [](const std::string& stretching_row, double bending) {
    std::string rows = "[" + stretching_row;
    for (int i = 1; i < 6; ++i) rows += ", " + stretching_row;
    const std::string b = "[" + std::to_string(bending) + ", 1e-5, 1e-5, 1e-5, 1e-5]";
    return R"({"fabrics": [{"name": "x", "areal_density_kg_per_m2": 0.2, "stretching": )" + rows +
           R"(], "bending": [)" + b + ", " + b + ", " + b + "]}]}";
  };
  expect_error(fabric("[-40, 1, -60, 5]", 1e-5), "no positive stiffness along the warp");
  expect_error(fabric("[40, 1, 60, 5]", -1e-5), "bending[0][0] is negative");
  const std::string good = dir.file("good.json");
  std::ofstream(good) << fabric("[40, -1, 60, -5]", 1e-5);  // negative cross terms: a fit, clamped
  EXPECT_EQ(load_fabrics(good).size(), 1u);
  EXPECT_THROW(load_fabrics(dir.file("missing.json")), InputError);
}
