// Segmentation accuracy against the ground truth of the shared data (../shared/data/labels):
// per-part IoU after Hungarian matching and 1 − Rand index, with the segmentation goals as
// thresholds, and the names of the parts (left = the character's left). The figures are printed as
// a table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "dresskit/mesh/io.h"
#include "dresskit/segmentation/graph.h"
#include "dresskit/segmentation/label_cleanup.h"
#include "dresskit/segmentation/metrics.h"
#include "dresskit/segmentation/segment.h"
#include "ground_truth.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::mesh;
using namespace dresskit::segmentation;

namespace {

// Predicted labels with the parts named in `merge` given the label of the part named `into`.
Eigen::VectorXi merge_named(const SegmentationResult& r, const std::string& merge,
                            const std::string& into) {
  const auto names = r.part_names();
  const auto from = std::find(names.begin(), names.end(), merge),
             to = std::find(names.begin(), names.end(), into);
  Eigen::VectorXi out = r.vertex_labels;
  if (from == names.end() || to == names.end()) return out;
  for (int i = 0; i < out.size(); ++i)
    if (out(i) == from - names.begin()) out(i) = static_cast<int>(to - names.begin());
  return out;
}

// The predicted name that most truth vertices of part t carry.
std::string majority_name(const SegmentationResult& r, const Eigen::VectorXi& predicted,
                          const test::GroundTruth& truth, int t) {
  std::map<int, int> votes;
  for (int i = 0; i < truth.labels.size(); ++i)
    if (truth.labels(i) == t && predicted(i) >= 0) ++votes[predicted(i)];
  if (votes.empty()) return "";
  const auto best = std::max_element(
      votes.begin(), votes.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  return r.parts[best->first].name;
}

// Mean IoU ≥ 0.85 and Rand error ≤ 0.10 (c), every truth part carrying the name of its truth label
// (predicted: r's labels, perhaps with parts merged), and, where the axes were not given, +Y up and
// +Z forward found (the data's README).
void expect_parts_named_as_truth(const SegmentationResult& r, const Eigen::VectorXi& predicted,
                                 const test::GroundTruth& truth, const LabelComparison& c, bool given) {
  EXPECT_GE(c.mean_iou, 0.85);
  EXPECT_LE(1.0 - c.rand_index, 0.10);
  for (size_t t = 0; t < truth.names.size(); ++t)
    EXPECT_EQ(majority_name(r, predicted, truth, static_cast<int>(t)), truth.names[t]) << given;
  if (!given) {
    EXPECT_GT(r.axes.up.dot(Eigen::Vector3d::UnitY()), 0.95);
    EXPECT_GT(r.axes.forward.dot(Eigen::Vector3d::UnitZ()), 0.95) << r.axes.forward_source;
  }
}

LabelComparison report(const std::string& what, const Eigen::VectorXi& predicted,
                       const test::GroundTruth& truth, const SegmentationResult& r) {
  const LabelComparison c = compare_labels(predicted, truth.labels);
  std::printf("ACCURACY %-34s mean IoU %.3f  1-Rand %.3f  K=%d  %.0f ms |", what.c_str(),
              c.mean_iou, 1.0 - c.rand_index, r.parts_chosen, r.seconds.total * 1e3);
  // c.iou has one entry per truth label up to the largest present; absent parts are not printed.
  for (size_t t = 0; t < c.iou.size(); ++t)
    if ((truth.labels.array() == static_cast<int>(t)).any())
      std::printf(" %s %.3f", truth.names[t].c_str(), c.iou[t]);
  std::printf("\n");
  return c;
}

// Every part is one connected patch: the orphan-patch pass finds nothing to move.
void expect_one_patch_per_part(const TriangleMesh& mesh, const SegmentationResult& r) {
  const MeshGraph g = build_mesh_graph(mesh.V, mesh.F);
  Eigen::VectorXi labels = r.vertex_labels;
  EXPECT_EQ(merge_orphan_patches(g, adjacency(g), vertex_areas(mesh.V, mesh.F), labels), 0);
  for (const NamedPart& p : r.parts) {
    EXPECT_GE(p.confidence, 0.0) << p.name;
    EXPECT_LE(p.confidence, 1.0) << p.name;
  }
}

SegmentationOptions body_options(bool given_axes) {
  SegmentationOptions o;
  o.parts = 6;
  if (given_axes) {  // the data's README: +Y up, facing +Z
    o.up = Eigen::Vector3d::UnitY();
    o.forward = Eigen::Vector3d::UnitZ();
  }
  return o;
}

class MakeHumanBody : public ::testing::TestWithParam<std::string> {};
class GarmentCodeBody : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(MakeHumanBody, MeanIouAndNames) {
  DRESSKIT_REQUIRE_DATA();
  const std::string dir = test::data_dir();
  LoadOptions load;
  load.units = Units::parse("dm");
  const TriangleMesh mesh = load_mesh(dir + "/bodies/" + GetParam() + ".obj", load);
  const test::GroundTruth truth = test::mh_body_truth(dir);
  ASSERT_EQ(truth.labels.size(), mesh.num_vertices());
  for (bool given : {true, false}) {
    const SegmentationResult r = segment_mesh(mesh, body_options(given));
    const LabelComparison c =
        report(GetParam() + (given ? "" : " (axes estimated)"), r.vertex_labels, truth, r);
    expect_parts_named_as_truth(r, r.vertex_labels, truth, c, given);
  }
  // The number of parts chosen automatically: the eigengap's 5, then the head as a sixth limb.
  SegmentationOptions automatic = body_options(true);
  automatic.parts = 0;
  const SegmentationResult a = segment_mesh(mesh, automatic);
  EXPECT_EQ(a.parts_chosen, 6);
  EXPECT_EQ(a.limbs_added, 1);
  EXPECT_GE(report(GetParam() + " (parts automatic)", a.vertex_labels, truth, a).mean_iou, 0.85);
}
INSTANTIATE_TEST_SUITE_P(Segmentation, MakeHumanBody,
                         ::testing::Values("mh_woman_young_average", "mh_man_young_average",
                                           "mh_girl_child_11y"));

TEST_P(GarmentCodeBody, MeanIouAndNames) {
  DRESSKIT_REQUIRE_DATA();
  const std::string dir = test::data_dir();
  const TriangleMesh mesh = load_mesh(dir + "/bodies/" + GetParam() + ".obj");
  const test::GroundTruth truth = test::gc_body_truth(dir, mesh.num_vertices());
  for (bool given : {true, false}) {
    const SegmentationResult r = segment_mesh(mesh, body_options(given));
    const Eigen::VectorXi merged = merge_named(r, "head", "torso");
    const LabelComparison c =
        report(GetParam() + (given ? "" : " (axes estimated)"), merged, truth, r);
    expect_one_patch_per_part(mesh, r);
    // Axes estimated on the T-pose: its arm span is close to its height, PCA must still find up.
    expect_parts_named_as_truth(r, merged, truth, c, given);
  }
  SegmentationOptions automatic = body_options(true);
  automatic.parts = 0;
  const SegmentationResult a = segment_mesh(mesh, automatic);
  EXPECT_EQ(a.parts_chosen, 6);
  EXPECT_GE(
      report(GetParam() + " (parts automatic)", merge_named(a, "head", "torso"), truth, a).mean_iou,
      0.85);
}
INSTANTIATE_TEST_SUITE_P(Segmentation, GarmentCodeBody,
                         ::testing::Values("gc_mean_all", "gc_mean_all_tpose"));

namespace {

struct OutfitCase {
  std::string key;
  double top_min,
      bottom_min;  // thresholds on mean IoU; the goal is 0.80 (see docs/segmentation.md)
};

class MakeHumanOutfit : public ::testing::TestWithParam<OutfitCase> {};

// The truth restricted to one garment: a top's parts are torso and arms (sleeves), a bottom's torso
// and legs; the few labels of the other kind on it (a top's hem bound to a thigh) count as torso.
test::GroundTruth garment_truth(const test::GroundTruth& outfit, const Eigen::VectorXi& in_garment,
                                bool& is_top) {
  int arms = 0, legs = 0;
  for (int i = 0; i < outfit.labels.size(); ++i) {
    if (!in_garment(i) || outfit.labels(i) < 0) continue;
    const std::string& name = outfit.names[outfit.labels(i)];
    arms += name.rfind("arm", 0) == 0;
    legs += name.rfind("leg", 0) == 0;
  }
  is_top = arms > legs;
  test::GroundTruth g = outfit;
  for (int i = 0; i < g.labels.size(); ++i) {
    if (!in_garment(i)) {
      g.labels(i) = -1;
      continue;
    }
    const std::string& name = g.names[g.labels(i)];
    if (name.rfind(is_top ? "leg" : "arm", 0) == 0) g.labels(i) = 0;  // torso
  }
  return g;
}

}  // namespace

// An outfit is two components (a top and a bottom) in one file; the number of parts is chosen by
// the eigengap, and each garment is compared with its own labels.
TEST_P(MakeHumanOutfit, TopAndBottomMeanIou) {
  DRESSKIT_REQUIRE_DATA();
  const OutfitCase& param = GetParam();
  const std::string dir = test::data_dir();
  LoadOptions load;
  load.units = Units::parse("dm");
  const TriangleMesh mesh = load_mesh(dir + "/garments/mh_" + param.key + ".obj", load);
  const test::GroundTruth truth = test::mh_outfit_truth(dir, param.key);
  ASSERT_EQ(truth.labels.size(), mesh.num_vertices());
  SegmentationOptions o;
  o.up = Eigen::Vector3d::UnitY();
  o.forward = Eigen::Vector3d::UnitZ();
  const SegmentationResult r = segment_mesh(mesh, o);
  ASSERT_EQ(r.components, 2);
  for (int c = 0; c < 2; ++c) {
    Eigen::VectorXi in_garment = Eigen::VectorXi::Zero(mesh.num_vertices());
    for (int i = 0; i < mesh.num_vertices(); ++i)
      in_garment(i) = r.vertex_labels(i) >= 0 && r.parts[r.vertex_labels(i)].component == c;
    bool is_top = false;
    const test::GroundTruth g = garment_truth(truth, in_garment, is_top);
    std::string names;
    for (const auto& p : r.parts)
      if (p.component == c) names += " " + p.name;
    const LabelComparison cmp =
        report(param.key + (is_top ? " top:" : " bottom:") + names, r.vertex_labels, g, r);
    EXPECT_GE(cmp.mean_iou, is_top ? param.top_min : param.bottom_min)
        << (is_top ? "top" : "bottom");
    // Symmetric garments get symmetric cuts (docs/segmentation.md, "Symmetric cuts"): the male
    // trousers' legs (mirror-symmetric within half an edge) match the truth equally well.
    if (param.key == "male_casualsuit02" && !is_top) {
      EXPECT_NEAR(cmp.iou[3], cmp.iou[4], 0.02);
    }
  }
  // A skirt is cut in its own frame: with estimated axes (forward 0.15° off +Z) the same cut.
  if (!r.skirt_components.empty()) {
    const SegmentationResult e = segment_mesh(mesh, SegmentationOptions{});
    auto sizes = [](const SegmentationResult& s) {
      std::vector<int> v;
      for (const auto& p : s.parts)
        if (p.name.rfind("skirt", 0) == 0) v.push_back(p.vertices);
      std::sort(v.begin(), v.end());
      return v;
    };
    EXPECT_EQ(sizes(e), sizes(r));
    // Facing +Z, and so with its sides named as with the axes given: a skirt's hem is no foot (the
    // elegantsuit's flares behind its knees, which taken for feet turned the estimate round and
    // swapped every left and right).
    EXPECT_GT(e.axes.forward.z(), 0.95) << e.axes.forward_source;
    int same = 0;
    for (int i = 0; i < mesh.num_vertices(); ++i)
      same += r.vertex_labels(i) >= 0 && e.vertex_labels(i) >= 0 &&
              r.parts[r.vertex_labels(i)].name == e.parts[e.vertex_labels(i)].name;
    EXPECT_GE(same, 0.99 * mesh.num_vertices());
  }
}
INSTANTIATE_TEST_SUITE_P(
    Segmentation, MakeHumanOutfit,
    // Goal 0.80. The thresholds are what the method reaches today, just below it (female casual
    // top 0.848, bottom 0.838; blouse 0.899, skirt 0.880; male top 0.919, bottom 0.806), so that a
    // regression fails (docs/segmentation.md).
    ::testing::Values(OutfitCase{"female_casualsuit01", 0.84, 0.83},
                      OutfitCase{"female_elegantsuit01", 0.89, 0.87},
                      OutfitCase{"male_casualsuit02", 0.91, 0.80}),
    [](const auto& info) { return info.param.key; });
