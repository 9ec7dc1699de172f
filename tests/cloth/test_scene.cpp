#include <gtest/gtest.h>

#include <fstream>

#include "dresskit/cloth/scene.h"
#include "dresskit/mesh/errors.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace {
std::string write(const test::TempDir& dir, const std::string& text) {
  const std::string path = dir.file("scene.json");
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST(ClothScene, TheIssuesExampleReadsAsWritten) {
  test::TempDir dir;
  const ClothScene s = load_cloth_scene(write(dir, R"({"units": "m",
   "cloth": {"grid": {"size": [1.0, 1.0], "resolution": [64, 64], "center": [0, 0.5, 0], "normal": [0, 1, 0]},
             "fabric": "gray-interlock", "pins": [[0, 0], [63, 0]]},
   "colliders": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.3},
                 {"type": "plane", "point": [0, -0.5, 0], "normal": [0, 1, 0]}],
   "simulation": {"integrator": "implicit", "dt": 0.01, "duration": 2.0, "fps": 24,
                  "gravity": [0, -9.81, 0], "strain_limit": 0.1, "dynamic_stiffness": true}})"));
  EXPECT_EQ(s.model.rest_positions.rows(), 64 * 64);
  EXPECT_EQ(s.pins, (std::vector<int>{0, 63}));
  EXPECT_EQ(s.simulation.colliders.size(), 2u);
  EXPECT_EQ(s.simulation.integrator, Integrator::implicit_euler);
  EXPECT_DOUBLE_EQ(s.simulation.dt, 0.01);
  EXPECT_TRUE(s.simulation.strain_limiting);
  EXPECT_DOUBLE_EQ(s.simulation.strain_limit, 0.1);
  EXPECT_TRUE(s.simulation.dynamic_stiffness);
  EXPECT_DOUBLE_EQ(s.run.duration, 2.0);
  EXPECT_NEAR(s.model.rest_positions.col(1).mean(), 0.5, 1e-12);
}

TEST(ClothScene, UnitsScaleGeometryAndAChainNeedsItsMass) {
  test::TempDir dir;
  const ClothScene s = load_cloth_scene(write(dir, R"({"units": "cm",
   "cloth": {"chain": {"particles": 5, "spacing": 10, "top": [0, 100, 0]}, "total_mass": 0.5,
             "stiffness": 30, "pins": [0]}})"));
  EXPECT_EQ(s.model.springs.size(), 4);
  EXPECT_NEAR(s.model.springs.rest_length[0], 0.1, 1e-15);
  EXPECT_NEAR(s.model.rest_positions(0, 1), 1.0, 1e-15);
  EXPECT_NEAR(s.model.mass.sum(), 0.5, 1e-15);
  EXPECT_DOUBLE_EQ(s.model.springs.k_rest[0], 30.0);
}

TEST(ClothScene, BadScenesNameTheKey) {
  test::TempDir dir;
  const std::string grid = R"("grid": {"size": [1, 1], "resolution": [4, 4]})";
  const std::pair<std::string, std::string> cases[] = {
      {"{", "not valid JSON"},
      {R"({"cloth": {)" + grid + R"(}, "colour": 1})", "colour: unknown key"},
      {R"({"cloth": {)" + grid + R"(, "fabric": "silk"}})", "silk"},
      {R"({"cloth": {)" + grid + R"(}, "simulation": {"dt": 0}})", "simulation.dt"},
      {R"({"cloth": {)" + grid + R"(}, "simulation": {"dt": -1}})", "simulation.dt"},
      {R"({"cloth": {)" + grid + R"(, "pins": [[4, 0]]}})", "cloth.pins"},
      {R"({"cloth": {)" + grid + R"(, "pins": [4294967296]}})", "cloth.pins: vertex 2147483647 is out of range"},
      {R"({"cloth": {)" + grid + R"(, "pins": [[4294967296, 0]]}})", "cloth.pins: grid index"},
      {R"({"cloth": {)" + grid + R"(, "total_mass": -2}})", "cloth.total_mass"},
      {R"({"cloth": {)" + grid + R"(}, "colliders": [{"type": "cone"}]})", "colliders[0].type"},
      {R"({"cloth": {)" + grid + R"(}, "colliders": [{"type": "sphere", "radius": 1, "size": 2}]})",
       "colliders[0].size"},
      {R"({"cloth": {"grid": {"size": [1, 1], "resolution": [1, 4]}}})", "cloth.grid.resolution"},
      {R"({"cloth": {"grid": {"size": [1e300, 1e300], "resolution": [8, 8]}}})", "cloth.grid.size"},
      {R"({"units": 1e-12, "cloth": {)" + grid + R"(}})", "cloth.grid.size: must be 1 mm to 1 km"},
      {R"({"cloth": {)" + grid + R"(, "fabric_file": "."}})", "not a regular file"},
      {R"({"cloth": {)" + grid + R"(, "mesh": "x.obj"}})", "exactly one of"},
      {R"({"cloth": {"chain": {"particles": 3}}})", "total_mass"},
      {R"({"cloth": {)" + grid + R"(}, "simulation": {"integrator": "rk4"}})", "rk4"},
      {R"({"cloth": {)" + grid + R"(}, "simulation": {"time_scheme": "bdf3"}})",
       "simulation.time_scheme"},
  };
  for (const auto& [text, fragment] : cases) {
    const std::string path = write(dir, text);
    try {
      load_cloth_scene(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(fragment), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
}

TEST(ClothScene, ProjectiveDynamicsKeys) {
  test::TempDir dir;
  const std::string grid = R"("grid": {"size": [1, 1], "resolution": [4, 4]})";
  const ClothScene defaults = load_cloth_scene(write(dir, R"({"cloth": {)" + grid + R"(}})"));
  EXPECT_EQ(defaults.simulation.projective.time_scheme, TimeScheme::backward_euler);
  EXPECT_TRUE(defaults.simulation.projective.collisions);
  const ClothScene s =
      load_cloth_scene(write(dir, R"({"cloth": {)" + grid + R"(}, "simulation": {"integrator":
      "projective", "time_scheme": "bdf2", "projective_collisions": false}})"));
  EXPECT_EQ(s.simulation.integrator, Integrator::projective);
  EXPECT_EQ(s.simulation.projective.time_scheme, TimeScheme::bdf2);
  EXPECT_FALSE(s.simulation.projective.collisions);
  EXPECT_FALSE(defaults.simulation.projective.adaptive_weights);
  EXPECT_EQ(defaults.simulation.projective.lbfgs_history, 0);
  const ClothScene t =
      load_cloth_scene(write(dir, R"({"cloth": {)" + grid + R"(}, "simulation": {"integrator":
      "projective", "time_scheme": "tr_bdf2", "projective_adaptive_weights": true,
      "projective_lbfgs_history": 5}})"));
  EXPECT_EQ(t.simulation.projective.time_scheme, TimeScheme::tr_bdf2);
  EXPECT_TRUE(t.simulation.projective.adaptive_weights);
  EXPECT_EQ(t.simulation.projective.lbfgs_history, 5);
}

TEST(ClothScene, AdaptiveStepKeys) {
  test::TempDir dir;
  const std::string grid = R"("grid": {"size": [1, 1], "resolution": [4, 4]})";
  const ClothScene defaults = load_cloth_scene(write(dir, R"({"cloth": {)" + grid + R"(}})"));
  EXPECT_FALSE(defaults.simulation.rise_skips_held_springs);
  const ClothScene s = load_cloth_scene(write(dir, R"({"cloth": {)" + grid + R"(}, "simulation":
      {"max_strain_change": 0.1, "rise_skips_held_springs": true}})"));
  EXPECT_TRUE(s.simulation.rise_skips_held_springs);
  EXPECT_DOUBLE_EQ(s.simulation.max_strain_change, 0.1);
  EXPECT_THROW(load_cloth_scene(write(dir, R"({"cloth": {)" + grid + R"(}, "simulation":
      {"rise_skips_held_springs": 1}})")), InputError);
}
