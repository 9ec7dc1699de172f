// Double layers and stacked garments (cloth/layers.h): construction, the gap held inside the
// thickness limits at every step, and the layer order on analytic colliders.
#include <gtest/gtest.h>

#include <fstream>

#include "cloth/bare_options.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/scene.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/testing/errors.h"
#include "dresskit/thickness/thickness.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;
using namespace dresskit::thickness;

namespace {
ClothModel grid_cloth(int n, double height, const char* fabric = "gray-interlock") {
  return build_cloth(make_grid({1.0, 1.0}, {n, n}, {0, height, 0}, {0, 1, 0}),
                     fabric_by_name(fabric));
}

SimulationOptions sphere_options() {
  SimulationOptions o = test::bare_options(Integrator::implicit_euler);
  o.air_damping = 0.1;
  o.colliders.push_back(Collider::sphere({0, 0, 0}, 0.3));
  return o;
}
}  // namespace

TEST(Layers, DoubleLayerHasTheCopyTheSpringsAndAClosedSurface) {
  const ClothModel single = grid_cloth(5, 0.5);
  const LayerThickness t{0.01, 0.008, 0.015};
  const ClothModel d = make_double_layer(single, t);
  const int nv = 25;
  ASSERT_EQ(d.rest_positions.rows(), 2 * nv);
  EXPECT_EQ(d.layer.sum(), nv);
  EXPECT_EQ(d.layer_offset, (std::vector<double>{0.0, 0.01}));
  EXPECT_EQ(d.layer_min_gap, (std::vector<double>{0.0, 0.004}));
  // The outer layer is the inner one moved by the thickness along the (here +Y) normal.
  EXPECT_TRUE(d.rest_positions.bottomRows(nv).isApprox(
      single.rest_positions.rowwise() + Eigen::RowVector3d(0, 0.01, 0), 1e-12));
  EXPECT_DOUBLE_EQ(d.mass.sum(), 2.0 * single.mass.sum());
  EXPECT_EQ(d.springs.count(SpringType::structural),
            2 * single.springs.count(SpringType::structural));
  EXPECT_EQ(d.springs.count(SpringType::bending), 2 * single.springs.count(SpringType::bending));
  EXPECT_EQ(d.springs.count(SpringType::layer_structural), nv);
  EXPECT_EQ(d.springs.count(SpringType::layer_shear),
            2 * single.springs.count(SpringType::structural));
  ASSERT_EQ(d.springs.limited.size(), static_cast<std::size_t>(nv));
  for (std::size_t k = 0; k < d.springs.limited.size(); ++k) {
    const int s = d.springs.limited[k];
    EXPECT_EQ(d.springs.type[s], SpringType::layer_structural);
    EXPECT_DOUBLE_EQ(d.springs.rest_length[s], 0.01);
    EXPECT_DOUBLE_EQ(d.springs.limit_min[k], 0.008);
    EXPECT_DOUBLE_EQ(d.springs.limit_max[k], 0.015);
  }
  // Inter-layer structural stiffness = the mean of the vertex's own structural springs: a corner of
  // a square grid has two equal edges, so it equals theirs averaged.
  double corner = 0.0;
  int edges = 0;
  for (int s = 0; s < single.springs.size(); ++s)
    if (single.springs.type[s] == SpringType::structural &&
        (single.springs.i[s] == 0 || single.springs.j[s] == 0)) {
      corner += single.springs.k_rest[s];
      ++edges;
    }
  for (int s = 0; s < d.springs.size(); ++s) {
    if (d.springs.type[s] == SpringType::layer_structural && d.springs.i[s] == 0) {
      EXPECT_NEAR(d.springs.k_rest[s], corner / edges, 1e-9);
    }
  }
  // Inner faces, outer faces and 2 triangles per boundary edge (16 on a 5×5 grid): closed.
  EXPECT_EQ(d.faces.rows(), 2 * single.faces.rows() + 2 * 16);
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < d.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++directed[{d.faces(f, c), d.faces(f, (c + 1) % 3)}];
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(directed.count({e.second, e.first}), 1u) << e.first << "-" << e.second;
  }

  EXPECT_THROW(make_double_layer(single, {0.01, 0.012, 0.015}), InputError);  // min > thickness
  EXPECT_THROW(make_double_layer(single, {0.0, 0.0, 0.0}), InputError);
  EXPECT_THROW(make_double_layer(d, t), InputError);  // already two layers
}

TEST(Layers, StackingOffsetsIndicesLayersAndOffsets) {
  const ClothModel a = grid_cloth(4, 0.5),
                   b = make_double_layer(grid_cloth(3, 0.6), {0.02, 0.01, 0.03});
  const ClothModel m = stack_layers({a, b}, 0.003);
  EXPECT_EQ(m.rest_positions.rows(), 16 + 18);
  EXPECT_EQ(garment_offsets({a, b}), (std::vector<int>{0, 16, 34}));
  EXPECT_EQ(m.layer.maxCoeff(), 2);
  EXPECT_EQ(m.layer[16], 1);
  EXPECT_EQ(m.layer[33], 2);
  ASSERT_EQ(m.layer_offset.size(), 3u);
  EXPECT_DOUBLE_EQ(m.layer_offset[1], 0.003);
  EXPECT_DOUBLE_EQ(m.layer_offset[2], 0.023);
  EXPECT_EQ(m.layer_min_gap, (std::vector<double>{0.0, 0.003, 0.005}));
  EXPECT_EQ(m.springs.size(), a.springs.size() + b.springs.size());
  EXPECT_EQ(m.springs.limited.front(), a.springs.size() + b.springs.limited.front());
  EXPECT_EQ(m.faces.minCoeff(), 0);
  EXPECT_EQ(m.faces.maxCoeff(), 33);
}

// A garment's stitches (a sewn pattern's pairs left unwelded) stack with it: every field, indices
// moved by the particles beneath.
TEST(Layers, StackingKeepsEveryFieldOfTheStitches) {
  const ClothModel a = grid_cloth(4, 0.5);
  ClothModel b = grid_cloth(3, 0.6);
  add_seam_pairs(b.seams, {{0, 8}, {2, 6}}, 9, {100.0, 0.0});
  cap_stitches_by_acceleration(b.seams, 0, b.mass, 40.0);
  const ClothModel m = stack_layers({a, b}, 0.003);
  ASSERT_EQ(m.seams.size(), 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(m.seams.a[k], b.seams.a[k] + 16);
    EXPECT_EQ(m.seams.b0[k], b.seams.b0[k] + 16);
    EXPECT_EQ(m.seams.b1[k], b.seams.b1[k] + 16);
    EXPECT_EQ(m.seams.t[k], b.seams.t[k]);
    EXPECT_EQ(m.seams.stiffness[k], b.seams.stiffness[k]);
  }
  ASSERT_EQ(m.seams.max_force.size(), 2u);
  EXPECT_EQ(m.seams.max_force, b.seams.max_force);
}

TEST(Layers, GapStaysInsideTheLimitsAtEveryStepOnASphere) {
  const LayerThickness t{0.017, 0.0159, 0.0225};  // camel-ponte-roma's thermal thickness and limits
  // With cloth–cloth collisions, as every scene with faces runs: without them (the layer-order
  // guard alone) the coarse hem rolls, and 2 particles of the outer layer's second row lie under
  // the inner layer's first row at 4 of the 20 checked frames (side −15.8 mm, the face's own
  // normal; the interpolated vertex normals the measure used before put them at −2.5 mm, inside
  // its tolerance).
  SimulationOptions o = sphere_options();
  o.self_collision = true;
  ClothSimulator sim(make_double_layer(grid_cloth(16, 0.45, "camel-ponte-roma"), t), o);
  double lowest = 1.0, highest = 0.0;
  for (int step = 0; step < 480; ++step) {
    ASSERT_TRUE(sim.step().ok) << step;
    const LayerGap g = layer_gap(sim.model(), sim.positions());
    lowest = std::min(lowest, g.min);
    highest = std::max(highest, g.max);
    ASSERT_GE(g.min, t.min * (1 - 1e-3)) << "step " << step;
    ASSERT_LE(g.max, t.max * (1 + 1e-3)) << "step " << step;
    if (step % 24 == 0) {
      EXPECT_EQ(layer_order(sim.model(), sim.positions(), sim.options().colliders).violations, 0);
    }
  }
  EXPECT_LT(lowest, t.thickness);  // the limits were reached, not idle
  // No particle of either layer inside the sphere; the outer one keeps the thickness above it.
  Eigen::Vector3d n;
  for (int p = 0; p < sim.positions().rows(); ++p)
    EXPECT_GE(sim.options().colliders[0].distance(sim.positions().row(p), &n),
              sim.options().collision_margin - 1e-9);
}

// The layer-order measure on constructed layers: a particle is checked against the nearest point of
// the layer beneath and flagged only on its inner side.
TEST(Layers, OrderMeasureIsLocalAndIgnoresParticlesBesideTheLayerBeneath) {
  // Two nested half-cylinders (a curled hem and the one under it), radius 0.10 inside, 0.11
  // outside, in order: a height along +Y would put the outer one's lower half beneath the inner
  // one's top; the local side does not.
  auto tube = [](double radius, double length, int around, int along) {
    TriangleMesh m;
    m.V.resize(around * along, 3);
    for (int j = 0; j < along; ++j)
      for (int i = 0; i < around; ++i) {
        const double a = M_PI * i / (around - 1);
        m.V.row(j * around + i) << radius * std::cos(a), radius * std::sin(a),
            length * j / (along - 1);
      }
    m.F.resize(2 * (around - 1) * (along - 1), 3);
    int f = 0;
    for (int j = 0; j + 1 < along; ++j)
      for (int i = 0; i + 1 < around; ++i) {
        const int a = j * around + i;  // outward normals: counter-clockwise seen from outside
        m.F.row(f++) << a, a + around, a + 1;
        m.F.row(f++) << a + 1, a + around, a + around + 1;
      }
    return m;
  };
  const Fabric fabric = fabric_by_name("gray-interlock");
  const ClothModel stacked = stack_layers(
      {build_cloth(tube(0.10, 0.3, 17, 7), fabric), build_cloth(tube(0.11, 0.3, 17, 7), fabric)},
      0.002);
  LayerOrder order = layer_order(stacked, stacked.rest_positions, {});
  const int n = 17 * 7;
  EXPECT_EQ(order.violations, 0);
  EXPECT_EQ(order.checked,
            n - 2 * 17 - 2 * 5);  // the outer layer's border rows and columns lie beside
  // The outer layer moved to radius 0.09: every checked particle is under the inner one.
  Eigen::MatrixX3d x = stacked.rest_positions;
  x.bottomRows(n).leftCols(2) *= 0.09 / 0.11;
  order = layer_order(stacked, x, {});
  EXPECT_EQ(order.violations, order.checked);
  EXPECT_GT(order.checked, n / 2);
  // Moved along the axis past the inner layer's end: beside it, not checked.
  x = stacked.rest_positions;
  x.bottomRows(n).col(2).array() += 0.35;
  EXPECT_EQ(layer_order(stacked, x, {}).checked, 0);
}

// Beneath a particle two sheets of the layer below (a fold): 1 cm and 3 cm over a floor; the
// particle at 1.5 cm. The nearest sheet is the lower one, the highest the upper one.
TEST(Layers, MatchLayersFindsTheNearestOrTheHighestSheetBeneath) {
  const Fabric fabric = fabric_by_name("gray-interlock");
  auto sheet = [&](double height) { return build_cloth(make_grid({0.2, 0.2}, {5, 5}, {0, height, 0}, {0, 1, 0}), fabric); };
  ClothModel below = stack_layers({sheet(0.01), sheet(0.03)}, 0.0);
  below.layer.setZero();  // one layer folded over itself
  ClothModel top = sheet(0.015);
  const ClothModel stacked = stack_layers({below, top}, 0.0);
  const std::vector<Collider> floor = {Collider::plane({0, 0, 0}, {0, 1, 0})};
  const int p = static_cast<int>(stacked.rest_positions.rows()) - 13;  // an inner particle of the top sheet
  ASSERT_EQ(stacked.layer[p], 1);
  const LayerContacts nearest = match_layers(stacked, stacked.rest_positions, floor);
  const LayerContacts highest = match_layers(stacked, stacked.rest_positions, floor, true);
  ASSERT_GE(nearest.below_face[p], 0);
  ASSERT_GE(highest.below_face[p], 0);
  EXPECT_NEAR(nearest.height_below(p, stacked, stacked.rest_positions, floor), 0.01, 1e-9);
  EXPECT_NEAR(highest.height_below(p, stacked, stacked.rest_positions, floor), 0.03, 1e-9);
  EXPECT_NEAR(highest.distance[p], 0.015, 1e-9);
}

TEST(Layers, StackedGarmentsKeepTheirOrderOnASphere) {
  // Three single layers dropped together: the layer-order guard keeps them stacked.
  std::vector<ClothModel> garments = {grid_cloth(16, 0.40), grid_cloth(16, 0.42),
                                      grid_cloth(16, 0.44)};
  SimulationOptions o = sphere_options();
  ClothSimulator sim(stack_layers(garments, 0.004), o);
  int worst = 0, checked = 0;
  for (int step = 0; step < 480; ++step) {
    ASSERT_TRUE(sim.step().ok) << step;
    if (step % 24 == 23) {
      const LayerOrder order = layer_order(sim.model(), sim.positions(), o.colliders);
      worst = std::max(worst, order.violations);
      checked = order.checked;
    }
  }
  EXPECT_GT(checked, 400);
  // Measured 20 of 461 (the guard alone, without cloth–cloth collisions, cannot stop every crossing:
  // docs/cloth.md, Layers); 146 without the guard.
  EXPECT_LE(worst, checked / 20);
  // Without the guard the measure does see crossings: it is not blind.
  o.layer_order_guard = false;
  ClothSimulator unguarded(stack_layers(garments, 0.004), o);
  int crossed = 0;
  for (int step = 0; step < 480; ++step) {
    ASSERT_TRUE(unguarded.step().ok);
    if (step % 24 == 23)
      crossed = std::max(
          crossed, layer_order(unguarded.model(), unguarded.positions(), o.colliders).violations);
  }
  EXPECT_GT(crossed, worst);
}

TEST(Layers, SceneBuildsDoubleAndStackedLayersWithThicknessFromHeat) {
  test::TempDir dir;
  const std::string scene = dir.file("s.json");
  std::ofstream(scene) << R"({"cloths": [
      {"grid": {"size": [1, 1], "resolution": [8, 8], "center": [0, 0.5, 0]}, "fabric": "ivory-rib-knit", "pins": [[0, 0]]},
      {"grid": {"size": [1, 1], "resolution": [8, 8], "center": [0, 0.6, 0]}, "fabric": "royal-target",
       "thickness": {"t_skin": 37, "t_env": -20, "time": 3600}, "pins": [[7, 7]]},
      {"grid": {"size": [1, 1], "resolution": [4, 4], "center": [0, 0.7, 0]}, "thickness": {"mm": 5, "min_mm": 4, "max_mm": 8}}],
    "simulation": {"layer_separation": 0.003}})";
  const ClothScene s = load_cloth_scene(scene);
  ASSERT_EQ(s.garments.size(), 3u);
  EXPECT_FALSE(s.garments[0].double_layer);
  EXPECT_TRUE(s.garments[1].double_layer);
  EXPECT_EQ(s.garments[1].first_vertex, 64);
  EXPECT_EQ(s.garments[1].vertices, 128);
  // royal-target by heat: the same figures as the thickness library gives.
  const ThicknessResult heat = [] {
    ThicknessOptions o;
    o.t_env = -20;
    return compute_thickness(fabric_by_name("royal-target").composition, o);
  }();
  EXPECT_DOUBLE_EQ(s.garments[1].thickness.thickness, heat.thickness);
  EXPECT_DOUBLE_EQ(s.garments[1].thickness.max, heat.thickness_max);
  EXPECT_DOUBLE_EQ(s.garments[2].thickness.thickness, 0.005);
  EXPECT_EQ(s.pins,
            (std::vector<int>{0, 64 + 63, 64 + 64 + 63}));  // both layers of garment 1 pinned
  ASSERT_EQ(s.model.layer_offset.size(), 5u);
  EXPECT_NEAR(s.model.layer_offset[1], 0.003, 1e-12);
  EXPECT_NEAR(s.model.layer_offset[2], 0.003 + heat.thickness, 1e-12);

  auto error_of = [&](const std::string& text) {
    std::ofstream(scene) << text;
    return test::input_error_of([&] { load_cloth_scene(scene); });
  };
  EXPECT_NE(
      error_of(R"({"cloth": {"grid": {}, "thickness": {"mm": 5, "min_mm": 6}}})").find("min_mm"),
      std::string::npos);
  EXPECT_NE(error_of(R"({"cloth": {"grid": {}, "thickness": {"t_skin": 20, "t_env": 20}}})")
                .find("thickness"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"cloth": {"grid": {}, "thickness": "thick"}})").find("heat"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"cloth": {"grid": {}}, "cloths": []})").find("exactly one"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"cloths": [{"chain": {}, "total_mass": 1}]})").find("chain"),
            std::string::npos);
}

TEST(Layers, EveryExampleSceneLoads) {
  int scenes = 0, double_layers = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(
           std::string(DRESSKIT_SOURCE_DIR) + "/examples")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const ClothScene s = load_cloth_scene(entry.path().string());
    EXPECT_GT(s.model.rest_positions.rows(), 0);
    for (const GarmentInfo& g : s.garments) double_layers += g.double_layer;
    ++scenes;
  }
  EXPECT_GE(scenes, 15);
  EXPECT_EQ(double_layers, 7);  // four fabrics on the sphere, the pillow, two stacked scenes
}
