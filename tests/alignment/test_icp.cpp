// ICP accuracy against known transforms (random axis, angle θ, translation up to 10 % of the
// diagonal, 0.5 % noise, 10 % outliers), global placement from any angle, and bad input. The full
// table is bench_alignment's; these are fewer trials with the same thresholds.
#include <gtest/gtest.h>

#include <limits>

#include "../../alignment/src/kd_tree.h"  // private to the library; tested here
#include "dresskit/testing/alignment_shapes.h"
#include "dresskit/testing/registration_trials.h"
#include "dresskit/mesh/errors.h"
#include "test_data.h"

using namespace dresskit::alignment;
using namespace dresskit::mannequin;

using namespace dresskit;
using namespace dresskit::mesh;

namespace {

const std::vector<test::Shape>& shapes() {
  static const std::vector<test::Shape> s = test::alignment_shapes(test::data_dir(), false);
  return s;
}

struct Tally {
  int ok = 0, n = 0;
  std::string failures;
};

template <class Align>
Tally run_trials(const std::vector<double>& angles, int per_shape, Align align,
                 std::vector<std::size_t> which = {}) {
  if (which.empty())
    for (std::size_t s = 0; s < shapes().size(); ++s) which.push_back(s);
  Tally t;
  for (double angle : angles) {
    std::mt19937 rng(42 + static_cast<int>(angle));
    for (std::size_t s : which) {
      for (int k = 0; k < per_shape; ++k) {
        TrialOptions o;
        o.angle_deg = angle;
        const Trial trial = make_trial(shapes()[s].points, o, rng);
        const TrialError e = trial_error(trial, align(trial));
        ++t.n;
        if (e.success()) {
          ++t.ok;
        } else {
          t.failures += " [" + shapes()[s].name + " θ=" + std::to_string(angle) + ": " +
                        std::to_string(e.rotation_deg) + "°, " +
                        std::to_string(100 * e.translation) + "%]";
        }
      }
    }
  }
  return t;
}

}  // namespace

TEST(Icp, RecoversKnownTransformsUpTo30Degrees) {
  if (shapes().size() < 4) DRESSKIT_REQUIRE_DATA();
  const Tally t = run_trials({5, 10, 20, 30}, 2, [](const Trial& tr) {
    return icp_align(tr.source, tr.target).transform;
  });
  EXPECT_GE(t.ok, 0.95 * t.n) << t.ok << "/" << t.n << " within 0.5° and 0.5 %:" << t.failures;
}

TEST(Icp, SoftStageRecoversTheNearlySymmetricLeg) {
  // The MakeHuman leg is nearly a surface of revolution: with hard nearest-neighbour
  // correspondences its rotation about its own axis is biased under 0.5 % noise (about half of
  // the trials miss 0.5°), although the Cramér–Rao bound allows 99 % (docs/alignment.md). The soft
  // final stage must recover it on the same trials, and clearly beat hard correspondences.
  DRESSKIT_REQUIRE_DATA();
  LoadOptions dm;
  dm.units = Units::parse("dm");
  TriangleMesh body = load_mesh(test::data_dir() + "/bodies/mh_woman_young_average.obj", dm);
  apply_part_labels(body, test::data_dir() + "/labels/mh_body_part_labels.json");
  const PointSet leg = test::part_points(body, "leg_left");
  IcpOptions hard;
  hard.soft_neighbours = 0;
  hard.coarse_epsilon_factor = 1.0;
  std::vector<double> soft_errors, hard_errors;
  int soft_ok = 0, hard_ok = 0;
  std::string failures;
  for (double angle : {5.0, 10.0, 20.0, 30.0}) {
    std::mt19937 rng(300 + static_cast<int>(angle));
    for (int k = 0; k < 3; ++k) {
      TrialOptions o;
      o.angle_deg = angle;
      const Trial trial = make_trial(leg, o, rng);
      const TrialError soft = trial_error(trial, icp_align(trial.source, trial.target).transform);
      const TrialError plain =
          trial_error(trial, icp_align(trial.source, trial.target, hard).transform);
      soft_ok += soft.success();
      hard_ok += plain.success();
      soft_errors.push_back(soft.rotation_deg);
      hard_errors.push_back(plain.rotation_deg);
      if (!soft.success())
        failures += " [θ=" + std::to_string(angle) + ": " + std::to_string(soft.rotation_deg) +
                    "°, " + std::to_string(100 * soft.translation) + "%]";
    }
  }
  std::sort(soft_errors.begin(), soft_errors.end());
  std::sort(hard_errors.begin(), hard_errors.end());
  EXPECT_GE(soft_ok, 9) << soft_ok << "/12 within 0.5° and 0.5 %:" << failures;
  EXPECT_LT(soft_errors[6], 0.7 * hard_errors[6])
      << "median rotation error: soft " << soft_errors[6] << "°, hard " << hard_errors[6] << "°";
  EXPECT_GT(soft_ok, hard_ok);
}

TEST(Icp, GlobalPlacementRecoversAnyAngle) {
  // The two torsos (mannequin and MakeHuman): small, so that every angle fits in a few seconds.
  if (shapes().size() < 4) DRESSKIT_REQUIRE_DATA();
  const Tally t = run_trials({5, 10, 20, 30, 45, 60, 90, 135, 180}, 1,
                             [](const Trial& tr) {
                               const GlobalResult g = global_align(tr.source, tr.target);
                               EXPECT_EQ(g.candidates.size(), 24u);
                               return g.result.transform;
                             },
                             {1, 3});
  EXPECT_GE(t.ok, 0.9 * t.n) << t.ok << "/" << t.n << t.failures;
}

TEST(Icp, LocalIcpFailsFromFarStartsSoTheGlobalStepIsNeeded) {
  // The reason for the multi-start: from 135° plain ICP lands in a wrong minimum.
  const Tally t = run_trials(
      {135}, 2, [](const Trial& tr) { return icp_align(tr.source, tr.target).transform; }, {0, 1});
  EXPECT_LT(t.ok, t.n);
}

TEST(Icp, ReportsFitnessRmseIterationsAndScale) {
  const PointSet& body = shapes()[0].points;
  std::mt19937 rng(3);
  TrialOptions o;
  o.angle_deg = 10;
  o.outliers = 0.0;
  o.noise = 0.0;
  Trial trial = make_trial(body, o, rng);
  const IcpResult r = icp_align(trial.source, trial.target);
  EXPECT_GT(r.fitness, 0.99);
  EXPECT_LT(r.rmse, 1e-3 * trial.diagonal);
  EXPECT_GT(r.iterations, 0);
  EXPECT_GT(r.seconds, 0.0);
  EXPECT_NEAR(r.scale, 1.0, 1e-9);
  EXPECT_LT(trial_error(trial, r.transform).rotation_deg, 0.05);

  // Similarity: the source shrunk by 0.8 about its centroid; the scale comes back as 1/0.8.
  const Eigen::RowVector3d c = trial.source.V.colwise().mean();
  trial.source.V = ((trial.source.V.rowwise() - c) * 0.8).rowwise() + c;
  IcpOptions scaled;
  scaled.with_scale = true;
  const IcpResult s = icp_align(trial.source, trial.target, scaled);
  EXPECT_NEAR(s.scale, 1.25, 0.01);
  EXPECT_GT(s.fitness, 0.95);
}

TEST(Icp, BadInputThrowsNamingTheProblem) {
  const PointSet& good = shapes()[1].points;
  auto expect_error = [&](const PointSet& bad, const std::string& words) {
    try {
      icp_align(bad, good);
      ADD_FAILURE() << "no error for " << words;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("source"), std::string::npos) << e.what();
    }
  };
  expect_error(PointSet{}, "only 0 points");
  expect_error(PointSet{good.V.topRows(5), {}}, "only 5 points");
  expect_error(PointSet{Eigen::MatrixX3d::Constant(50, 3, 0.25), {}}, "identical");
  Eigen::MatrixX3d line(50, 3);
  for (int i = 0; i < 50; ++i) line.row(i) = Eigen::RowVector3d(i, 2.0 * i, 0.5 * i);
  expect_error(PointSet{line, {}}, "one line");
  PointSet nan{good.V, {}};
  nan.V(17, 1) = std::numeric_limits<double>::quiet_NaN();
  expect_error(nan, "point 17 has a non-finite");
  EXPECT_THROW(global_align(good, PointSet{}), InputError);
}

TEST(Icp, PointLocatorFindsTheNearestPoint) {
  const Eigen::MatrixX3d& V = shapes()[1].points.V;
  const PointLocator locator(V);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(V.rows()) - 1);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d p = V.row(pick(rng)).transpose() + Eigen::Vector3d(0.003, -0.002, 0.001);
    double d2 = 0.0;
    const int i = locator.nearest(p, &d2);
    Eigen::Index brute = 0;
    (V.rowwise() - p.transpose()).rowwise().squaredNorm().minCoeff(&brute);
    EXPECT_EQ(i, brute);
    EXPECT_NEAR(d2, (V.row(brute).transpose() - p).squaredNorm(), 1e-9);
  }
}

TEST(Icp, KdTreeMatchesBruteForce) {
  // The tree behind ICP's correspondences and PointLocator: nearest and k nearest within a
  // distance limit, against a brute-force search, with duplicated points and split-plane ties.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Eigen::Vector3f> points(3000);
  for (auto& p : points) p = Eigen::Vector3f(u(rng), u(rng), 0.1f * std::round(5 * u(rng)));
  for (int i = 0; i < 200; ++i) points[2000 + i] = points[i];  // exact duplicates
  const detail::KdTree3 tree(points);
  for (int q = 0; q < 300; ++q) {
    const Eigen::Vector3f x(1.2f * u(rng), 1.2f * u(rng), 0.5f * u(rng));
    const float limit = q % 3 ? 0.04f : 1e9f;
    std::vector<std::pair<float, int>> all;
    for (int i = 0; i < static_cast<int>(points.size()); ++i)
      all.push_back({(points[i] - x).squaredNorm(), i});
    std::sort(all.begin(), all.end());
    float d2 = -1.0f;
    const int i = tree.nearest(x, limit, &d2);
    if (all[0].first < limit) {
      ASSERT_GE(i, 0);
      EXPECT_FLOAT_EQ(d2, all[0].first);
      EXPECT_FLOAT_EQ((points[i] - x).squaredNorm(), all[0].first);
    } else {
      EXPECT_EQ(i, -1);
    }
    int index[7];
    float dk[7];
    const int n = tree.nearest_k(x, 7, limit, index, dk);
    int expected = 0;
    while (expected < 7 && all[expected].first < limit) ++expected;
    ASSERT_EQ(n, expected);
    for (int k = 0; k < n; ++k) {
      EXPECT_FLOAT_EQ(dk[k], all[k].first) << k;
      EXPECT_FLOAT_EQ((points[index[k]] - x).squaredNorm(), all[k].first) << k;
    }
  }
}
