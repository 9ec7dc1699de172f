// Tests on the real meshes of ../shared/data (DRESSKIT_DATA_DIR).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/topology.h"
#include "dresskit/testing/expect.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::mesh;

namespace {
// An independent reading of an OBJ's `v` and `f` lines (0-based): per triangle the loader should
// make, in order, the corners of the polygon it comes from.
struct PlainObj {
  std::vector<Eigen::RowVector3d> v;
  std::vector<std::vector<int>> f;
};
PlainObj read_plain_obj(const std::string& path) {
  PlainObj obj;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v") {
      Eigen::RowVector3d p;
      s >> p(0) >> p(1) >> p(2);
      obj.v.push_back(p);
    } else if (tag == "f") {
      std::vector<int> idx;
      std::string corner;
      while (s >> corner) idx.push_back(std::stoi(corner.substr(0, corner.find('/'))) - 1);
      for (size_t k = 1; k + 1 < idx.size(); ++k) obj.f.push_back(idx);
    }
  }
  return obj;
}

struct DataMesh {
  const char* path;
  const char* units;
};
const DataMesh kObjFiles[] = {
    {"bodies/gc_mean_all.obj", "m"},
    {"bodies/gc_mean_all_tpose.obj", "m"},
    {"bodies/mh_woman_young_average.obj", "dm"},
    {"bodies/mh_man_young_average.obj", "dm"},
    {"bodies/mh_girl_child_11y.obj", "dm"},
    {"garments/mh_female_casualsuit01.obj", "dm"},
    {"garments/mh_female_elegantsuit01.obj", "dm"},
    {"garments/mh_male_casualsuit02.obj", "dm"},
    {"garments/gpg_tee_before_sim.obj", "0.0033333333333333335"},
    {"reference/gpg_tee_sim.obj", "0.0033333333333333335"},
    {"reference/female_elegantsuit01__on__mh_woman_young_average.obj", "dm"},
};

TriangleMesh load(const DataMesh& d) {
  LoadOptions options;
  options.units = Units::parse(d.units);
  return load_mesh(test::data_dir() + "/" + d.path, options);
}
}  // namespace

class ObjFile : public ::testing::TestWithParam<DataMesh> {};

TEST_P(ObjFile, VerticesAndFacesAreInTheFilesOwnOrder) {
  DRESSKIT_REQUIRE_DATA();
  const DataMesh& d = GetParam();
  const TriangleMesh m = load(d);
  const PlainObj plain = read_plain_obj(test::data_dir() + "/" + d.path);
  const double scale = Units::parse(d.units).metres_per_unit;
  ASSERT_EQ(m.num_vertices(), static_cast<int>(plain.v.size()));
  for (int i = 0; i < m.num_vertices(); ++i) {
    ASSERT_TRUE(m.V.row(i).isApprox(plain.v[i] * scale, 1e-12)) << "vertex " << i;
  }
  // Faces: in the file's order, each triangle over corners of its polygon (duplicate positions may
  // map to the first of their `v` lines, so compare positions rather than indices).
  ASSERT_EQ(m.num_faces(), static_cast<int>(plain.f.size()));
  for (int f = 0; f < m.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto& polygon = plain.f[static_cast<size_t>(f)];
      ASSERT_TRUE(std::any_of(polygon.begin(), polygon.end(), [&](int c) { return m.V.row(m.F(f, k)) == m.V.row(c); }))
          << "face " << f;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Data, ObjFile, ::testing::ValuesIn(kObjFiles), [](const auto& info) {
  std::string n = info.param.path;
  for (auto& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return n;
});

class Body : public ::testing::TestWithParam<DataMesh> {};

TEST_P(Body, CleanupGivesAClosedManifoldOutwardBody) {
  DRESSKIT_REQUIRE_DATA();
  const TriangleMesh m = load(GetParam());
  const CleanupResult r = cleanup_mesh(m);
  const TopologyReport t = analyse_topology(r.mesh);
  test::expect_closed_outward(t);
  // A human body of 1.1–2 m height and a plausible volume (0.02–0.15 m³).
  test::expect_between(bounding_box(r.mesh).sizes().y(), 1.1, 2.0, "height [m]");
  test::expect_between(t.signed_volume, 0.02, 0.15, "volume [m³]");
  // Quads of MakeHuman bodies survive cleanup, and every vertex keeps its file index.
  if (m.quads.rows() > 0) {
    EXPECT_GT(r.mesh.quads.rows(), m.quads.rows() * 99 / 100);
  }
  EXPECT_EQ((r.mesh.source_vertex.array() < 0).count(), 0);
}

INSTANTIATE_TEST_SUITE_P(Data, Body, ::testing::ValuesIn(kObjFiles, kObjFiles + 5),
                         [](const auto& info) {
                           std::string n = info.param.path;
                           for (auto& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return n;
                         });

TEST(RealData, BodyLabelsFollowTheFileOrderThroughCleanup) {
  DRESSKIT_REQUIRE_DATA();
  const TriangleMesh body = load({"bodies/mh_woman_young_average.obj", "dm"});
  std::ifstream in(test::data_dir() + "/labels/mh_body_part_labels.json");
  const auto j = nlohmann::json::parse(in);
  const auto names = j["labels"].get<std::vector<std::string>>();
  ASSERT_EQ(static_cast<int>(names.size()), body.num_vertices());
  const CleanupResult r = cleanup_mesh(body);
  // Left (+X) arm vertices, found through source_vertex, lie at positive x; right at negative x.
  double left = 0, right = 0;
  int nl = 0, nr = 0;
  for (int i = 0; i < r.mesh.num_vertices(); ++i) {
    const std::string& name = names[r.mesh.source_vertex(i)];
    if (name == "arm_left") left += r.mesh.V(i, 0), ++nl;
    if (name == "arm_right") right += r.mesh.V(i, 0), ++nr;
  }
  ASSERT_GT(nl, 100);
  ASSERT_GT(nr, 100);
  EXPECT_GT(left / nl, 0.25);   // arms are well away from the midline [m]
  EXPECT_LT(right / nr, -0.25);
}

TEST(RealData, ObjRoundTripOfARealBodyIsExact) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  const TriangleMesh m = load({"bodies/mh_man_young_average.obj", "dm"});
  save_mesh(m, dir.file("man.obj"));
  const TriangleMesh back = load_mesh(dir.file("man.obj"));
  EXPECT_EQ(back.V, m.V);
  EXPECT_EQ(back.quads, m.quads);
}
