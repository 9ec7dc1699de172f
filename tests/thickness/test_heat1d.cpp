// The heat solver against closed forms: the finite slab's Fourier series and the semi-infinite
// medium's erfc solution, with the measured order of convergence of each scheme.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "dresskit/mesh/errors.h"
#include "dresskit/testing/errors.h"
#include "dresskit/thickness/heat1d.h"

using namespace dresskit::thickness;

namespace dresskit {
namespace {

HeatProblem slab() {
  HeatProblem p;
  p.diffusivity = 1e-7;  // a fabric's order of magnitude [m²/s]
  p.length = 0.02;
  p.t_skin = 37.0;
  p.t_env = -10.0;
  p.t_initial = -10.0;
  p.duration = 0.05 * p.length * p.length / p.diffusivity;  // αt/L² = 0.05: profile half developed
  return p;
}

double max_error_vs_series(const HeatProblem& p, const HeatResult& r) {
  double e = 0.0;
  for (Eigen::Index i = 0; i < r.x.size(); ++i)
    e = std::max(e, std::abs(r.temperature[i] - heat_finite_slab(p, r.x[i], p.duration)));
  return e;
}

// The largest error against the series of `scheme` on each (cells, steps) grid.
std::vector<double> errors_of(const HeatProblem& p, HeatScheme scheme,
                              const std::vector<std::pair<int, int>>& grids) {
  std::vector<double> errors;
  for (const auto& [cells, steps] : grids) {
    HeatOptions o;
    o.scheme = scheme;
    o.cells = cells;
    o.steps = steps;
    errors.push_back(max_error_vs_series(p, solve_heat(p, o)));
  }
  return errors;
}

// The observed order of convergence between consecutive grids, each half the size of the one
// before: log2 of the ratio of their errors.
std::vector<double> orders(const std::vector<double>& errors) {
  std::vector<double> out;
  for (std::size_t k = 1; k < errors.size(); ++k) out.push_back(std::log2(errors[k - 1] / errors[k]));
  return out;
}

TEST(Heat1d, TridiagonalSolveMatchesDenseSolve) {
  const int n = 9;
  Eigen::VectorXd sub = Eigen::VectorXd::Random(n), sup = Eigen::VectorXd::Random(n);
  Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, 3.0) + Eigen::VectorXd::Random(n) * 0.5;
  Eigen::VectorXd rhs = Eigen::VectorXd::Random(n);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    A(i, i) = diag[i];
    if (i > 0) A(i, i - 1) = sub[i];
    if (i + 1 < n) A(i, i + 1) = sup[i];
  }
  const Eigen::VectorXd expected = A.partialPivLu().solve(rhs);
  solve_tridiagonal(sub, diag, sup, rhs);
  EXPECT_LT((rhs - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Heat1d, SeriesSolutionMeetsItsBoundaryAndInitialConditions) {
  const HeatProblem p = slab();
  EXPECT_NEAR(heat_finite_slab(p, 0.0, 10.0), p.t_skin, 1e-9);
  EXPECT_NEAR(heat_finite_slab(p, p.length, 10.0), p.t_env, 1e-9);
  // Long after: the steady straight line.
  EXPECT_NEAR(heat_finite_slab(p, 0.25 * p.length, 1e4 * p.duration), 37.0 - 0.25 * 47.0, 1e-9);
  // Early on, far from the skin, the slab is still at its initial temperature.
  EXPECT_NEAR(heat_finite_slab(p, 0.5 * p.length, 1e-3 * p.duration), p.t_initial, 1e-6);
}

TEST(Heat1d, CrankNicolsonIsSecondOrderAgainstTheSeries) {
  const HeatProblem p = slab();
  // Δt ∝ Δx: both error terms shrink by 4 per halving.
  const std::vector<double> errors =
      errors_of(p, HeatScheme::crank_nicolson, {{20, 20}, {40, 40}, {80, 80}, {160, 160}});
  const std::vector<double> order = orders(errors);
  for (std::size_t k = 0; k < order.size(); ++k) EXPECT_GE(order[k], 1.8) << "refinement " << k + 1;
  EXPECT_LT(errors.back(), 2e-3);  // [K] out of a 47 K range
}

TEST(Heat1d, ImplicitEulerIsFirstOrderInTime) {
  // 800 cells: fine enough that the time error dominates.
  const std::vector<double> errors =
      errors_of(slab(), HeatScheme::implicit_euler, {{800, 25}, {800, 50}, {800, 100}, {800, 200}});
  for (double order : orders(errors)) EXPECT_NEAR(order, 1.0, 0.2);
}

TEST(Heat1d, ExplicitIsSecondOrderInSpaceWithinItsLimitAndSubStepsBeyondIt) {
  const HeatProblem p = slab();
  std::vector<double> errors;
  for (int n : {20, 40, 80}) {
    HeatOptions o;
    o.scheme = HeatScheme::explicit_euler;
    o.cells = n;
    o.steps = static_cast<int>(std::ceil(p.diffusivity * p.duration * n * n / (0.4 * p.length * p.length)));
    const HeatResult r = solve_heat(p, o);
    EXPECT_LE(r.courant, 0.5);
    EXPECT_EQ(r.steps_taken, o.steps);  // no sub-steps needed
    errors.push_back(max_error_vs_series(p, r));
  }
  for (double order : orders(errors)) EXPECT_GE(order, 1.8);

  HeatOptions beyond;
  beyond.scheme = HeatScheme::explicit_euler;
  beyond.cells = 80;
  beyond.steps = 10;  // α Δt / Δx² ≈ 32: unstable as such
  const HeatResult r = solve_heat(p, beyond);
  EXPECT_LE(r.courant, 0.5);
  EXPECT_GT(r.steps_taken, beyond.steps);
  EXPECT_TRUE(r.temperature.allFinite());
  EXPECT_LT(max_error_vs_series(p, r), 0.05);
  beyond.explicit_substep = false;
  EXPECT_THROW(solve_heat(p, beyond), InputError);
}

TEST(Heat1d, MatchesTheErfcSolutionOfASemiInfiniteMedium) {
  HeatProblem p = slab();
  p.duration = 3600.0;
  p.length = 10.0 * std::sqrt(p.diffusivity * p.duration);  // the far end never feels the skin
  HeatOptions o;
  o.cells = 400;
  o.steps = 400;
  const HeatResult r = solve_heat(p, o);
  double e = 0.0;
  for (Eigen::Index i = 0; i < r.x.size(); ++i)
    e = std::max(e, std::abs(r.temperature[i] - heat_semi_infinite(p, r.x[i], p.duration)));
  EXPECT_LT(e, 5e-3);
  EXPECT_GT(e, 0.0);
}

TEST(Heat1d, RecordsTheSurfaceAndFindsCrossings) {
  HeatProblem p = slab();
  HeatOptions o;
  o.cells = 40;
  o.steps = 30;
  o.record_every = 7;
  const HeatResult r = solve_heat(p, o);
  ASSERT_EQ(r.times.size(), 6u);  // 0, 7, 14, 21, 28 steps and the end
  EXPECT_EQ(r.surface.rows(), 6);
  EXPECT_DOUBLE_EQ(r.times.back(), p.duration);
  EXPECT_TRUE(r.surface.row(5).transpose().isApprox(r.temperature));

  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(3, 0.0, 2.0);
  EXPECT_DOUBLE_EQ(crossing_depth(x, Eigen::Vector3d(10, 4, 0), 7.0), 0.5);
  EXPECT_DOUBLE_EQ(crossing_depth(x, Eigen::Vector3d(0, 4, 10), 7.0), 1.5);  // rising profile
  EXPECT_DOUBLE_EQ(crossing_depth(x, Eigen::Vector3d(10, 9, 8), 7.0), -1.0);
}

TEST(Heat1d, RejectsBadProblemsByName) {
  const HeatProblem good = slab();
  auto message = [](const HeatProblem& p, const HeatOptions& o) {
    return test::input_error_of([&] { solve_heat(p, o); });
  };
  HeatProblem p = good;
  p.diffusivity = 0.0;
  EXPECT_NE(message(p, {}).find("diffusivity"), std::string::npos);
  p = good;
  p.length = -1.0;
  EXPECT_NE(message(p, {}).find("length"), std::string::npos);
  p = good;
  p.duration = NAN;
  EXPECT_NE(message(p, {}).find("duration"), std::string::npos);
  HeatOptions o;
  o.cells = 1;
  EXPECT_NE(message(good, o).find("cells"), std::string::npos);
  o = {};
  o.steps = 0;
  EXPECT_NE(message(good, o).find("steps"), std::string::npos);
  EXPECT_THROW(parse_heat_scheme("leapfrog"), InputError);
  EXPECT_EQ(parse_heat_scheme("cn"), HeatScheme::crank_nicolson);
}

}  // namespace
}  // namespace dresskit
