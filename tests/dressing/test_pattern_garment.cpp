// A pattern's panels carried from the body they are placed around to another, part by part
// (dressing/src/pattern_garment.h, panel_moves): checked against the bodies' own geometry — a body
// moved as a whole moves every panel with it, from GarmentCode's A-pose to its T-pose the sleeves
// turn as the arms' principal axes do, and on a stouter body every panel keeps its clearance
// (measured by brute force over all its points).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "dresskit/alignment/part_labels.h"
#include "dresskit/mesh/io.h"
#include "dresskit/pattern/cut.h"
#include "dresskit/pattern/pattern.h"
#include "pattern_garment.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::dressing::detail;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A GarmentCode body with the shared data's part labels (one file for both poses: same topology).
mesh::TriangleMesh labelled_gc_body(const std::string& name) {
  const std::string path = test::data_dir() + "/bodies/" + name + ".obj";
  mesh::TriangleMesh m = mesh::load_mesh(path);
  alignment::apply_part_labels(m, test::data_dir() + "/labels/gc_body_segmentation.json", "", path);
  return m;
}

/// The angle in the frontal plane (x, y) of the principal axis of a labelled part's vertices [rad],
/// measured from −Y (straight down) towards the side the part lies on.
double frontal_angle(const mesh::TriangleMesh& m, const std::string& part) {
  int label = -1;
  for (std::size_t k = 0; k < m.label_names.size(); ++k)
    if (m.label_names[k] == part) label = int(k);
  Eigen::MatrixX3d P(0, 3);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v)
    if (m.labels[v] == label) {
      P.conservativeResize(P.rows() + 1, 3);
      P.row(P.rows() - 1) = m.V.row(v);
    }
  const Eigen::RowVector3d c = P.colwise().mean();
  const Eigen::MatrixX3d Q = P.rowwise() - c;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Q.transpose() * Q);
  Eigen::Vector3d axis = eig.eigenvectors().col(2);
  if (axis.y() > 0.0) axis = -axis;  // pointing down the arm, from the shoulder
  return std::atan2(std::abs(axis.x()), -axis.y());
}

struct CutShirt {
  pattern::Pattern pattern;
  pattern::CutPattern cut;
};

CutShirt cut_shirt() {
  CutShirt s;
  s.pattern = pattern::read_pattern(test::data_dir() + "/patterns/gc_shirt_mean_specification.json");
  s.cut = pattern::cut_pattern(s.pattern, {});
  return s;
}

// Every panel follows the part its name says it covers: a sleeve its arm (GarmentCode's `left` is
// the body's +X side, as the labels' `left_arm`), the torso panels the torso.
void expect_parts_by_name(const CutShirt& s, const PanelMoves& m) {
  ASSERT_EQ(m.parts.size(), s.pattern.panels.size());
  for (std::size_t q = 0; q < m.parts.size(); ++q) {
    const std::string& name = s.pattern.panels[q].name;
    const std::string want = name.find("sleeve") == std::string::npos ? "torso"
                             : name.find("left") != std::string::npos ? "arm_left"
                                                                       : "arm_right";
    EXPECT_EQ(m.parts[q], want) << name;
  }
}

/// Each panel's least distance from its points (all of them) to the body's vertices [m].
std::vector<double> clearances(const Eigen::MatrixX3d& points, const Eigen::VectorXi& panel_of_vertex, int panels,
                               const mesh::TriangleMesh& body) {
  std::vector<double> least(std::size_t(panels), HUGE_VAL);
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    const double d2 = (body.V.rowwise() - points.row(v)).rowwise().squaredNorm().minCoeff();
    double& l = least[std::size_t(panel_of_vertex[v])];
    l = std::min(l, std::sqrt(d2));
  }
  return least;
}

}  // namespace

TEST(PanelMoves, OnAStouterBodyEveryPanelKeepsItsClearance) {
  DRESSKIT_REQUIRE_DATA();
  const mesh::TriangleMesh from = labelled_gc_body("gc_mean_all");
  mesh::TriangleMesh to = from;  // 15 % wider and deeper about the vertical axis through the torso
  const double cx = from.V.col(0).mean(), cz = from.V.col(2).mean();
  to.V.col(0) = (to.V.col(0).array() - cx) * 1.15 + cx;
  to.V.col(2) = (to.V.col(2).array() - cz) * 1.15 + cz;
  const CutShirt s = cut_shirt();
  const int panels = int(s.pattern.panels.size());
  const PanelMoves m = panel_moves(s.cut.placed, s.cut.panel_of_vertex, panels, from, to);
  Eigen::MatrixX3d moved = s.cut.placed;
  for (Eigen::Index v = 0; v < moved.rows(); ++v) {
    const Eigen::Matrix4d& T = m.moves[std::size_t(s.cut.panel_of_vertex[v])];
    moved.row(v) = (T.topLeftCorner<3, 3>() * s.cut.placed.row(v).transpose() + T.topRightCorner<3, 1>()).transpose();
  }
  const std::vector<double> was = clearances(s.cut.placed, s.cut.panel_of_vertex, panels, from),
                            is = clearances(moved, s.cut.panel_of_vertex, panels, to);
  // Within the sampling's reach (the clearance is taken over at most 64 points a panel); moved only
  // by its part, a torso panel would come 2–3 cm nearer.
  for (int q = 0; q < panels; ++q)
    EXPECT_GT(is[std::size_t(q)], was[std::size_t(q)] - 0.01) << s.pattern.panels[std::size_t(q)].name;
}

TEST(PanelMoves, ABodyMovedAsAWholeMovesEveryPanelWithIt) {
  DRESSKIT_REQUIRE_DATA();
  const mesh::TriangleMesh from = labelled_gc_body("gc_mean_all");
  mesh::TriangleMesh to = from;
  const Eigen::RowVector3d shift(0.1, -0.8, 0.15);
  to.V.rowwise() += shift;
  const CutShirt s = cut_shirt();
  const PanelMoves m = panel_moves(s.cut.placed, s.cut.panel_of_vertex, int(s.pattern.panels.size()), from, to);
  expect_parts_by_name(s, m);
  for (const Eigen::Matrix4d& T : m.moves) {
    EXPECT_LT((T.topLeftCorner<3, 3>() - Eigen::Matrix3d::Identity()).norm(), 1e-9);
    EXPECT_LT((T.topRightCorner<3, 1>() - shift.transpose()).norm(), 1e-9);
  }
}

TEST(PanelMoves, SleevesTurnAsTheArmsFromAPoseToTPose) {
  DRESSKIT_REQUIRE_DATA();
  const mesh::TriangleMesh a_pose = labelled_gc_body("gc_mean_all"), t_pose = labelled_gc_body("gc_mean_all_tpose");
  const CutShirt s = cut_shirt();
  const PanelMoves m =
      panel_moves(s.cut.placed, s.cut.panel_of_vertex, int(s.pattern.panels.size()), a_pose, t_pose);
  expect_parts_by_name(s, m);
  // The arms' principal axes turn by about 40° towards the horizontal.
  const double raised_left = frontal_angle(t_pose, "left_arm") - frontal_angle(a_pose, "left_arm");
  const double raised_right = frontal_angle(t_pose, "right_arm") - frontal_angle(a_pose, "right_arm");
  ASSERT_GT(raised_left, 20.0 * kPi / 180.0);
  for (std::size_t q = 0; q < m.parts.size(); ++q) {
    const Eigen::Matrix3d R = m.moves[q].topLeftCorner<3, 3>();
    const Eigen::Vector3d t = m.moves[q].topRightCorner<3, 1>();
    const std::string& part = m.parts[q];
    if (part == "torso") {
      // The torso stands where it stood: moved by no more than the shoulders' meeting rings shift
      // as the arms rise.
      EXPECT_LT((R - Eigen::Matrix3d::Identity()).norm(), 1e-12) << s.pattern.panels[q].name;
      EXPECT_LT(t.norm(), 0.03) << s.pattern.panels[q].name;
      continue;
    }
    // A sleeve turns about +Z only (the frontal plane), upwards on its side, by the arm's turn
    // within 5°.
    const Eigen::AngleAxisd turn(R);
    EXPECT_NEAR(std::abs(turn.axis().z()), 1.0, 1e-9) << s.pattern.panels[q].name;
    const double up = part == "arm_left" ? turn.angle() * turn.axis().z() : -turn.angle() * turn.axis().z();
    EXPECT_NEAR(up, part == "arm_left" ? raised_left : raised_right, 5.0 * kPi / 180.0) << s.pattern.panels[q].name;
  }
}
