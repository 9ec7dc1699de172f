// Segmentation kernels against closed forms and hand-made cases, the procedural mannequin and
// garments with their true labels, several components, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../mesh/mesh_fixtures.h"
#include "../mannequin/mannequin_fixture.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/segmentation/label_cleanup.h"
#include "dresskit/segmentation/graph.h"
#include "dresskit/segmentation/kmeans.h"
#include "dresskit/segmentation/metrics.h"
#include "dresskit/segmentation/segment.h"
#include "dresskit/segmentation/skirt.h"
#include "dresskit/segmentation/spectral.h"

using namespace dresskit::mannequin;

using namespace dresskit;
using namespace dresskit::mesh;
using namespace dresskit::segmentation;

namespace {

// A path graph 0 – 1 – … – n−1 with unit affinities.
Eigen::SparseMatrix<double> path_affinity(int n) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i + 1 < n; ++i) t.emplace_back(i, i + 1, 1.0), t.emplace_back(i + 1, i, 1.0);
  Eigen::SparseMatrix<double> W(n, n);
  W.setFromTriplets(t.begin(), t.end());
  return W;
}

// A strip of 2·n triangles along x (faces looking at +Z) whose height z(x) is given per column.
template <class Height>
TriangleMesh strip(int n, Height z) {
  TriangleMesh m;
  m.V.resize(2 * (n + 1), 3);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2; ++j) m.V.row(2 * i + j) << i - n / 2.0, j, z(i - n / 2.0);
  m.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    m.F.row(2 * i) << 2 * i, 2 * i + 2, 2 * i + 1;
    m.F.row(2 * i + 1) << 2 * i + 1, 2 * i + 2, 2 * i + 3;
  }
  return m;
}

TriangleMesh flat_strip(int n) {
  return strip(n, [](double) { return 0.0; });
}

// An open tube along z: `rings` rings of 24 vertices at z = 0.25·k − offset, radius r(z), faces
// looking outwards.
template <class Radius>
TriangleMesh tube(int rings, double offset, Radius r) {
  const int around = 24;
  TriangleMesh m;
  m.V.resize(rings * around, 3);
  for (int k = 0; k < rings; ++k)
    for (int a = 0; a < around; ++a) {
      const double z = 0.25 * k - offset, t = 2 * M_PI * a / around;
      m.V.row(k * around + a) << r(z) * std::cos(t), r(z) * std::sin(t), z;
    }
  m.F.resize(2 * (rings - 1) * around, 3);
  for (int k = 0; k + 1 < rings; ++k)
    for (int a = 0; a < around; ++a) {
      const int i = k * around + a, j = k * around + (a + 1) % around;
      m.F.row(2 * (k * around + a)) << i, j, j + around;
      m.F.row(2 * (k * around + a) + 1) << i, j + around, i + around;
    }
  return m;
}

// Mesh with the vertices and faces of a and b side by side (b shifted by `offset`).
TriangleMesh side_by_side(const TriangleMesh& a, const TriangleMesh& b,
                          const Eigen::Vector3d& offset) {
  TriangleMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V.rowwise() + offset.transpose();
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return m;
}

}  // namespace

TEST(SegmentationGraph, EdgesAffinitiesAndComponents) {
  const TriangleMesh cube = fixtures::cube(1.0);
  const MeshGraph g = build_mesh_graph(cube.V, cube.F);
  EXPECT_EQ(g.num_edges(), 18);  // 12 cube edges + 6 face diagonals
  EXPECT_GT(g.affinity.minCoeff(), 0.0);
  EXPECT_LE(g.affinity.maxCoeff(), 1.0);
  Eigen::VectorXi comp;
  EXPECT_EQ(connected_components(g, comp), 1);
  EXPECT_NEAR(vertex_areas(cube.V, cube.F).sum(), 6.0, 1e-12);

  const TriangleMesh two = side_by_side(cube, cube, Eigen::Vector3d(5, 0, 0));
  EXPECT_EQ(connected_components(build_mesh_graph(two.V, two.F), comp), 2);
}

TEST(SegmentationGraph, ConcaveFoldWeighsLessThanConvexFold) {
  // A valley at x = −2 (the surface bends towards its normals: concave) and a ridge of the same
  // angle at x = 2 (convex): the valley's edge has the lower affinity, and both are below a flat
  // edge.
  const TriangleMesh m = strip(12, [](double x) { return std::clamp(x + 2.0, 0.0, 4.0); });
  const MeshGraph g = build_mesh_graph(m.V, m.F);
  auto along = [&](double x) {
    for (int e = 0; e < g.num_edges(); ++e)
      if (m.V(g.from(e), 0) == x && m.V(g.to(e), 0) == x) return g.affinity(e);
    return -1.0;
  };
  EXPECT_LT(along(-2), along(2));
  EXPECT_LT(along(2), along(-4));
  EXPECT_LT(along(-2), 0.5 * along(-4));
}

TEST(SegmentationGraph, BridgesASlitButNotTwoComponents) {
  // A strip rolled into a tube that is open along a slit as wide as one edge: bridging joins the
  // slit's two edges; two such tubes side by side are never joined to each other.
  const int n = 24;
  TriangleMesh tube = strip(n, [](double) { return 0.0; });
  const double radius = (n + 1) / (2 * M_PI);  // the slit is about one edge wide
  for (int v = 0; v < tube.num_vertices(); ++v) {
    const double angle = (tube.V(v, 0) + n / 2.0) / radius;
    tube.V.row(v) << radius * std::cos(angle), tube.V(v, 1), radius * std::sin(angle);
  }
  MeshGraph g = build_mesh_graph(tube.V, tube.F);
  EXPECT_EQ(bridge_boundary_gaps(tube.V, 1.5, 6, g), 4);  // two across the slit, two diagonals
  MeshGraph none = build_mesh_graph(tube.V, tube.F);
  EXPECT_EQ(bridge_boundary_gaps(tube.V, 0.5, 6, none), 0);  // narrower than the slit

  const TriangleMesh two = side_by_side(tube, tube, Eigen::Vector3d(0, 1.2, 0));
  MeshGraph g2 = build_mesh_graph(two.V, two.F);
  EXPECT_EQ(bridge_boundary_gaps(two.V, 1.5, 6, g2), 8);
  Eigen::VectorXi comp;
  EXPECT_EQ(connected_components(g2, comp), 2);
}

TEST(SegmentationSpectral, PathGraphMatchesClosedForm) {
  // Plain Laplacian of a path with n vertices: λ_k = 2 − 2 cos(π k / n).
  const int n = 400;
  const Eigen::SparseMatrix<double> L = graph_laplacian(path_affinity(n), LaplacianKind::plain);
  const EigenResult r = smallest_eigenpairs(L, 6);
  EXPECT_EQ(r.method, "spectra shift-invert");
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r.values(k), 2 - 2 * std::cos(M_PI * k / n), 1e-10) << k;
  EXPECT_LT(r.residual, 1e-8);
  // The dense solver agrees.
  EigenOptions dense;
  dense.dense_below = n + 1;
  const EigenResult d = smallest_eigenpairs(L, 6, dense);
  EXPECT_EQ(d.method, "dense");
  EXPECT_LT((d.values - r.values).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(SegmentationSpectral, NormalizedLaplacianHasUnitDiagonalAndZeroMode) {
  const Eigen::SparseMatrix<double> L =
      graph_laplacian(path_affinity(300), LaplacianKind::normalized);
  EXPECT_NEAR(L.diagonal().minCoeff(), 1.0, 1e-15);
  const EigenResult r = smallest_eigenpairs(L, 3);
  EXPECT_NEAR(r.values(0), 0.0, 1e-10);
  EXPECT_LT(r.residual, 1e-8);
}

TEST(SegmentationSpectral, NonConvergenceSaysWhatWasTried) {
  const Eigen::SparseMatrix<double> L = graph_laplacian(path_affinity(500), LaplacianKind::plain);
  EigenOptions o;
  o.tolerance = 0.0;  // never met
  o.max_iterations = 1;
  try {
    smallest_eigenpairs(L, 5, o);
    FAIL() << "expected EigenSolverError";
  } catch (const EigenSolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("did not converge"), std::string::npos) << what;
    EXPECT_NE(what.find("ncv 20"), std::string::npos) << what;
    EXPECT_NE(what.find("ncv 40"), std::string::npos) << what;
  }
}

TEST(SegmentationKMeans, FindsSeparatedBlobsDeterministically) {
  Eigen::MatrixXd X(300, 2);
  for (int i = 0; i < 300; ++i) {
    const int c = i % 3;
    X.row(i) << 10.0 * c + std::sin(i), -5.0 * c + std::cos(3.0 * i);
  }
  const KMeansResult a = kmeans(X, 3), b = kmeans(X, 3);
  EXPECT_EQ(a.labels, b.labels);
  for (int i = 3; i < 300; ++i) EXPECT_EQ(a.labels(i), a.labels(i % 3)) << i;
  EXPECT_NE(a.labels(0), a.labels(1));
  EXPECT_NE(a.labels(1), a.labels(2));
}

TEST(SegmentationMetrics, HungarianAndRandIndex) {
  Eigen::MatrixXd score(3, 3);
  score << 1, 2, 3, 2, 4, 6, 3, 6, 9;  // best: anti-diagonal is 3 + 4 + 3 = 10 vs diagonal 14
  const std::vector<int> m = max_weight_matching(score);
  EXPECT_EQ(m, (std::vector<int>{0, 1, 2}));
  Eigen::MatrixXd rect(2, 3);
  rect << 0, 5, 1, 4, 0, 0;
  EXPECT_EQ(max_weight_matching(rect), (std::vector<int>{1, 0}));

  Eigen::VectorXi truth(6), pred(6);
  truth << 0, 0, 0, 1, 1, -1;
  pred << 2, 2, 2, 0, 0, 1;  // a relabelling: perfect
  LabelComparison c = compare_labels(pred, truth);
  EXPECT_DOUBLE_EQ(c.mean_iou, 1.0);
  EXPECT_DOUBLE_EQ(c.rand_index, 1.0);
  EXPECT_EQ(c.compared, 5);
  pred << 0, 0, 1, 1, 1, 1;  // one vertex wrong: IoUs 2/3 and 2/3; 4 of 10 pairs disagree
  c = compare_labels(pred, truth);
  EXPECT_NEAR(c.mean_iou, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(c.rand_index, 0.6, 1e-12);
  EXPECT_NEAR(c.agreement, 0.8, 1e-12);
}

TEST(SegmentationCleanup, OrphanPatchJoinsItsNeighbourAndFacesFollow) {
  const TriangleMesh strip = flat_strip(10);
  const MeshGraph g = build_mesh_graph(strip.V, strip.F);
  const Adjacency adj = adjacency(g);
  Eigen::VectorXi labels(strip.num_vertices());
  for (int v = 0; v < labels.size(); ++v) labels(v) = strip.V(v, 0) < 0 ? 0 : 1;
  labels(2) = labels(3) = 1;  // a patch of label 1 inside label 0
  const int moved = merge_orphan_patches(g, adj, vertex_areas(strip.V, strip.F), labels);
  EXPECT_EQ(moved, 2);
  for (int v = 0; v < labels.size(); ++v) EXPECT_EQ(labels(v), strip.V(v, 0) < 0 ? 0 : 1) << v;
  const Eigen::VectorXi faces = face_labels_from_vertices(strip.F, labels);
  EXPECT_EQ(faces(0), 0);
  EXPECT_EQ(faces(faces.size() - 1), 1);
}

// Rings of the tube (24 vertices each, in order) that carry both labels 0 and 1.
int mixed_rings(const Eigen::VectorXi& labels) {
  int mixed = 0;
  for (int k = 0; k < labels.size() / 24; ++k) {
    const auto ring = labels.segment(24 * k, 24);
    mixed += (ring.array() == 0).any() && (ring.array() == 1).any();
  }
  return mixed;
}

TEST(SegmentationCleanup, RandomWalkerStraightensACutAndKeepsThinParts) {
  // A uniform tube cut along the wavy line z = 0.5 + 0.4 cos θ: in the band (one radius each side)
  // the walk's probabilities are constant on each ring, so the cut becomes one ring.
  const TriangleMesh m = tube(41, 5.0, [](double) { return 1.0; });
  const MeshGraph g = build_mesh_graph(m.V, m.F);
  const Adjacency adj = adjacency(g);
  Eigen::VectorXi labels(m.V.rows());
  for (int v = 0; v < labels.size(); ++v) labels(v) = m.V(v, 2) > 0.5 + 0.4 * m.V(v, 0) ? 1 : 0;
  const int before = labels.sum();
  EXPECT_EQ(mixed_rings(labels), 3);  // wavy: the rings at z = 0.25, 0.5, 0.75
  Eigen::VectorXi off = labels;
  EXPECT_EQ(refine_boundaries_random_walker(g, adj, m.V, 0.0, off), 0);  // band 0: off
  EXPECT_GT(refine_boundaries_random_walker(g, adj, m.V, 1.0, labels), 0);
  EXPECT_LE(mixed_rings(labels), 1);      // straight, but for ties at the middle of the band
  EXPECT_NEAR(labels.sum(), before, 24);  // within one ring of the mean level
  // A label two rings thick between two others keeps its vertices: the band takes at most half of
  // a label's depth.
  for (int v = 0; v < labels.size(); ++v)
    labels(v) = m.V(v, 2) < -0.1 ? 0 : m.V(v, 2) < 0.4 ? 1 : 2;
  refine_boundaries_random_walker(g, adj, m.V, 3.0, labels);
  EXPECT_GE((labels.array() == 1).count(), 24);
}

TEST(SegmentationCleanup, LimbCutFollowsTheHarmonicField) {
  // A straight tube, hub below, limb above a wavy cut z = 0.5 + 0.4 cos θ: the field from the
  // limb's tip to the hub's core is nearly constant on each ring (the seeds, measured from the
  // wavy cut, are not quite whole rings), so the cut becomes nearly one ring, at the mean level of
  // the wavy one.
  const TriangleMesh m = tube(41, 5.0, [](double) { return 1.0; });
  const MeshGraph g = build_mesh_graph(m.V, m.F);
  Eigen::VectorXi labels(m.V.rows());
  for (int v = 0; v < labels.size(); ++v) labels(v) = m.V(v, 2) > 0.5 + 0.4 * m.V(v, 0) ? 1 : 0;
  const int limb_before = labels.sum();
  EXPECT_EQ(mixed_rings(labels), 3);
  Eigen::VectorXi off = labels;
  EXPECT_EQ(reshape_limb_cuts(g, adjacency(g), 0.0, off), 0);  // 0: off
  EXPECT_GT(reshape_limb_cuts(g, adjacency(g), 0.95, labels), 0);
  EXPECT_LE(mixed_rings(labels), 1);
  EXPECT_NEAR(labels.sum(), limb_before, 24);  // within one ring of the same level
}

TEST(SegmentationSkirt, BandEndsWhereTheSkirtStopsFollowingTheHips) {
  // A skirt along +Z from the hem (z = 0) to the waist (z = 10): a waistband of radius 1 down to
  // z = 9, hips widening to 1.4 at z = 7, then straight. The band ends at the hips' corner (30 % of
  // the length from the waist); the halves are mirror images, the vertices on the sagittal plane
  // stay with the band.
  auto radius = [](double z) { return z >= 9 ? 1.0 : z >= 7 ? 1.0 + 0.2 * (9 - z) : 1.4; };
  const TriangleMesh m = tube(41, 0.0, radius);
  const MeshGraph g = build_mesh_graph(m.V, m.F);
  const Eigen::VectorXd area = vertex_areas(m.V, m.F);
  std::vector<int> all(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) all[v] = v;
  AxesEstimate axes;
  axes.up = Eigen::Vector3d::UnitZ();
  axes.forward = Eigen::Vector3d::UnitX();
  axes.left = axes.up.cross(axes.forward);  // +Y
  axes.up_given = axes.forward_given = true;
  SkirtFrame frame = detect_skirt(g, m.V, area, all, axes);
  ASSERT_TRUE(frame.is_skirt);
  EXPECT_NEAR(frame.axis.z(), 1.0, 1e-9);
  EXPECT_NEAR(frame.left.y(), 1.0, 1e-9);
  EXPECT_NEAR(frame.waist_radius, 1.0, 1e-9);
  EXPECT_NEAR(frame.hem_radius, 1.4, 1e-9);
  Eigen::VectorXi labels = Eigen::VectorXi::Constant(m.num_vertices(), -1);
  split_skirt(g, m.V, area, all, frame, labels);
  EXPECT_NEAR(frame.band_fraction, 0.3, 0.07);
  int count[3] = {0, 0, 0};
  for (int v = 0; v < m.num_vertices(); ++v) {
    ASSERT_GE(labels(v), 0);
    ++count[labels(v)];
    const bool on_plane = std::abs(m.V(v, 1)) < 1e-9;
    if (std::abs(m.V(v, 2) - frame.band_height) < 1e-9) continue;  // on the cut
    if (m.V(v, 2) > frame.band_height || on_plane)
      EXPECT_EQ(labels(v), 0) << v;
    else
      EXPECT_EQ(labels(v), m.V(v, 1) > 0 ? 1 : 2) << v;
  }
  EXPECT_EQ(count[1], count[2]);

  // Not skirts: a tube that narrows to the hem, one leaning 45° from the given up, and a component
  // with three openings.
  const TriangleMesh narrowing = tube(41, 0.0, [](double z) { return 1.0 + 0.04 * z; });
  const MeshGraph gn = build_mesh_graph(narrowing.V, narrowing.F);
  EXPECT_FALSE(detect_skirt(gn, narrowing.V, area, all, axes).is_skirt);
  AxesEstimate tilted = axes;
  tilted.up = Eigen::Vector3d(1, 0, 1).normalized();
  tilted.forward = Eigen::Vector3d(1, 0, -1).normalized();
  EXPECT_FALSE(detect_skirt(g, m.V, area, all, tilted).is_skirt);
  TriangleMesh holed = m;  // a third opening: drop the two faces of one quad in the middle
  holed.F.conservativeResize(m.F.rows() - 2, 3);
  holed.F.bottomRows(m.F.rows() - 2 - 40 * 24) = m.F.bottomRows(m.F.rows() - 2 - 40 * 24);
  const MeshGraph gh = build_mesh_graph(holed.V, holed.F);
  EXPECT_FALSE(detect_skirt(gh, holed.V, area, all, axes).is_skirt);
  // With an estimated up, the waist is the narrower opening: the tube upside down is the same
  // skirt.
  TriangleMesh flipped = m;
  flipped.V.col(2) = (10.0 - m.V.col(2).array()).matrix();
  AxesEstimate estimated;
  EXPECT_TRUE(detect_skirt(build_mesh_graph(flipped.V, flipped.F), flipped.V, area, all, estimated)
                  .is_skirt);
}

TEST(SegmentationCleanup, MirrorVerticesOfASymmetricTube) {
  // A tube along z with 24 vertices per ring is symmetric across x = 0 (normal +X): vertex a of a
  // ring mirrors to vertex 12 − a. Bent sideways it is not.
  const TriangleMesh m = tube(9, 0.0, [](double) { return 1.0; });
  const Eigen::VectorXd area = vertex_areas(m.V, m.F);
  std::vector<int> all(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) all[v] = v;
  const std::vector<int> mirror = mirror_vertices(m.V, area, all, Eigen::Vector3d::UnitX(), 0.05);
  ASSERT_EQ(mirror.size(), static_cast<size_t>(m.num_vertices()));
  for (int v = 0; v < m.num_vertices(); ++v) {
    EXPECT_EQ(mirror[v], (v / 24) * 24 + (12 - v % 24 + 24) % 24) << v;
    EXPECT_EQ(mirror[mirror[v]], v);
  }
  TriangleMesh bent = m;
  for (int v = 0; v < bent.num_vertices(); ++v) bent.V(v, 0) += 0.1 * bent.V(v, 2) * bent.V(v, 2);
  EXPECT_TRUE(mirror_vertices(bent.V, area, all, Eigen::Vector3d::UnitX(), 0.05).empty());
}

TEST(SegmentationScene, MannequinPartsAndNames) {
  const TriangleMesh& body = test::DefaultScene::get().mannequin;
  SegmentationOptions o;
  o.parts = 6;
  const SegmentationResult r = segment_mesh(body, o);
  const LabelComparison c = compare_labels(r.vertex_labels, body.labels);
  std::printf("mannequin: mean IoU %.3f, 1-Rand %.3f\n", c.mean_iou, 1 - c.rand_index);
  EXPECT_GE(c.mean_iou, 0.85);
  // Names: the part matched to each true part carries its name (head_neck is our head).
  for (size_t t = 0; t < body.label_names.size(); ++t) {
    const std::string want = body.label_names[t] == "head_neck" ? "head" : body.label_names[t];
    ASSERT_GE(c.matched[t], 0);
    EXPECT_EQ(r.parts[c.matched[t]].name, want);
  }
  // Labels in the fixed order of names, so that colours match from mesh to mesh.
  EXPECT_EQ(r.part_names(), (std::vector<std::string>{"torso", "head", "arm_left", "arm_right",
                                                      "leg_left", "leg_right"}));
  EXPECT_GT(r.axes.up.y(), 0.95);  // estimated
  EXPECT_GT(r.axes.forward.z(), 0.95) << r.axes.forward_source;
  EXPECT_LT(r.eigen_residual, 1e-8);
  // Deterministic.
  EXPECT_EQ(segment_mesh(body, o).vertex_labels, r.vertex_labels);
}

TEST(SegmentationScene, GarmentsPartsAndNames) {
  // Mean IoU reached today with the number of parts chosen by the eigengap (goal 0.80, not met for
  // the trousers: docs/segmentation.md); a regression fails. The procedural skirt's truth is one
  // part `skirt`: our three skirt parts are merged into one before comparing (as GarmentCode's
  // `body` is our head and torso); unmerged it is 0.379.
  const double reached[] = {0.91, 0.99, 0.52};  // t-shirt 0.916, skirt 1.000, trousers 0.522
  const auto& scene = test::DefaultScene::get();
  for (size_t g = 0; g < all_garment_kinds().size(); ++g) {
    const TriangleMesh& garment = scene.garments[g];
    const SegmentationResult r = segment_mesh(garment);
    Eigen::VectorXi merged = r.vertex_labels;
    for (int v = 0; v < merged.size(); ++v)
      if (r.parts[merged(v)].name.rfind("skirt", 0) == 0) merged(v) = 0;
    const LabelComparison c = compare_labels(merged, garment.labels);
    std::printf("%s: %d parts, mean IoU %.3f (unmerged %.3f), 1-Rand %.3f:",
                to_string(all_garment_kinds()[g]).c_str(), r.parts_chosen, c.mean_iou,
                compare_labels(r.vertex_labels, garment.labels).mean_iou, 1 - c.rand_index);
    for (const auto& p : r.parts) std::printf(" %s", p.name.c_str());
    std::printf("\n");
    EXPECT_GE(c.mean_iou, reached[g]) << to_string(all_garment_kinds()[g]);
  }
  // The skirt is cut into a waist band and mirror halves; skirt_left on the character's left (+X),
  // the band above the halves.
  const TriangleMesh& skirt = scene.garments[1];
  const SegmentationResult r = segment_mesh(skirt);
  ASSERT_EQ(r.part_names(), (std::vector<std::string>{"skirt_waist", "skirt_left", "skirt_right"}));
  ASSERT_EQ(r.skirt_components, std::vector<int>{0});
  EXPECT_GT(r.skirt_band_fraction[0], 0.1);
  EXPECT_LT(r.skirt_band_fraction[0], 0.5);
  Eigen::Vector3d centroid[3] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                 Eigen::Vector3d::Zero()};
  int count[3] = {0, 0, 0};
  for (int v = 0; v < skirt.num_vertices(); ++v)
    centroid[r.vertex_labels(v)] += skirt.V.row(v).transpose(), ++count[r.vertex_labels(v)];
  for (int k = 0; k < 3; ++k) centroid[k] /= count[k];
  EXPECT_GT(centroid[1].x(), 0.05);
  EXPECT_LT(centroid[2].x(), -0.05);
  EXPECT_GT(centroid[0].y(), std::max(centroid[1].y(), centroid[2].y()));
  EXPECT_NEAR(count[1], count[2], 0.05 * count[1]);
  // A skirt in one part (asked for, or not split) is named by its two boundary loops.
  SegmentationOptions one;
  one.parts = 1;
  EXPECT_EQ(segment_mesh(skirt, one).parts[0].name, "skirt");
  SegmentationOptions unsplit;
  unsplit.split_skirts = false;
  EXPECT_TRUE(segment_mesh(skirt, unsplit).skirt_components.empty());
  EXPECT_EQ(segment_mesh(scene.garments[0], one).parts[0].name, "body");
}

TEST(SegmentationComponents, EachComponentGetsItsOwnParts) {
  const auto& scene = test::DefaultScene::get();
  // Mannequin and t-shirt apart from each other in one mesh: 6 + 3 parts, never across components.
  const TriangleMesh both =
      side_by_side(scene.mannequin, scene.garments[0], Eigen::Vector3d(2, 0, 0));
  SegmentationOptions o;
  o.parts = 9;
  const SegmentationResult r = segment_mesh(both, o);
  EXPECT_EQ(r.components, 2);
  ASSERT_EQ(r.parts_per_component.size(), 2u);
  EXPECT_EQ(r.parts_per_component[0] + r.parts_per_component[1], 9);
  for (int v = 0; v < both.num_vertices(); ++v)
    EXPECT_EQ(r.parts[r.vertex_labels(v)].component, v < scene.mannequin.num_vertices() ? 0 : 1);
}

TEST(SegmentationBadInput, ClearErrorsOrDocumentedFallbacks) {
  const TriangleMesh cube = fixtures::cube(1.0);
  SegmentationOptions o;
  o.parts = 9;  // more parts than the 8 vertices
  EXPECT_THROW(segment_mesh(cube, o), InputError);
  o.parts = -1;
  EXPECT_THROW(segment_mesh(cube, o), InputError);
  o.parts = kMaxParts + 1;
  EXPECT_THROW(segment_mesh(test::DefaultScene::get().mannequin, o), InputError);
  o.parts = 8;  // as many parts as vertices: one each
  const SegmentationResult each = segment_mesh(cube, o);
  EXPECT_EQ(each.parts_chosen, 8);
  EXPECT_EQ(each.vertex_labels.maxCoeff(), 7);
  o.parts = 1;  // fewer parts than the two components
  EXPECT_THROW(segment_mesh(side_by_side(cube, cube, Eigen::Vector3d(3, 0, 0)), o), InputError);
  TriangleMesh no_faces = cube;
  no_faces.F.resize(0, 3);
  EXPECT_THROW(segment_mesh(no_faces), InputError);

  // Isolated vertices: labelled −1, the rest segmented.
  TriangleMesh isolated = cube;
  isolated.V.conservativeResize(10, 3);
  isolated.V.bottomRows(2) << 5, 5, 5, 6, 6, 6;
  o.parts = 2;
  const SegmentationResult r = segment_mesh(isolated, o);
  EXPECT_EQ(r.isolated_vertices, 2);
  EXPECT_EQ(r.vertex_labels(8), -1);
  EXPECT_EQ(r.vertex_labels(9), -1);
  EXPECT_GE(r.vertex_labels.head(8).minCoeff(), 0);

  // Degenerate: every triangle has zero area (all vertices on a line). No crash, no NaN labels.
  TriangleMesh line = flat_strip(6);
  line.V.col(1).setZero();
  const SegmentationResult d = segment_mesh(line, o);
  EXPECT_EQ(d.parts_chosen, 2);
  EXPECT_GE(d.vertex_labels.minCoeff(), 0);

  // A face with a repeated corner adds no self-loop; a face (a, a, a) is a component of one vertex.
  TriangleMesh repeated = cube;
  repeated.F.conservativeResize(cube.F.rows() + 1, 3);
  repeated.F.row(cube.F.rows()) << 0, 0, 1;
  EXPECT_EQ(build_mesh_graph(repeated.V, repeated.F).num_edges(), 18);
  TriangleMesh lone = isolated;
  lone.F.conservativeResize(cube.F.rows() + 1, 3);
  lone.F.row(cube.F.rows()) << 8, 8, 8;
  o.parts = 3;
  const SegmentationResult l = segment_mesh(lone, o);
  EXPECT_EQ(l.components, 2);
  EXPECT_GE(l.vertex_labels(8), 0);

  // One part: everything in it.
  o.parts = 1;
  const SegmentationResult one = segment_mesh(cube, o);
  EXPECT_EQ(one.vertex_labels.maxCoeff(), 0);
  EXPECT_EQ(one.vertex_labels.minCoeff(), 0);
}

// Impossible option values are refused before any work, naming the option (the eigen-solver would
// otherwise run for minutes on an ncv of 10⁸).
TEST(Segmentation, ImpossibleOptionValuesAreRefusedNamingTheOption) {
  const TriangleMesh cube = fixtures::cube(1.0);
  auto refused = [&](SegmentationOptions o, const std::string& name) {
    try {
      segment_mesh(cube, o);
    } catch (const InputError& e) {
      return std::string(e.what()).rfind(name, 0) == 0;
    }
    return false;
  };
  SegmentationOptions o;
  o.eigen.ncv = -5;
  EXPECT_TRUE(refused(o, "ncv"));
  o.eigen.ncv = 100000000;
  EXPECT_TRUE(refused(o, "ncv"));
  o = {};
  o.over_segmentation = -1;
  EXPECT_TRUE(refused(o, "over_segmentation"));
  o = {};
  o.symmetry_tolerance = std::nan("");
  EXPECT_TRUE(refused(o, "symmetry_tolerance"));
  o = {};
  o.bridge_gaps = -1.0;
  EXPECT_TRUE(refused(o, "bridge_gaps"));
}
