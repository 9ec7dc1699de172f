// Cloth dropped onto real bodies with only what a user knows in the scene (cloth, fabric, body,
// units): onto the head, a shoulder, a T-pose arm, from 3.5 m, the stiffest fabric, MakeHuman bodies
// in decimetres and a scene in centimetres; with the defaults and with every integrator named
// alone. Each run must finish with nothing deeper than 2 mm inside the body (mesh/inside.h: an
// AABB tree and ray parity, not the simulator's distance grid), no self-intersection, structural
// strain ≤ 12 %, and a cloth that fell (testing/drops.h). Coarse cloths (24 vertices a side for
// the 0.8 m squares) keep the matrix to seconds a case.
#include <gtest/gtest.h>

#include "dresskit/testing/drops.h"
#include "test_data.h"

using namespace dresskit::cloth;

namespace dresskit {
namespace {

struct Drop {
  std::string case_name, integrator;  ///< integrator "" = the defaults
  double duration;
};

std::string name_of(const ::testing::TestParamInfo<Drop>& info) {
  std::string s = info.param.case_name + "_" + (info.param.integrator.empty() ? "defaults" : info.param.integrator);
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

class DropMatrix : public ::testing::TestWithParam<Drop> {};

TEST_P(DropMatrix, EndsOutsideTheBodyUntangledWithinTheStrainLimit) {
  DRESSKIT_REQUIRE_DATA();
  const Drop& d = GetParam();
  test::TempDir dir;
  const std::string simulation =
      d.integrator.empty() ? "{}" : "{\"integrator\": \"" + d.integrator + "\"}";
  const testing::DropOutcome o =
      testing::run_drop(testing::drop_case(d.case_name, 24), simulation, dir.path().string(), d.duration);
  EXPECT_TRUE(o.run.ok) << o.run.failure;
  EXPECT_EQ(o.inside, 0) << "deepest " << o.deepest * 1e3 << " mm";
  EXPECT_EQ(o.crossings, 0);
  EXPECT_LE(o.max_strain, 0.12);
  EXPECT_GE(o.drop, 0.02) << "the cloth did not fall";
  std::printf("%s: %d steps, %.2f s simulated, %.2f s CPU, %s; strain %.3f, fell %.3f m, deepest inside %.2f mm\n",
              name_of({d, 0}).c_str(), o.steps, o.simulated, o.seconds, o.run.stopped_reason.c_str(),
              o.max_strain, o.drop, o.deepest * 1e3);
}

std::vector<Drop> matrix() {
  std::vector<Drop> drops;
  for (const char* c : {"head", "shoulder", "tpose_arm", "head_stiff", "mh_man_dm_head", "mh_woman_cm_head"})
    drops.push_back({c, "", 1.0});
  drops.push_back({"head_from_3.5m", "", 1.2});  // reaches the head after 0.8 s
  for (const char* integrator : {"projective", "implicit", "newton", "symplectic"}) {
    drops.push_back({"head", integrator, 1.0});
    drops.push_back({"mh_man_dm_head", integrator, 0.8});
  }
  drops.push_back({"head_from_3.5m", "implicit", 1.2});
  drops.push_back({"tpose_arm", "symplectic", 1.0});
  return drops;
}

INSTANTIATE_TEST_SUITE_P(Real, DropMatrix, ::testing::ValuesIn(matrix()), name_of);

}  // namespace
}  // namespace dresskit
