// The shared patterns sewn and dressed on gc_mean_all and on other bodies: stitches closed, nothing
// inside the body (checked by winding numbers, independently of the simulator's distance field), no
// crossings (the shirt: its measured few), the garment worn rather than hanging in the air, panel
// areas kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <nlohmann/json.hpp>

#include "dresskit/cloth/self_collision.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/io.h"
#include "dresskit/pattern/cut.h"
#include "dresskit/pattern/pattern.h"
#include "dresskit/testing/winding_number.h"
#include "pattern_fixtures.h"
#include "tools/cli_run.h"

using namespace dresskit::cloth;
using namespace dresskit::dressing;
using namespace dresskit::mesh;

namespace dresskit {
namespace {

/// Distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

double distance_to(const TriangleMesh& m, const Eigen::Vector3d& p) {
  double best = 1e30;
  for (int f = 0; f < m.num_faces(); ++f)
    best = std::min(best, point_triangle_distance(p, m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)),
                                                  m.V.row(m.F(f, 2))));
  return best;
}

struct Worn {
  int deep_inside = 0;         ///< vertices deeper than 2 mm inside the body
  double near_fraction = 0.0;  ///< of vertices within 8 cm of the body
};

/// Independent of the toolkit's distance fields: a vertex is inside when its winding number with
/// respect to the body is above one half; its depth is its distance to the body's triangles by
/// brute force. Nearness: brute force distance on a subsample of every 7th vertex.
Worn worn(const TriangleMesh& body, const Eigen::MatrixX3d& x) {
  Worn w;
  int near = 0, sampled = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const Eigen::Vector3d p = x.row(i).transpose();
    if (std::abs(test::winding_number(body, p)) > 0.5 && distance_to(body, p) > 0.002)
      ++w.deep_inside;
    if (i % 7 == 0) {
      ++sampled;
      near += distance_to(body, p) <= 0.08;
    }
  }
  w.near_fraction = double(near) / sampled;
  return w;
}

struct SharedPattern {
  std::string name, file;
  double max_gap;                    ///< [m] sewn pairs' largest distance before welding
  int max_crossings;                 ///< the garment's own crossings once dressed
  std::string body = "gc_mean_all";  ///< in ../shared/data/bodies
  std::string body_units = "m";
  bool moved = false;            ///< carried from the pattern's body to this one before sewing
  std::string method = "drawn";  ///< how the seams closed
  /// Share of the garment's vertices within 8 cm of the body at least (a garment made for a larger
  /// body hangs looser).
  double min_near = 0.95;
  /// The body the pattern is placed around, in ../shared/data/bodies (metres): carried by parts
  /// rather than by frames ("": none).
  std::string pattern_body = "";
};

void PrintTo(const SharedPattern& p, std::ostream* os) { *os << p.name; }

// Layers inferred for a sewn hoody and a mesh suit of t-shirt and jeans given the other way round:
// both are tops (the hoody's panels are a bodice and sleeves, though its hanging sleeves are cut as
// legs), the suit covers the legs and so goes under the hoody, which is graded over it. (Graded
// over the suit carried from its wearer, the hoody still crosses it: the order is tested here, the
// crossings between the layers by the matrix benchmark's two-outfit cases.)
TEST(PatternDress, InferredLayersPutASewnTopOverASuit) {
  DRESSKIT_REQUIRE_DATA();
  GarmentFile hoody, suit;
  hoody.file = MeshFile::file(test::shared_pattern("gc_hoody_mean_specification.json"));
  suit.file = MeshFile::file(test::data_dir() + "/garments/mh_female_casualsuit01.obj");
  suit.file.load.units = Units::parse("dm");
  DressOptions o;
  o.settle = false;
  o.infer_layers = true;
  const DressResult r = dress(MeshFile::file(test::data_dir() + "/bodies/gc_mean_all.obj"), {hoody, suit}, o);
  ASSERT_EQ(r.garments.size(), 2u);
  EXPECT_EQ(r.garments[0].name, "mh_female_casualsuit01");
  EXPECT_EQ(r.garments[1].name, "gc_hoody_mean_specification");
  const auto grading = std::find_if(r.stages.begin(), r.stages.end(), [](const DressStage& s) { return s.name == "grading"; });
  ASSERT_NE(grading, r.stages.end());
  EXPECT_TRUE(grading->ran);
}

// The shirt carried by parts to MakeHuman's woman, her vertices moved by a picometre (the second
// trial of bench_pattern): settled with the springs held at their length limit left out of the
// adaptive step's rise, it crosses itself (6 times); settled again judging them, not at all, and that
// run is kept.
TEST(PatternDress, ASettleThatCrossesItselfRunsAgainJudgingHeldSprings) {
  DRESSKIT_REQUIRE_DATA();
  const std::string path = test::data_dir() + "/bodies/mh_woman_young_average.obj";
  LoadOptions load;
  load.units = Units::parse("dm");
  TriangleMesh body = load_mesh(path, load);
  for (Eigen::Index v = 0; v < body.V.rows(); ++v)
    body.V(v, (v * 7) % 3) += 1e-12 * std::sin(1.7 * static_cast<double>(v));
  GarmentFile g;
  g.file = MeshFile::file(test::shared_pattern("gc_shirt_mean_specification.json"));
  g.pattern_body = MeshFile::file(test::data_dir() + "/bodies/gc_mean_all.obj");
  const DressResult r = dress(MeshFile::given(path, body), {g});
  ASSERT_TRUE(r.settled);
  EXPECT_TRUE(r.settle.ok) << r.settle.failure;
  const auto settle = std::find_if(r.stages.begin(), r.stages.end(), [](const DressStage& s) { return s.name == "settle"; });
  ASSERT_NE(settle, r.stages.end());
  std::cout << settle->reason << "\n";
  const std::string retried = "settled again judging the springs held at their length limit (";
  const std::size_t at = settle->reason.find(retried);
  ASSERT_NE(at, std::string::npos) << settle->reason;
  const std::size_t from = at + retried.size();
  const std::string verdict = settle->reason.substr(from, settle->reason.find(')', from) - from);  // "6 → 0 crossings"
  EXPECT_NE(verdict.find(" → 0 crossings"), std::string::npos) << settle->reason;
  EXPECT_EQ(r.garments[0].crossings_dressed, 0);
  EXPECT_EQ(count_intersections(r.garments[0].dressed, r.garments[0].mesh.F), 0);
}

class PatternDress : public ::testing::TestWithParam<SharedPattern> {};

TEST_P(PatternDress, SewnClosedWornAndAreasKept) {
  DRESSKIT_REQUIRE_DATA();
  const SharedPattern& c = GetParam();
  MeshFile body = MeshFile::file(test::data_dir() + "/bodies/" + c.body + ".obj");
  body.load.units = Units::parse(c.body_units);
  GarmentFile g;
  g.file = MeshFile::file(test::shared_pattern(c.file));
  if (!c.pattern_body.empty())
    g.pattern_body = MeshFile::file(test::data_dir() + "/bodies/" + c.pattern_body + ".obj");
  const DressResult r = dress(body, {g});
  ASSERT_EQ(r.garments.size(), 1u);
  const DressedGarment& d = r.garments[0];
  ASSERT_TRUE(d.from_pattern);
  ASSERT_TRUE(r.settled);
  EXPECT_TRUE(r.settle.ok) << r.settle.failure;
  // Every stitch pair came within 1 mm and was held there (sewn), then welded.
  EXPECT_TRUE(d.pattern.closed);
  EXPECT_EQ(d.pattern.sewn_pairs, d.pattern.stitch_pairs);
  EXPECT_EQ(d.pattern.sew_method, c.method);
  EXPECT_LE(d.pattern.max_gap, c.max_gap);
  EXPECT_GT(d.pattern.stitch_pairs, 100);
  // Carried to another body only: MakeHuman's bodies stand 0.8 m lower than the pattern's; their
  // frames lie 11–15 cm further forward (their hands, held in front, count in the frame's box),
  // their torsos 2–4 cm.
  if (c.moved) {
    EXPECT_LT(d.pattern.moved_by.y(), -0.5) << c.name;
    EXPECT_EQ(d.pattern.carried_by, c.pattern_body.empty() ? "frames" : "parts") << c.name;
    if (c.pattern_body.empty()) {
      EXPECT_GT(d.pattern.moved_by.z(), 0.05) << c.name;
    } else {
      EXPECT_GT(d.pattern.moved_by.z(), 0.0) << c.name;  // forward with the torso, a few cm
      EXPECT_LT(d.pattern.moved_by.z(), 0.08) << c.name;
      ASSERT_EQ(d.pattern.panel_parts.size(), d.pattern.panels.size());
      for (std::size_t k = 0; k < d.pattern.panels.size(); ++k)
        EXPECT_EQ(d.pattern.panel_parts[k].rfind("arm", 0) == 0,
                  d.pattern.panels[k].find("sleeve") != std::string::npos)
            << d.pattern.panels[k] << " " << d.pattern.panel_parts[k];
    }
  } else {
    EXPECT_EQ(d.pattern.moved_by, Eigen::Vector3d::Zero()) << c.name;
    EXPECT_EQ(d.pattern.carried_by, "as placed") << c.name;
  }
  // Each hangs from the shoulders: none is held by a waistband while settling (the hoody and the
  // sleeveless dress have skirt parts).
  EXPECT_EQ(d.waistband_vertices, 0) << c.name;
  // Worn: nothing deeper than 2 mm in the body, ≥ 95 % of the garment within 8 cm of it (the
  // pencil dress on the smaller woman: 90 %, measured 91 %).
  const Worn w = worn(r.body, d.dressed);
  EXPECT_EQ(w.deep_inside, 0) << c.name;
  EXPECT_GE(w.near_fraction, c.min_near) << c.name;
  // No triangle pair of the garment crosses another (the shirt: a few under its arms).
  EXPECT_LE(count_intersections(d.dressed, d.mesh.F), c.max_crossings) << c.name;
  // Pairs left unwelded (a fold between their sides) are held together by seams while settling.
  for (const auto& [a, b] : d.pattern.unwelded)
    EXPECT_LT((d.dressed.row(a) - d.dressed.row(b)).norm(), 0.003) << c.name << " " << a << "-" << b;
  // Panel areas within 3 % of the flat pattern's.
  ASSERT_EQ(d.pattern.panel_area_dressed.size(), d.pattern.panels.size());
  for (std::size_t k = 0; k < d.pattern.panels.size(); ++k)
    EXPECT_NEAR(d.pattern.panel_area_dressed[k] / d.pattern.panel_area[k], 1.0, 0.03)
        << c.name << " " << d.pattern.panels[k];
}

// The three shared patterns on their body (the pencil dress's bodice sewn first, then its skirt),
// and carried to MakeHuman's young man and woman (in dm, standing elsewhere, of other heights; on
// the woman, drawing leaves the shirt's pairs open and seam forces close them). The shirt's sewn
// pairs end up to 1.8 mm apart where its side seams meet its sleeves, with a fold of cloth between
// some (left unwelded) (docs/pattern.md). The shirt on the young man, whose frames leave a shoulder
// seam open, is carried by parts from GarmentCode's body, its sleeves turned to his arms and its
// panels kept as far from him as from that body: sewn by drawing, its pairs held up to 2.8 mm
// apart.
INSTANTIATE_TEST_SUITE_P(
    Shared, PatternDress,
    ::testing::Values(SharedPattern{"hoody", "gc_hoody_mean_specification.json", 0.001, 0},
                      SharedPattern{"shirt", "gc_shirt_mean_specification.json", 0.002, 0},
                      SharedPattern{"pencil_dress", "gc_dress_pencil_specification.json", 0.001, 0},
                      SharedPattern{"hoody_on_man", "gc_hoody_mean_specification.json", 0.001, 0,
                                    "mh_man_young_average", "dm", true},
                      SharedPattern{"shirt_on_woman", "gc_shirt_mean_specification.json", 0.002, 0,
                                    "mh_woman_young_average", "dm", true, "seam forces"},
                      SharedPattern{"pencil_dress_on_woman", "gc_dress_pencil_specification.json",
                                    0.001, 0, "mh_woman_young_average", "dm", true, "drawn", 0.9},
                      SharedPattern{"shirt_on_man_by_parts", "gc_shirt_mean_specification.json", 0.003,
                                    0, "mh_man_young_average", "dm", true, "drawn", 0.95, "gc_mean_all"}),
    [](const auto& info) { return info.param.name; });

TEST(PatternDressCli, DressBodyPatternWritesOutputsAndSeams) {
  DRESSKIT_REQUIRE_DATA();
  using namespace test::cli;
  test::TempDir dir;
  const std::string out = dir.file("hoody");
  const CliRun r = run(dir, "dress " + test::data_dir() + "/bodies/gc_mean_all.obj " +
                                test::shared_pattern("gc_hoody_mean_specification.json") + " -o " +
                                out + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string stem = "gc_hoody_mean_specification";
  for (const std::string& f : {stem + ".dressed.obj", stem + ".placed.obj",
                               std::string("dressed.glb"), std::string("report.json")})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  const auto j = nlohmann::json::parse(slurp(out + "/report.json"));
  const auto& g = j["garments"][0];
  EXPECT_EQ(g["name"], stem);
  EXPECT_EQ(g["seams"]["count"], 12);
  EXPECT_LE(g["seams"]["max_gap_m"].get<double>(), 0.001);
  EXPECT_EQ(g["seams"]["sewn_pairs"], g["seams"]["pairs"]);
  EXPECT_EQ(g["seams"]["method"], "drawn");
  EXPECT_EQ(g["panels"].size(), 6u);
  EXPECT_EQ(g["panels"][0]["name"], "left_btorso");
  const TriangleMesh dressed = load_mesh(out + "/" + stem + ".dressed.obj");
  EXPECT_EQ(dressed.num_faces(), g["pattern"]["triangles"].get<int>());
  // Texture coordinates: the flat pattern, one per cut vertex (the panels' own, also where seams
  // join them), every triangle the right way round seen from outside, of its flat shape: the
  // triangles' total area in the texture is the panels', and each dressed edge is as long as its
  // texture edge within the fabric's strain.
  {
    const dresskit::pattern::Pattern p =
        dresskit::pattern::read_pattern(test::shared_pattern("gc_hoody_mean_specification.json"));
    const dresskit::pattern::CutPattern cut = dresskit::pattern::cut_pattern(p);
    std::ifstream in(out + "/" + stem + ".dressed.obj");
    std::vector<Eigen::Vector2d> tc;
    std::vector<std::array<int, 6>> corners;  // v, vt per corner
    std::map<std::string, int> group_faces;   // faces under each `g` line's panel
    std::string group;
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      std::string key;
      words >> key;
      if (key == "g") {
        words >> group;
      } else if (key == "vt") {
        Eigen::Vector2d t;
        words >> t.x() >> t.y();
        tc.push_back(t);
      } else if (key == "f") {
        std::array<int, 6> c{};
        char slash;
        for (int k = 0; k < 3; ++k) words >> c[2 * k] >> slash >> c[2 * k + 1];
        ASSERT_FALSE(words.fail()) << line;
        corners.push_back(c);
        ++group_faces[group];
      }
    }
    EXPECT_EQ(tc.size(), std::size_t(cut.flat.rows()));
    // A group per panel, holding that panel's triangles.
    ASSERT_EQ(group_faces.size(), p.panels.size());
    for (std::size_t k = 0; k < p.panels.size(); ++k)
      EXPECT_EQ(group_faces[p.panels[k].name], (cut.panel_of_face.array() == int(k)).count()) << p.panels[k].name;
    ASSERT_EQ(corners.size(), std::size_t(dressed.num_faces()));
    double area = 0.0;
    int backwards = 0;
    std::vector<double> stretch;
    for (const auto& c : corners) {
      const Eigen::Vector2d a = tc[c[1] - 1], b = tc[c[3] - 1], d = tc[c[5] - 1];
      const double twice = (b - a).x() * (d - a).y() - (b - a).y() * (d - a).x();
      area += 0.5 * twice;
      backwards += twice <= 0.0;
      for (int k = 0; k < 3; ++k) {
        const int u = c[2 * k] - 1, v = c[2 * ((k + 1) % 3)] - 1;
        const double flat = (tc[c[2 * ((k + 1) % 3) + 1] - 1] - tc[c[2 * k + 1] - 1]).norm();
        stretch.push_back((dressed.V.row(u) - dressed.V.row(v)).norm() / flat - 1.0);
      }
    }
    EXPECT_EQ(backwards, 0);
    EXPECT_NEAR(area, cut.triangle_area.sum(), 0.002 * cut.triangle_area.sum());
    std::sort(stretch.begin(), stretch.end());
    EXPECT_LT(std::abs(stretch[stretch.size() / 2]), 0.05);  // median
    EXPECT_LT(stretch.back(), 0.12);                          // within the length limits
  }
  // A bad pattern: exit 2, one line naming the stitch, nothing written.
  write(dir.file("bad.json"),
        test::two_panel_pattern(
            "{\"endpoints\": [1, 2]}",
            R"([[{"panel": "front", "edge": 1}, {"panel": "cuff", "edge": 0}]])"));
  const CliRun bad = run(dir, "dress " + test::data_dir() + "/bodies/gc_mean_all.obj " +
                                  dir.file("bad.json") + " -o " + dir.file("bad_out"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("stitch 0: panel 'cuff' does not exist"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad_out")));
  // A body in the wrong units is said before sewing (not as a seam left open minutes later).
  const CliRun units = run(dir, "dress " + test::data_dir() + "/bodies/gc_mean_all.obj " +
                                    test::shared_pattern("gc_hoody_mean_specification.json") +
                                    " --body-units cm -o " + dir.file("units_out"));
  EXPECT_EQ(units.code, 2);
  EXPECT_NE(units.err.find("the body is 0.0172 m tall in units cm; with --body-units m it would be 1.72 m"),
            std::string::npos)
      << units.err;
  EXPECT_EQ(units.err.find("sewing"), std::string::npos) << units.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("units_out")));
}

// A pattern has no 3D units of its own: sewn around a body given in centimetres, its outputs are in
// centimetres too, lying on the body as read.
TEST(PatternDressCli, APatternsOutputsAreInTheBodysUnits) {
  DRESSKIT_REQUIRE_DATA();
  using namespace test::cli;
  test::TempDir dir;
  TriangleMesh body = load_mesh(test::data_dir() + "/bodies/gc_mean_all.obj");
  body.V *= 100.0;
  save_mesh(body, dir.file("body_cm.obj"));
  const std::string out = dir.file("out");
  const CliRun r = run(dir, "dress " + dir.file("body_cm.obj") + " " +
                                test::shared_pattern("gc_hoody_mean_specification.json") +
                                " --body-units cm --no-settle -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_EQ(j["garments"][0]["units"], "cm");
  const TriangleMesh hoody = load_mesh(out + "/gc_hoody_mean_specification.placed.obj");
  // The hood's top is at the top of the head (172 cm), within a few centimetres; in metres it would
  // be at 1.7.
  EXPECT_NEAR(hoody.V.col(1).maxCoeff(), body.V.col(1).maxCoeff(), 5.0);
}

// A pattern whose panels are placed two metres beside the body sews shut in the air: the garment is
// not on the body, and the pattern is refused as placed for another body (exit 2, report.html alone).
TEST(PatternDressCli, APatternPlacedForAnotherBodyIsRefused) {
  DRESSKIT_REQUIRE_DATA();
  using namespace test::cli;
  test::TempDir dir;
  std::string far = test::two_panel_pattern();
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"[-20, 80, 15]", "[180, 80, 15]"},
        {"[20, 80, -15]", "[220, 80, -15]"}}) {
    const auto at = far.find(from);
    ASSERT_NE(at, std::string::npos);
    far.replace(at, from.size(), to);
  }
  write(dir.file("far.json"), far);
  const CliRun r = run(dir, "dress " + test::data_dir() + "/bodies/gc_mean_all.obj " +
                                dir.file("far.json") + " -o " + dir.file("out"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("far.json: sewn around this body, the garment is not on it"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the pattern is placed for another body"), std::string::npos) << r.err;
  // Refused by placement, after the pattern was sewn: report.html alone shows what was tried.
  EXPECT_NE(r.err.find("(only " + dir.file("out") + "/report.html written: what was tried)"), std::string::npos) << r.err;
  std::vector<std::string> written;
  for (const auto& e : std::filesystem::directory_iterator(dir.file("out")))
    if (e.path().filename().string()[0] != '.') written.push_back(e.path().filename().string());
  EXPECT_EQ(written, std::vector<std::string>{"report.html"});
}

// A pattern's body that is missing, or whose units make it 17 m tall: exit 2, one line naming the
// file and what is wrong, nothing written.
TEST(PatternDressCli, ABadPatternBodyIsRefusedNamingIt) {
  DRESSKIT_REQUIRE_DATA();
  using namespace test::cli;
  test::TempDir dir;
  const std::string dress = "dress " + test::data_dir() + "/bodies/gc_mean_all.obj " +
                            test::shared_pattern("gc_hoody_mean_specification.json") + " -o " + dir.file("out");
  const CliRun missing = run(dir, dress + " --pattern-body " + dir.file("nobody.obj"));
  EXPECT_EQ(missing.code, 2) << missing.err;
  EXPECT_NE(missing.err.find("nobody.obj"), std::string::npos) << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  const std::string man = test::data_dir() + "/bodies/mh_man_young_average.obj";  // in dm
  const CliRun tall = run(dir, dress + " --pattern-body " + man);
  EXPECT_EQ(tall.code, 2) << tall.err;
  EXPECT_NE(tall.err.find(man + ": the pattern's body is 17.5 m tall in units m; with --pattern-body-units dm it "
                                "would be 1.75 m"),
            std::string::npos)
      << tall.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

}  // namespace
}  // namespace dresskit
