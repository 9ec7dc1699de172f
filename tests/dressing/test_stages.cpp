// The dressing stages one at a time (dressing/src/stages/), on the procedural mannequin and its
// garments made in memory: each stage reads the outfit the stages before it left and reports what it
// did or why it was left out.
#include <gtest/gtest.h>

#include "dresskit/cloth/fabric.h"
#include "dresskit/mannequin/garments.h"
#include "dresskit/mannequin/mannequin.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/testing/errors.h"
#include "dresskit/thickness/thickness.h"
#include "outfit.h"

using namespace dresskit;
using namespace dresskit::dressing;
using namespace dresskit::dressing::detail;
using namespace dresskit::mannequin;
using namespace dresskit::mesh;

namespace {

/// A coarse mannequin with a t-shirt and trousers made on it (labelled by construction).
struct SmallOutfit {
  MannequinOptions mo = [] {
    MannequinOptions o;
    o.edge_length = 0.05;
    return o;
  }();
  BodyShape shape{mo};
  GarmentOptions go = [] {
    GarmentOptions o;
    o.edge_length = 0.05;
    return o;
  }();
  TriangleMesh body = make_mannequin(shape);
  TriangleMesh shirt = make_garment(shape, GarmentKind::tshirt, go);
  TriangleMesh trousers = make_garment(shape, GarmentKind::trousers, go);
  MeshFile body_file = MeshFile::given("body", body);
  std::vector<GarmentFile> garments{{MeshFile::given("shirt", shirt), ""}, {MeshFile::given("trousers", trousers), "11oz-black-denim"}};
};

/// Runs the stages from load up to and including `last` (names as in docs/dressing.md).
StageReport run_up_to(Outfit& outfit, const DressOptions& options, const std::string& last) {
  using Run = StageReport (*)(Outfit&, const DressOptions&);
  const std::vector<std::pair<std::string, Run>> order{
      {"load", stages::load},           {"clean", stages::clean},         {"units", stages::units},
      {"segmentation", stages::segmentation}, {"wearer", stages::wearer}, {"layers", stages::layers},
      {"placement", stages::placement},
      {"thickness", stages::thickness}, {"grading", stages::grading},     {"settle", stages::settle},
      {"padding", stages::padding}};
  for (const auto& [name, run] : order) {
    const StageReport r = run(outfit, options);
    if (name == last) return r;
  }
  throw std::runtime_error("no stage " + last);
}

}  // namespace

TEST(Stages, LoadTakesMeshesGivenInMemoryAndRefusesTwoOfOneName) {
  const SmallOutfit s;
  Outfit outfit(s.body_file, s.garments);
  const StageReport r = stages::load(outfit, {});
  EXPECT_FALSE(r.ran);
  EXPECT_EQ(r.reason, "every mesh given in memory");
  ASSERT_EQ(outfit.result.garments.size(), 2u);
  EXPECT_EQ(outfit.result.garments[1].name, "trousers");
  EXPECT_EQ(outfit.result.garments[1].fabric, "11oz-black-denim");
  EXPECT_EQ(outfit.result.garments[0].fabric, "gray-interlock");  // the default fabric

  const std::vector<GarmentFile> twice{s.garments[0], s.garments[0]};
  Outfit same(s.body_file, twice);
  EXPECT_NE(test::input_error_of([&] { stages::load(same, {}); }).find("another garment is called shirt"),
            std::string::npos);
}

// A body or garment beyond the triangles the stages handle in seconds is refused when loaded,
// naming the file and the bound.
TEST(Stages, LoadRefusesMeshesLargerThanTheBound) {
  const SmallOutfit s;
  DressOptions o;
  o.max_garment_triangles = s.shirt.num_faces() - 1;
  Outfit outfit(s.body_file, s.garments);
  const std::string e = test::input_error_of([&] { stages::load(outfit, o); });
  EXPECT_NE(e.find("shirt: " + std::to_string(s.shirt.num_faces()) + " triangles, more than the " +
                   std::to_string(o.max_garment_triangles) + " a garment may have"),
            std::string::npos)
      << e;
  o.max_garment_triangles = 0;  // no bound
  o.max_body_triangles = s.body.num_faces() / 2;
  Outfit again(s.body_file, s.garments);
  EXPECT_NE(test::input_error_of([&] { stages::load(again, o); }).find("body: "), std::string::npos);
  o.max_body_triangles = s.body.num_faces();
  Outfit fits(s.body_file, s.garments);
  EXPECT_NO_THROW(stages::load(fits, o));
}

TEST(Stages, CleanRepairsOnlyAMeshWithDefects) {
  SmallOutfit s;
  {
    Outfit outfit(s.body_file, s.garments);
    stages::load(outfit, {});
    const StageReport r = stages::clean(outfit, {});
    EXPECT_FALSE(r.ran) << r.reason;
  }
  TriangleMesh shirt = s.shirt;  // one face made degenerate: two of its corners the same vertex
  shirt.F(0, 1) = shirt.F(0, 0);
  const std::vector<GarmentFile> garments{{MeshFile::given("shirt", shirt), ""}};
  Outfit outfit(s.body_file, garments);
  stages::load(outfit, {});
  const StageReport r = stages::clean(outfit, {});
  EXPECT_TRUE(r.ran);
  EXPECT_NE(r.reason.find("shirt: 1 degenerate faces"), std::string::npos) << r.reason;
  EXPECT_LT(outfit.result.garments[0].mesh.num_faces(), shirt.num_faces());
}

TEST(Stages, UnitsRefuseABodyOfNoPersonsHeightAndAGarmentOfNoBodysSize) {
  SmallOutfit s;
  {
    Outfit outfit(s.body_file, s.garments);
    run_up_to(outfit, {}, "clean");
    const StageReport r = stages::units(outfit, {});
    EXPECT_TRUE(r.ran);
    EXPECT_NEAR(outfit.body_height, 1.75, 0.02);
  }
  TriangleMesh giant = s.body;
  giant.V *= 10.0;  // a 17.5 m person: a body in decimetres read as metres
  const MeshFile giant_file = MeshFile::given("giant", giant);  // the outfit keeps a reference
  Outfit tall(giant_file, s.garments);
  run_up_to(tall, {}, "clean");
  EXPECT_NE(test::input_error_of([&] { stages::units(tall, {}); }).find("giant: the body is 17.4 m tall in units m; with --body-units dm it would be 1.74 m"),
            std::string::npos);
  TriangleMesh huge = s.shirt;
  huge.V *= 100.0;  // a shirt in centimetres read as metres
  const std::vector<GarmentFile> garments{{MeshFile::given("huge", huge), ""}};
  Outfit small(s.body_file, garments);
  run_up_to(small, {}, "clean");
  const std::string message = test::input_error_of([&] { stages::units(small, {}); });
  EXPECT_NE(message.find("huge: the garment is"), std::string::npos) << message;
  EXPECT_NE(message.find("with --garment-units cm it fits"), std::string::npos) << message;
}

TEST(Stages, SegmentationIsLeftOutForLabelledMeshesAndRefusesABodyWithoutLimbs) {
  SmallOutfit s;
  {
    Outfit outfit(s.body_file, s.garments);
    const StageReport r = run_up_to(outfit, {}, "segmentation");
    EXPECT_FALSE(r.ran);
    EXPECT_EQ(r.reason, "every mesh has part labels");
    EXPECT_EQ(outfit.result.body_parts.size(), s.body.label_names.size());
  }
  TriangleMesh trunk = s.body;  // every vertex labelled torso
  trunk.labels.setZero();
  trunk.label_names = {"torso"};
  const MeshFile trunk_file = MeshFile::given("trunk", trunk);
  Outfit outfit(trunk_file, s.garments);
  run_up_to(outfit, {}, "units");
  EXPECT_NE(test::input_error_of([&] { stages::segmentation(outfit, {}); }).find("trunk: does not look like a body"),
            std::string::npos);
}

TEST(Stages, LayersInferredPutTheTopOverTheBottomWithItsFabric) {
  SmallOutfit s;
  const std::vector<GarmentFile> top_first = s.garments;  // shirt given first, trousers second
  DressOptions o;
  o.infer_layers = true;
  Outfit outfit(s.body_file, top_first);
  const StageReport r = run_up_to(outfit, o, "layers");
  EXPECT_TRUE(r.ran);
  ASSERT_EQ(outfit.result.garments.size(), 2u);
  EXPECT_EQ(outfit.result.garments[0].name, "trousers");
  EXPECT_EQ(outfit.result.garments[1].name, "shirt");
  EXPECT_EQ(outfit.result.garments[1].layer, 1);
  EXPECT_EQ(outfit.fabrics[0].name, "11oz-black-denim");  // fabrics follow their garments
  EXPECT_NE(r.reason.find("trousers (bottom) < shirt (top)"), std::string::npos) << r.reason;

  Outfit given(s.body_file, top_first);
  EXPECT_NE(run_up_to(given, {}, "layers").reason.find("as given: shirt < trousers"), std::string::npos);
}

TEST(Stages, PlacementLeavesAGarmentMadeOnTheBodyWhereItIs) {
  SmallOutfit s;
  Outfit outfit(s.body_file, s.garments);
  const StageReport r = run_up_to(outfit, {}, "placement");
  EXPECT_FALSE(r.ran);
  EXPECT_NE(r.reason.find("shirt already on the body"), std::string::npos) << r.reason;
  for (const DressedGarment& g : outfit.result.garments) {
    EXPECT_FALSE(g.placed_by_placement);
    EXPECT_EQ(g.placed, g.mesh.V);
  }
}

TEST(Stages, ThicknessKeepsLayersApartByTheThickestCloth) {
  SmallOutfit s;
  Outfit outfit(s.body_file, s.garments);
  const StageReport r = run_up_to(outfit, {}, "thickness");
  EXPECT_TRUE(r.ran);
  double thickest = 0.0;
  for (const cloth::Fabric& f : outfit.fabrics)
    thickest = std::max(thickest, thickness::sheet_thickness(f.composition, f.areal_density));
  EXPECT_GT(thickest, 0.0);
  EXPECT_DOUBLE_EQ(outfit.separation, thickest);
  EXPECT_DOUBLE_EQ(outfit.result.garments[1].thickness, thickest);  // the denim is the thicker
}

TEST(Stages, GradingIsLeftOutForOneGarment) {
  SmallOutfit s;
  const std::vector<GarmentFile> one{s.garments[0]};
  Outfit outfit(s.body_file, one);
  const StageReport r = run_up_to(outfit, {}, "grading");
  EXPECT_FALSE(r.ran);
  EXPECT_EQ(r.reason, "one garment: no layers to grade");
}

TEST(Stages, SettleAndPaddingAreLeftOutWhenNotAskedForAndDressedIsPlaced) {
  SmallOutfit s;
  DressOptions o;
  o.settle = false;
  Outfit outfit(s.body_file, s.garments);
  const StageReport settle = run_up_to(outfit, o, "settle");
  EXPECT_FALSE(settle.ran);
  EXPECT_EQ(settle.reason, "not asked for");
  for (const DressedGarment& g : outfit.result.garments) EXPECT_EQ(g.dressed, g.placed);
  const StageReport padding = stages::padding(outfit, o);
  EXPECT_FALSE(padding.ran);
  EXPECT_EQ(padding.reason, "no padded garment");
}

// The settle holds the trousers by their waistband and ends at rest or at its duration, with the
// samples of energy and strain the report plots.
TEST(Stages, SettleHoldsTheWaistbandAndSamplesTheRun) {
  SmallOutfit s;
  DressOptions o;
  o.settle_seconds = 0.1;
  Outfit outfit(s.body_file, s.garments);
  const StageReport r = run_up_to(outfit, o, "settle");
  EXPECT_TRUE(r.ran);
  EXPECT_TRUE(outfit.result.settle.ok) << outfit.result.settle.failure;
  EXPECT_GT(outfit.result.garments[1].waistband_vertices, 0);
  EXPECT_NE(r.reason.find("waistband of trousers held"), std::string::npos) << r.reason;
  EXPECT_EQ(outfit.waistbands.size(), 2u);
  ASSERT_GE(outfit.result.settle_time.size(), 2u);
  EXPECT_NEAR(outfit.result.settle_time.back(), 0.1, 0.02);
  EXPECT_EQ(outfit.result.settle_energy.size(), outfit.result.settle_time.size());
}
