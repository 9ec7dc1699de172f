// The step loop (cloth/run.h) and the contact safeguards of adaptive stepping: a run stops when
// the cloth is at rest and says why, and fails when its steps stay near the smallest; a fast particle does not pass through a thin collider; a
// cloth that starts inside a collider is returned outside without a blow-up, and reported.
#include <gtest/gtest.h>

#include "cloth/bare_options.h"
#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/run.h"

using namespace dresskit::cloth;

namespace dresskit {
namespace {

ClothModel square(double size, int n, const Eigen::Vector3d& centre) {
  return build_cloth(make_grid({size, size}, {n, n}, centre, {0, 1, 0}), fabric_by_name("gray-interlock"));
}

// A square dropped 5 cm onto a plane comes to rest: the run stops long before its 10 s, at rest by
// the documented thresholds; without stopping at rest it runs the whole time.
TEST(Run, StopsWhenTheClothIsAtRestAndSaysWhy) {
  SimulationOptions o;
  o.colliders.push_back(Collider::plane({0, 0, 0}, {0, 1, 0}));
  RunOptions r;
  r.duration = 10.0;
  ClothSimulator sim(square(0.3, 12, {0, 0.05, 0}), o);
  int frames = 0;
  const RunResult result = run(sim, r, [&](int) { ++frames; });
  ASSERT_TRUE(result.ok) << result.failure;
  EXPECT_EQ(result.stopped_reason, "at rest");
  EXPECT_LT(sim.time(), 3.0);
  EXPECT_GT(result.rest_at, 0.05);  // it fell first
  EXPECT_NEAR(sim.time(), result.rest_at + r.rest.time, 0.02);
  EXPECT_LT(result.mean_speed, r.rest.mean_speed);
  EXPECT_LT(result.max_speed, r.rest.max_speed);
  EXPECT_EQ(frames, result.frames + 1);  // frame 0 and one per 1/24 s
  EXPECT_NEAR(result.frames, std::floor(sim.time() * r.fps + 1e-6), 1.0);

  r.rest.enabled = false;
  r.duration = 1.0;
  ClothSimulator all(square(0.3, 12, {0, 0.05, 0}), o);
  const RunResult full = run(all, r);
  EXPECT_EQ(full.stopped_reason, "duration reached");
  EXPECT_GE(all.time(), 1.0 - 1e-9);
}

// A run bounded by steps stops at the bound, keeps its state and says how far it got; one that ends
// by its duration on the bound's last step has not been cut short.
TEST(Run, StopsAtTheStepLimitAndSaysHowFarItGot) {
  SimulationOptions o;
  o.adaptive = false;
  o.colliders.push_back(Collider::plane({0, 0, 0}, {0, 1, 0}));
  RunOptions r;
  r.duration = 1.0;
  r.max_steps = 7;
  ClothSimulator sim(square(0.3, 12, {0, 0.05, 0}), o);
  const RunResult result = run(sim, r);
  ASSERT_TRUE(result.ok) << result.failure;
  EXPECT_EQ(result.stopped_reason, "step limit reached");
  EXPECT_EQ(result.totals.steps, 7);
  EXPECT_NEAR(sim.time(), 7 * o.dt, 1e-12);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find("step limit (7 steps) after 0.0583 of 1 s simulated"), std::string::npos)
      << result.warnings[0];
  r.duration = 7 * o.dt;
  ClothSimulator exact(square(0.3, 12, {0, 0.05, 0}), o);
  const RunResult whole = run(exact, r);
  EXPECT_EQ(whole.stopped_reason, "duration reached");
  EXPECT_TRUE(whole.warnings.empty());
}

// A horizontal square hinged at two corners of one edge swings down. With springs 10⁴ times stiffer
// than a real fabric's, projective dynamics' iterations stop moving at once while gravity is still
// unbalanced, and the run "comes to rest" in mid-air: it must say so in a warning. The real fabric
// and the stiffer one 100 times stiffer swing without one.
TEST(Run, WarnsWhenProjectiveDynamicsHoldsTheClothInsteadOfItsForces) {
  const int n = 21;
  auto hinged = [&](double scale, int& stuck, double& lowest) {
    Fabric fabric = fabric_by_name("ivory-rib-knit");
    fabric.stretching *= scale;
    ClothSimulator sim(build_cloth(make_grid({1.0, 1.0}, {n, n}, {0, 1, 0}, {0, 1, 0}), fabric), SimulationOptions{});
    sim.set_pinned({0, n - 1});
    RunOptions r;
    r.duration = 1.0;
    const RunResult result = run(sim, r);
    EXPECT_TRUE(result.ok) << result.failure;
    stuck = result.totals.stuck_steps;
    lowest = sim.positions().col(1).minCoeff();
    return result.warnings;
  };
  int stuck = 0;
  double lowest = 0.0;
  const std::vector<std::string> frozen = hinged(1e4, stuck, lowest);
  EXPECT_GT(lowest, 0.99);  // held in mid-air: what the warning is for
  ASSERT_EQ(frozen.size(), 1u);
  EXPECT_NE(frozen[0].find("held by the solver"), std::string::npos) << frozen[0];
  EXPECT_GT(stuck, 0);
  for (double scale : {1.0, 1e2}) {
    EXPECT_TRUE(hinged(scale, stuck, lowest).empty()) << scale;
    EXPECT_EQ(stuck, 0) << scale;
    EXPECT_LT(lowest, 0.8) << scale;  // it swung down
  }
}

// A run whose steps stay near the simulator's smallest step fails as stalled after the set number
// of steps, saying so, instead of taking hours of such steps; with the check off it runs its time.
TEST(Run, StopsAndFailsWhenItsStepsStayNearTheSmallest) {
  SimulationOptions o;
  o.adaptive = false;
  o.dt = 1e-3;
  o.dt_min = 1e-3;  // every step at the smallest
  RunOptions r;
  r.duration = 0.2;
  r.rest.enabled = false;
  ClothSimulator sim(square(0.3, 8, {0, 0.5, 0}), o);
  const RunResult stalled = run(sim, r);
  EXPECT_FALSE(stalled.ok);
  EXPECT_TRUE(stalled.stalled);
  EXPECT_EQ(stalled.totals.steps, r.stall.steps);
  EXPECT_NEAR(sim.time(), r.stall.steps * o.dt, 1e-9);
  EXPECT_EQ(stalled.stopped_reason.rfind("stalled: ", 0), 0u) << stalled.stopped_reason;

  r.stall.enabled = false;
  ClothSimulator all(square(0.3, 8, {0, 0.5, 0}), o);
  const RunResult full = run(all, r);
  EXPECT_TRUE(full.ok);
  EXPECT_EQ(full.stopped_reason, "duration reached");
  EXPECT_GE(all.time(), 0.2 - 1e-9);
}

// A step that blows up fails before its cloth–cloth collisions run (on an exploded state they find
// millions of candidate pairs): symplectic Euler on denim at 1/25 s, far beyond its stability limit.
TEST(Run, ABlowUpFailsBeforeTheClothClothCollisions) {
  SimulationOptions o = test::bare_options(Integrator::symplectic_euler);
  o.dt = 0.04;
  o.adaptive = false;
  o.strain_limiting = false;
  o.self_collision = true;
  ClothModel model = build_cloth(make_grid({0.5, 0.5}, {16, 16}, {0, 0, 0}, {0, 0, 1}),
                                 fabric_by_name("11oz-black-denim"));
  ClothSimulator sim(model, o);
  sim.set_pinned({240, 255});
  StepResult failed;
  for (int step = 0; step < 25 && failed.ok; ++step) failed = sim.step();
  ASSERT_FALSE(failed.ok);
  EXPECT_EQ(failed.failure.rfind("blow-up at t = ", 0), 0u) << failed.failure;
  EXPECT_EQ(failed.self.proximity_pairs, 0);
  EXPECT_EQ(failed.self.ccd_passes, 0);
  EXPECT_TRUE(sim.positions().allFinite());  // the last good state is kept
}

// A cloth falling at 20 m/s onto a plank 4 mm thick, at a fixed 1/60 s (33 cm a step): every
// particle's path crosses the plank within one step and ends below it. The continuous collision
// pass finds the crossing on the path and stops the cloth on top.
TEST(Collider, AFastClothDoesNotPassThroughAThinPlank) {
  SimulationOptions o = test::bare_options(Integrator::implicit_euler);
  o.dt = 1.0 / 60;
  o.colliders.push_back(Collider::box({0, 0, 0}, {0.5, 0.002, 0.5}));
  ClothSimulator sim(square(0.2, 8, {0, 0.2, 0}), o);
  sim.set_state(sim.positions(), Eigen::RowVector3d(0, -20, 0).replicate(sim.positions().rows(), 1));
  int caught = 0;
  for (int step = 0; step < 20; ++step) {
    const StepResult r = sim.step();
    ASSERT_TRUE(r.ok) << r.failure;
    caught += r.tunnelling;
  }
  EXPECT_GT(caught, 0);
  EXPECT_GE(sim.positions().col(1).minCoeff(), 0.002 + o.collision_margin - 1e-6);  // on top
}

// A square placed through a sphere (a disc of it up to 2 cm deep inside): the particles inside leave
// at a bounded speed (reported as deep pushes), nothing blows up, and after a second none is inside.
TEST(Collider, AClothStartingInsideIsReturnedOutsideAndReported) {
  for (Integrator integrator : {Integrator::projective, Integrator::implicit_euler}) {
    SimulationOptions o;
    o.integrator = integrator;
    o.colliders.push_back(Collider::sphere({0, 0, 0}, 0.1));
    ClothSimulator sim(square(0.3, 16, {0, 0.08, 0}), o);
    int inside = 0;
    for (int i = 0; i < sim.positions().rows(); ++i) inside += sim.positions().row(i).norm() < 0.1;
    ASSERT_GT(inside, 10);
    RunOptions r;
    r.duration = 1.0;
    r.rest.enabled = false;
    const RunResult result = run(sim, r);
    ASSERT_TRUE(result.ok) << to_string(integrator) << ": " << result.failure;
    EXPECT_GT(result.totals.deep_pushes, 0);
    for (int i = 0; i < sim.positions().rows(); ++i)
      EXPECT_GE(sim.positions().row(i).norm(), 0.1) << to_string(integrator) << " particle " << i;
    EXPECT_LE(sim.max_strain(), 0.12) << to_string(integrator);
  }
}

}  // namespace
}  // namespace dresskit
