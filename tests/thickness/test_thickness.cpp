// Fibre mixing, the thickness and its limits, down fill and the surface dumps.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "dresskit/mesh/errors.h"
#include "dresskit/testing/errors.h"
#include "dresskit/thickness/thickness.h"
#include "test_data.h"

using namespace dresskit::thickness;

namespace dresskit {
namespace {

using test::input_error_of;

TEST(Fibres, TableHasTheIssuesFibresWithPositiveFigures) {
  for (const char* name : {"cotton", "polyester", "spandex", "nylon", "rayon", "wool", "down", "air"}) {
    const Fibre& f = fibre_by_name(name);
    EXPECT_GT(f.density, 0.0) << name;
    EXPECT_GT(f.specific_heat, 0.0) << name;
    EXPECT_GT(f.conductivity, 0.0) << name;
    EXPECT_FALSE(f.source.empty()) << name;
  }
  EXPECT_EQ(fibre_by_name("elastane").name, "spandex");
  EXPECT_EQ(fibre_by_name("viscose").name, "rayon");
  EXPECT_NE(input_error_of([] { fibre_by_name("kevlar"); }).find("cotton"), std::string::npos);
}

TEST(Fibres, CompositionParsingAndChecks) {
  const Composition c = parse_composition("cotton=0.6,polyester=0.4");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[1].first, "polyester");
  EXPECT_DOUBLE_EQ(c[1].second, 0.4);
  EXPECT_NO_THROW(check_composition(c));
  EXPECT_NE(input_error_of([] { parse_composition("cotton0.6"); }).find("cotton0.6"), std::string::npos);
  EXPECT_NE(input_error_of([] { parse_composition("cotton=abc"); }).find("abc"), std::string::npos);
  EXPECT_NE(input_error_of([] { check_composition(parse_composition("cotton=0.6,polyester=0.3")); }).find("sum"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { check_composition(parse_composition("cotton=1.2,polyester=-0.2")); }).find("-0.2"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { check_composition(parse_composition("cotton=0.5,silk=0.5")); }).find("silk"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { check_composition(parse_composition("cotton=0.5,cotton=0.5")); }).find("twice"),
            std::string::npos);
  EXPECT_NE(input_error_of([] { check_composition(parse_composition("cotton=0.5,air=0.5")); }).find("solidity"),
            std::string::npos);
  // Within 1e-6 of 1 is accepted.
  EXPECT_NO_THROW(check_composition(parse_composition("cotton=0.6000005,polyester=0.4")));
}

TEST(Fibres, SolidFibreHasItsOwnFiguresAndTwoPhaseMaxwellMatchesTheFormula) {
  const Fibre& cotton = fibre_by_name("cotton");
  const FabricThermal solid = fabric_thermal({{"cotton", 1.0}}, 1.0);
  EXPECT_NEAR(solid.conductivity_series, cotton.conductivity, 1e-12);
  EXPECT_NEAR(solid.conductivity_parallel, cotton.conductivity, 1e-12);
  EXPECT_NEAR(solid.conductivity_nominal, cotton.conductivity, 1e-12);
  EXPECT_NEAR(solid.volumetric_heat_capacity, cotton.density * cotton.specific_heat, 1e-6);

  const double phi = 0.3, kf = cotton.conductivity, ka = fibre_by_name("air").conductivity;
  const FabricThermal t = fabric_thermal({{"cotton", 1.0}}, phi);
  EXPECT_NEAR(t.conductivity_nominal, ka * (kf + ka + phi * (kf - ka)) / (kf + ka - phi * (kf - ka)), 1e-12);
  EXPECT_NEAR(t.conductivity_series, 1.0 / (phi / kf + (1 - phi) / ka), 1e-12);
  EXPECT_NEAR(t.conductivity_parallel, phi * kf + (1 - phi) * ka, 1e-12);
  EXPECT_NEAR(t.density, phi * cotton.density + (1 - phi) * fibre_by_name("air").density, 1e-9);
}

TEST(Fibres, NominalConductivityLiesBetweenTheBoundsForAnyBlend) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::vector<std::string> names = {"cotton", "polyester", "spandex", "nylon", "rayon", "wool", "down"};
  for (int trial = 0; trial < 200; ++trial) {
    Composition c;
    double sum = 0.0;
    for (const auto& n : names) {
      c.emplace_back(n, u(rng));
      sum += c.back().second;
    }
    for (auto& entry : c) entry.second /= sum;
    const FabricThermal t = fabric_thermal(c, 0.01 + 0.98 * u(rng));
    EXPECT_LE(t.conductivity_series, t.conductivity_nominal + 1e-15);
    EXPECT_LE(t.conductivity_nominal, t.conductivity_parallel + 1e-15);
    EXPECT_GT(t.conductivity_series, fibre_by_name("air").conductivity);
  }
  EXPECT_NE(input_error_of([] { fabric_thermal({{"cotton", 1.0}}, 0.0); }).find("solidity"), std::string::npos);
  EXPECT_NE(input_error_of([] { fabric_thermal({{"cotton", 1.0}}, 1.5); }).find("solidity"), std::string::npos);
}

TEST(Thickness, OrderedLimitsAndAgreementWithTheClosedForm) {
  const ThicknessResult r = compute_thickness(parse_composition("cotton=0.6,polyester=0.4"));
  EXPECT_LT(r.thickness_min, r.thickness);
  EXPECT_LT(r.thickness, r.thickness_max);
  EXPECT_DOUBLE_EQ(r.threshold, 13.5);  // midpoint of 37 and −10
  EXPECT_NEAR(r.thickness, r.thickness_closed_form, 0.005 * r.thickness_closed_form);
  // The limits follow the same law from their own diffusivities.
  EXPECT_NEAR(r.thickness_min,
              penetration_depth(r.fabric.diffusivity_series(), 3600, 37, -10, 13.5), 0.005 * r.thickness_min);
  EXPECT_NEAR(r.thickness_max,
              penetration_depth(r.fabric.diffusivity_parallel(), 3600, 37, -10, 13.5), 0.005 * r.thickness_max);
  // A penetration depth grows with √t.
  ThicknessOptions longer;
  longer.exposure = 4 * 3600.0;
  const ThicknessResult r4 = compute_thickness(parse_composition("cotton=0.6,polyester=0.4"), longer);
  EXPECT_NEAR(r4.thickness / r.thickness, 2.0, 0.01);
}

TEST(Thickness, AWarmerStartReachesDeeper) {
  const Composition c = {{"wool", 1.0}};
  ThicknessOptions o;
  const double cold = compute_thickness(c, o).thickness;
  o.t_initial = 0.0;  // between T_env and the 13.5 °C threshold
  const ThicknessResult warm = compute_thickness(c, o);
  EXPECT_GT(warm.thickness, cold);
  // The erfc solution with the initial temperature as the far field: the threshold's fraction of
  // (T_skin − T_initial) sets the depth.
  const double expected = penetration_depth(warm.fabric.diffusivity_nominal(), o.exposure, o.t_skin, 0.0, 13.5);
  EXPECT_NEAR(warm.thickness, expected, 0.01 * expected);
}

TEST(Thickness, AgreesAcrossSchemes) {
  const Composition c = parse_composition("nylon=0.87,spandex=0.13");
  ThicknessOptions o;
  const double cn = compute_thickness(c, o).thickness;
  o.heat.scheme = HeatScheme::implicit_euler;
  o.heat.steps = 4000;
  EXPECT_NEAR(compute_thickness(c, o).thickness, cn, 0.005 * cn);
  o.heat.scheme = HeatScheme::explicit_euler;
  EXPECT_NEAR(compute_thickness(c, o).thickness, cn, 0.005 * cn);
}

TEST(Thickness, RejectsBadConditionsByValue) {
  const Composition c = {{"cotton", 1.0}};
  ThicknessOptions o;
  o.t_env = 37.0;
  EXPECT_NE(input_error_of([&] { compute_thickness(c, o); }).find("T_skin"), std::string::npos);
  o = {};
  o.threshold = 40.0;
  EXPECT_NE(input_error_of([&] { compute_thickness(c, o); }).find("threshold 40"), std::string::npos);
  o = {};
  o.exposure = 0.0;
  EXPECT_NE(input_error_of([&] { compute_thickness(c, o); }).find("exposure"), std::string::npos);
  o = {};
  o.heat.cells = 0;
  EXPECT_NE(input_error_of([&] { compute_thickness(c, o); }).find("cells"), std::string::npos);
  // A warmer environment than the skin is fine: heat flows the other way.
  o = {};
  o.t_skin = 20.0;
  o.t_env = 45.0;
  const ThicknessResult r = compute_thickness(c, o);
  EXPECT_NEAR(r.thickness, r.thickness_closed_form, 0.005 * r.thickness_closed_form);
}

TEST(Thickness, DownFillIsAreaTimesThicknessTimesFillDensity) {
  const FabricThermal down = fabric_thermal({{"down", 1.0}}, 0.002);
  const DownFill fill = down_fill({0.1, 0.25, 0.0}, 0.03, down);
  ASSERT_EQ(fill.panel_kg.size(), 3u);
  EXPECT_NEAR(fill.fill_density, 0.002 * 1310.0, 1e-9);
  EXPECT_NEAR(fill.panel_kg[1], 0.25 * 0.03 * 2.62, 1e-12);
  EXPECT_NEAR(fill.total_kg, 0.35 * 0.03 * 2.62, 1e-12);
  EXPECT_EQ(fill.panel_kg[2], 0.0);
  EXPECT_THROW(down_fill({-0.1}, 0.03, down), InputError);
  EXPECT_THROW(down_fill({0.1}, 0.0, down), InputError);
}

TEST(Thickness, WritesTheSurfaceAsCsvAndPng) {
  test::TempDir dir;
  ThicknessOptions o;
  o.heat.record_every = 10;
  const ThicknessResult r = compute_thickness({{"wool", 1.0}}, o);
  write_temperature_surface(dir.path().string(), r, o);
  std::ifstream csv(dir.file("temperature.csv"));
  std::string header, line;
  std::getline(csv, header);
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, static_cast<int>(r.nominal.times.size()));
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), r.nominal.x.size());
  std::ifstream png(dir.file("temperature.png"), std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  // Without a recorded surface nothing is written.
  test::TempDir empty;
  const ThicknessResult plain = compute_thickness({{"wool", 1.0}});
  EXPECT_THROW(write_temperature_surface((empty.path() / "out").string(), plain, {}), OutputError);
  EXPECT_FALSE(std::filesystem::exists(empty.path() / "out"));
}

}  // namespace
}  // namespace dresskit

namespace dresskit {
namespace {
// A sheet of one fibre holding ρ × 0.25 × 1 mm of mass per area at solidity 0.25 is 1 mm thick; a
// blend's fibre density is the mass-weighted harmonic mean (the volumes add up); bad densities are
// refused.
TEST(Thickness, SheetThicknessIsMassOverFibreVolume) {
  const double rho_cotton = fibre_by_name("cotton").density, rho_poly = fibre_by_name("polyester").density;
  EXPECT_NEAR(sheet_thickness({{"cotton", 1.0}}, 0.1 * rho_cotton * 0.25 / 100.0, 0.25), 0.001, 1e-12);
  const double blend = 1.0 / (0.6 / rho_cotton + 0.4 / rho_poly);
  EXPECT_NEAR(sheet_thickness({{"cotton", 0.6}, {"polyester", 0.4}}, 0.2, 0.25), 0.2 / (blend * 0.25), 1e-12);
  EXPECT_THROW(sheet_thickness({{"cotton", 1.0}}, 0.0), InputError);
  EXPECT_THROW(sheet_thickness({{"cotton", 1.0}}, 0.2, 0.0), InputError);
}
}  // namespace
}  // namespace dresskit
