#include <gtest/gtest.h>

#include "dresskit/cloth/collider.h"
#include "dresskit/cloth/simulator.h"
#include "cloth/bare_options.h"
#include "dresskit/mesh/errors.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace {
ClothModel single_particle(double mass) {
  ClothModel m;
  m.rest_positions = Eigen::MatrixX3d::Zero(1, 3);
  m.mass = Eigen::VectorXd::Constant(1, mass);
  return m;
}
}  // namespace

TEST(Collider, SignedDistancesAndNormals) {
  Eigen::Vector3d n;
  const Collider plane = Collider::plane({0, -0.5, 0}, {0, 2, 0});
  EXPECT_DOUBLE_EQ(plane.distance({3, 0.5, 1}, &n), 1.0);
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d::UnitY()));
  const Collider sphere = Collider::sphere({1, 0, 0}, 0.5);
  EXPECT_NEAR(sphere.distance({1, 0, 0.2}, &n), -0.3, 1e-15);
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d::UnitZ()));
  const Collider box = Collider::box({0, 0, 0}, {1, 2, 3});
  EXPECT_NEAR(box.distance({0, 0, 2.5}, &n), -0.5, 1e-15);  // inside, nearest face +Z
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(box.distance({4, 6, 0}, &n), 5.0, 1e-12);     // outside an edge: 3-4-5
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d(0.6, 0.8, 0)));
  EXPECT_THROW(Collider::sphere({0, 0, 0}, -1.0), InputError);
  EXPECT_THROW(Collider::plane({0, 0, 0}, {0, 0, 0}), InputError);
  EXPECT_THROW(Collider::box({0, 0, 0}, {1, 0, 1}), InputError);
}

TEST(Collider, FrictionRemovesMuTimesTheNormalSpeedFromTheSlide) {
  SimulationOptions o = test::bare_options(Integrator::symplectic_euler);
  o.gravity.setZero();
  o.dt = 1e-3;
  o.collision_margin = 0.0;
  o.colliders.push_back(Collider::plane({0, 0, 0}, {0, 1, 0}, 0.5));
  ClothSimulator sim(single_particle(1.0), o);
  Eigen::MatrixX3d x(1, 3), v(1, 3);
  x << 0, 0.0005, 0;
  v << 3.0, -1.0, 0;  // hits the plane within this step
  sim.set_state(x, v);
  const StepResult r = sim.step();
  EXPECT_EQ(r.collisions, 1);
  EXPECT_NEAR(sim.positions()(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(sim.velocities()(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(sim.velocities()(0, 0), 3.0 - 0.5 * 1.0, 1e-12);
}

TEST(Wind, ParticleReachesTheClosedFormTerminalVelocity) {
  SimulationOptions o;
  o.integrator = Integrator::symplectic_euler;
  o.dt = 1e-3;
  o.air_damping = 2.0;
  o.wind = Eigen::Vector3d(1.5, 0, -0.5);
  ClothSimulator sim(single_particle(0.2), o);
  for (int i = 0; i < 20000; ++i) ASSERT_TRUE(sim.step().ok);
  // m dv/dt = m g − c m (v − w) = 0  ⇒  v = w + g / c.
  const Eigen::Vector3d expected = o.wind + o.gravity / o.air_damping;
  EXPECT_LT((sim.velocities().row(0).transpose() - expected).norm(), 1e-9);
}

TEST(Collisions, ClothFallsOntoASphereWithoutEnteringIt) {
  const int n = 24;
  const TriangleMesh g = make_grid({1.0, 1.0}, {n, n}, {0, 0.5, 0}, {0, 1, 0});
  ClothBuildOptions b;
  b.total_mass = 0.3;
  SimulationOptions o;
  o.dt = 1.0 / 120;
  o.air_damping = 0.2;
  o.colliders = {Collider::sphere({0, 0, 0}, 0.3), Collider::plane({0, -0.5, 0}, {0, 1, 0})};
  ClothSimulator sim(build_cloth(g, fabric_by_name("gray-interlock"), b), o);
  for (int step = 0; step < 240; ++step) {
    const StepResult r = sim.step();
    ASSERT_TRUE(r.ok) << r.failure;
    for (int i = 0; i < sim.positions().rows(); ++i) {
      Eigen::Vector3d nrm;
      for (const Collider& c : o.colliders) {
        ASSERT_GE(c.distance(sim.positions().row(i).transpose(), &nrm), o.collision_margin - 1e-12);
      }
    }
  }
  // It drapes: the centre rests on top of the sphere, the corners hang well below it.
  EXPECT_NEAR(sim.positions().col(1).maxCoeff(), 0.3 + o.collision_margin, 0.01);
  EXPECT_LT(sim.positions()(0, 1), 0.0);
}

TEST(Settle, HangingChainConvergesAndReportsIt) {
  ClothModel m;
  m.rest_positions.resize(3, 3);
  m.rest_positions << 0, 0, 0, 0, -0.1, 0, 0, -0.2, 0;
  m.mass = Eigen::Vector3d(0.02, 0.02, 0.02);  // strains stay below the knee: a linear law
  for (int k = 0; k < 2; ++k) {
    m.springs.i.push_back(k);
    m.springs.j.push_back(k + 1);
    m.springs.rest_length.push_back(0.1);
    m.springs.k_rest.push_back(50.0);
    m.springs.k_knee.push_back(50.0);
    m.springs.type.push_back(SpringType::structural);
  }
  SimulationOptions o;
  o.dt = 0.01;
  o.air_damping = 5.0;
  ClothSimulator sim(m, o);
  sim.set_pinned({0});
  SettleOptions s;
  s.force_tolerance = 1e-6;
  const SettleResult r = sim.settle(s);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.stopped_reason, "converged");
  EXPECT_LE(r.final_residual, 1e-6);
  EXPECT_FALSE(r.energy_history.empty());
  // Bottom spring carries one weight, top spring two: extensions m g / k and 2 m g / k.
  const double e = 0.02 * 9.81 / 50.0;
  EXPECT_NEAR(sim.positions()(2, 1), -0.2 - 3 * e, 1e-6);
  s.max_time = 0.05;  // too short
  ClothSimulator early(m, o);
  early.set_pinned({0});
  EXPECT_EQ(early.settle(s).stopped_reason, "max_time");
}
