// dress-a-mesh end to end: exit codes, one-line errors naming the file, no partial output, inputs
// never overwritten.
#include <gtest/gtest.h>

#include <regex>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../mesh/mesh_fixtures.h"
#include "cloth/collision_helpers.h"
#include "dresskit/mesh/io.h"
#include "test_data.h"
#include "tools/cli_run.h"

using namespace dresskit;
using namespace dresskit::mesh;

using namespace dresskit::test::cli;

TEST(Cli, VersionAndHelp) {
  test::TempDir dir;
  CliRun r = run(dir, "--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("dress-a-mesh 0."), std::string::npos);
  for (const char* sub : {"info", "clean", "demo"}) {
    r = run(dir, std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("--"), std::string::npos) << sub;
  }
}

TEST(Cli, UsageErrorsExit64) {
  test::TempDir dir;
  EXPECT_EQ(run(dir, "").code, 64);
  EXPECT_EQ(run(dir, "frobnicate").code, 64);
  const CliRun r = run(dir, "info");
  EXPECT_EQ(r.code, 64);
  EXPECT_EQ(lines(r.err), 1) << r.err;
}

// A value its option's check refuses is bad input, not a usage error: exit 2, one line naming it.
TEST(Cli, OptionValuesOutOfRangeExit2NamingTheOption) {
  test::TempDir dir;
  save_mesh(fixtures::cube(1.0), dir.file("in.obj"));
  for (const auto& [args, option] : std::vector<std::pair<std::string, std::string>>{
           {"clean " + dir.file("in.obj") + " -o " + dir.file("out.obj") + " --remesh -1", "--remesh: -1 is not a positive number"},
           {"pattern " + dir.file("p.json") + " -o " + dir.file("p") + " --length-ratio 0.5", "--length-ratio"},
           {"dress " + dir.file("in.obj") + " " + dir.file("in.obj") + " -o " + dir.file("p") + " --quality best", "--quality"},
           {"demo -o " + dir.file("p") + " --quality best", "--quality"},
           {"dress " + dir.file("in.obj") + " " + dir.file("in.obj") + " -o " + dir.file("p") + " --fabric silk", "--fabric"}}) {
    const CliRun r = run(dir, args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.obj")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("p")));
}

TEST(Cli, InfoTextAndJson) {
  test::TempDir dir;
  save_mesh(fixtures::cube(10.0), dir.file("cube.obj"));
  CliRun r = run(dir, "info " + dir.file("cube.obj") + " --units cm");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("closed: yes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("components: 1"), std::string::npos);
  r = run(dir, "info " + dir.file("cube.obj") + " --units cm --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 8);
  EXPECT_EQ(j["faces"], 12);
  EXPECT_EQ(j["quads"], 6);
  EXPECT_EQ(j["boundary_loops"], 0);
  EXPECT_TRUE(j["outward"].get<bool>());
  EXPECT_NEAR(j["volume_m3"].get<double>(), 0.001, 1e-12);  // 10 cm cube
  EXPECT_NEAR(j["bounding_box_m"]["max"][0].get<double>(), 0.05, 1e-12);
}

TEST(Cli, CleanWritesTheRepairedMeshAndSaysWhatItFixed) {
  test::TempDir dir;
  TriangleMesh m = fixtures::cube(1.0);
  std::swap(m.F(0, 1), m.F(0, 2));
  m.quads.resize(0, 4);
  save_mesh(m, dir.file("in.obj"));
  const std::string before = slurp(dir.file("in.obj"));
  const CliRun r = run(dir, "clean " + dir.file("in.obj") + " -o " + dir.file("out.ply"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("1 faces reoriented"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("closed and outward"), std::string::npos) << r.out;
  EXPECT_EQ(slurp(dir.file("in.obj")), before);  // input untouched
  EXPECT_EQ(load_mesh(dir.file("out.ply")).num_faces(), 12);
}

TEST(Cli, CleanMakesTheFolderItsOutputGoesInto) {
  test::TempDir dir;
  save_mesh(fixtures::cube(1.0), dir.file("in.obj"));
  CliRun r = run(dir, "clean " + dir.file("in.obj") + " -o " + dir.file("new/sub/out.ply"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(load_mesh(dir.file("new/sub/out.ply")).num_faces(), 12);
  // Under a file no folder can be made: exit 3, nothing written.
  r = run(dir, "clean " + dir.file("in.obj") + " -o " + dir.file("in.obj") + "/sub/out.ply");
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.file("in.obj")));
}

TEST(Cli, CleanRefusesToOverwriteItsInput) {
  test::TempDir dir;
  save_mesh(fixtures::cube(1.0), dir.file("in.obj"));
  const std::string before = slurp(dir.file("in.obj"));
  const CliRun r = run(dir, "clean " + dir.file("in.obj") + " -o " + dir.file("in.obj"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1);
  EXPECT_NE(r.err.find("refusing to overwrite the input"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir.file("in.obj")), before);
}

// Every bad input: exit 2, one line on stderr naming the file, and no output file.
TEST(Cli, BadInputsExit2WithOneLineAndNoOutput) {
  test::TempDir dir;
  write(dir.file("empty.obj"), "");
  write(dir.file("nofaces.obj"), "v 0 0 0\nv 1 0 0\n");
  write(dir.file("nan.obj"), "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write(dir.file("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  write(dir.file("trunc.ply"),
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n\x01\x02");
  write(dir.file("mesh.txt"), "hello\n");
  // Files the fuzzers found assimp hanging on: a header's end followed by a vertical tab, and a
  // .glb with the word "ply" near its start (its glTF reader refused it, its PLY reader looped).
  write(dir.file("end_tab.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nend_header\v0 0 0\n1 0 0\n0 1 0\n");
  write(dir.file("ply_word.glb"), "ply\x01\xb4p\x01ply\nformat ascii 0.0\nele\n\x10ment vertex 3\nproperty list uchar ");
  for (const char* name : {"missing.obj", "empty.obj", "nofaces.obj", "nan.obj", "range.obj",
                           "trunc.ply", "mesh.txt", "end_tab.ply", "ply_word.glb"}) {
    const std::string in = dir.file(name), out = dir.file("out.obj");
    for (const std::string& cmd : {"info " + in, "clean " + in + " -o " + out}) {
      const CliRun r = run(dir, cmd);
      EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
      EXPECT_EQ(lines(r.err), 1) << cmd << "\n" << r.err;
      EXPECT_NE(r.err.find(in), std::string::npos) << r.err;
      EXPECT_FALSE(std::filesystem::exists(out)) << cmd;
    }
  }
  // Bad values of options name the value.
  save_mesh(fixtures::cube(1.0), dir.file("ok.obj"));
  CliRun r = run(dir, "info " + dir.file("ok.obj") + " --units furlong");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("furlong"), std::string::npos);
  r = run(dir, "clean " + dir.file("ok.obj") + " -o " + dir.file("out.xyz"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("out.xyz"), std::string::npos);
  r = run(dir, "demo -o " + dir.file("d") + " --height 9");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("height"), std::string::npos);
  r = run(dir, "demo -o " + dir.file("d") + " --ease 0.5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("ease"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.file("d")));
}

// The demo is the dressing pipeline run on meshes made in memory: it writes the made meshes, and the
// pipeline's outputs and report, in which segmentation and placement were left out (the parts come
// with the meshes, which are made on the mannequin) and settling kept the layers apart.
TEST(Cli, DemoDressesTheMannequinThroughThePipeline) {
  test::TempDir dir;
  const CliRun r = run(dir, "demo -o " + dir.file("demo") + " --edge 0.03");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* name : {"mannequin", "tshirt", "skirt", "trousers"}) {
    for (const char* ext : {"obj", "ply", "glb"}) {
      EXPECT_TRUE(std::filesystem::exists(dir.file("demo/" + std::string(name) + "." + ext)))
          << name << ext;
    }
  }
  const auto report = nlohmann::json::parse(slurp(dir.file("demo/report.json")));
  EXPECT_TRUE(report["meshes"]["mannequin"]["closed"].get<bool>());
  EXPECT_EQ(report["meshes"]["tshirt"]["boundary_loops"], 4);
  EXPECT_EQ(report["meshes"]["trousers"]["boundary_loops"], 3);
  EXPECT_EQ(report["meshes"]["skirt"]["boundary_loops"], 2);
  EXPECT_EQ(load_mesh(dir.file("demo/mannequin.glb")).num_faces(),
            report["meshes"]["mannequin"]["faces"].get<int>());
  std::map<std::string, bool> ran;
  for (const auto& s : report["stages"]) ran[s["name"].get<std::string>()] = s["ran"].get<bool>();
  EXPECT_FALSE(ran.at("segmentation"));
  EXPECT_FALSE(ran.at("placement"));
  EXPECT_TRUE(ran.at("settle"));
  EXPECT_TRUE(ran.at("write"));
  EXPECT_EQ(report["settle"]["stopped_reason"], "duration reached");
  EXPECT_EQ(report["layers"]["crossings_between"], 0);
  ASSERT_EQ(report["garments"].size(), 2u);
  EXPECT_EQ(report["garments"][0]["name"], "trousers");
  EXPECT_GT(report["garments"][0]["waistband_vertices"].get<int>(), 10);
  for (const auto& g : report["garments"]) {
    EXPECT_EQ(g["crossings"]["dressed"], 0) << g["name"];
    EXPECT_EQ(g["vertices_inside_body_2mm"]["dressed"], 0) << g["name"];
    EXPECT_LT(g["max_strain"].get<double>(), 0.15) << g["name"];
  }
  // The outfit settled: the t-shirt sinks onto the shoulders, no higher than it was made.
  const TriangleMesh made = load_mesh(dir.file("demo/tshirt.obj"));
  const TriangleMesh dressed = load_mesh(dir.file("demo/tshirt.dressed.obj"));
  ASSERT_EQ(dressed.num_vertices(), made.num_vertices());
  EXPECT_LT(dressed.V.col(1).maxCoeff(), made.V.col(1).maxCoeff() + 0.002);
  EXPECT_GT((dressed.V - made.V).rowwise().norm().maxCoeff(), 0.002);
  // The dressed scene holds the mannequin and both garments.
  EXPECT_EQ(load_mesh(dir.file("demo/dressed.glb")).num_vertices(),
            report["meshes"]["mannequin"]["vertices"].get<int>() + made.num_vertices() +
                load_mesh(dir.file("demo/trousers.dressed.obj")).num_vertices());
  // A bad value: one line, exit 2, nothing written.
  const CliRun bad = run(dir, "demo -o " + dir.file("bad") + " --dress-seconds -1");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(lines(bad.err), 1) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad")));
}

TEST(Cli, SimulateWritesResultFramesAndReport) {
  test::TempDir dir;
  write(dir.file("chain.json"),
        R"({"cloth": {"chain": {"particles": 10, "spacing": 0.05, "top": [0, 1, 0],
    "direction": [1, 0, 0]}, "total_mass": 0.1, "stiffness": 100, "pins": [0]},
    "simulation": {"dt": 0.005, "duration": 0.5, "fps": 10, "air_damping": 0.5}})");
  const CliRun r =
      run(dir, "simulate " + dir.file("chain.json") + " -o " + dir.file("out") + " --frames");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto report = nlohmann::json::parse(slurp(dir.file("out/report.json")));
  for (const char* key :
       {"integrator", "dt", "steps", "frames", "wall_seconds", "seconds_per_frame", "max_strain",
        "mean_strain", "energy_history", "final_residual", "stopped_reason", "nan_detected"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  EXPECT_EQ(report["steps"], 100);
  EXPECT_EQ(report["frames"], 5);
  EXPECT_FALSE(report["nan_detected"].get<bool>());
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/result.obj")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/frame_00005.obj")));
  // A shorter run into the same folder leaves only its own frames (and a file of the user's).
  write(dir.file("out/notes.txt"), "mine");
  write(dir.file("chain.json"), std::regex_replace(slurp(dir.file("chain.json")), std::regex("0\\.5, \"fps"),
                                                   "0.2, \"fps"));
  const CliRun shorter =
      run(dir, "simulate " + dir.file("chain.json") + " -o " + dir.file("out") + " --frames");
  ASSERT_EQ(shorter.code, 0) << shorter.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir.file("out/report.json")))["frames"], 2);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/frame_00002.obj")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/frame_00003.obj")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/notes.txt")));
}

// Symplectic Euler at 1/25 s, far beyond its stability limit for denim: with a fixed step it blows
// up (the last good state is written, the message names the spring, its strain and the time, exit
// 4); named without "adaptive": false it takes the stable step it needs and finishes.
TEST(Cli, SimulateBlowUpKeepsTheLastGoodStateAndExits4) {
  test::TempDir dir;
  const std::string cloth = R"("cloth": {"grid": {"size": [0.5, 0.5], "resolution": [8, 8]},
    "fabric": "11oz-black-denim", "pins": [[0, 7], [7, 7]]})";
  write(dir.file("stiff.json"), "{" + cloth + R"(, "simulation": {"integrator": "symplectic", "dt": 0.04,
    "adaptive": false, "strain_limiting": false, "duration": 1.0}})");
  CliRun r = run(dir, "simulate " + dir.file("stiff.json") + " -o " + dir.file("out"));
  EXPECT_EQ(r.code, 4) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  for (const char* word : {"blow-up at t = 0.0800 s", "structural spring", "particles", "strained", "by the integrator"})
    EXPECT_NE(r.err.find(word), std::string::npos) << word << " in " << r.err;
  const std::string obj = slurp(dir.file("out/result.obj"));
  EXPECT_EQ(obj.find("nan"), std::string::npos);
  auto report = nlohmann::json::parse(slurp(dir.file("out/report.json")));
  EXPECT_NE(report["stopped_reason"].get<std::string>().find("failed"), std::string::npos);

  write(dir.file("named.json"), "{" + cloth + R"(, "simulation": {"integrator": "symplectic", "dt": 0.04,
    "duration": 0.25}})");
  r = run(dir, "simulate " + dir.file("named.json") + " -o " + dir.file("named"));
  ASSERT_EQ(r.code, 0) << r.err;
  report = nlohmann::json::parse(slurp(dir.file("named/report.json")));
  EXPECT_LT(report["smallest_dt"].get<double>(), 0.04 / 16);  // the stability bound's substeps
  EXPECT_LE(report["max_strain"].get<double>(), 0.1 + 1e-3);
}

TEST(Cli, SimulateBadSceneExits2NamingTheKey) {
  test::TempDir dir;
  write(dir.file("bad.json"),
        R"({"cloth": {"grid": {"size": [1, 1], "resolution": [4, 4]}, "fabric": "silk"}})");
  const CliRun r = run(dir, "simulate " + dir.file("bad.json") + " -o " + dir.file("out"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lines(r.err), 1);
  EXPECT_NE(r.err.find("silk"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

// Two flat panels sewn along two sides into a tube (no gravity): the seams close, the report says
// so, the output is welded, and the cloth never intersects itself.
TEST(Cli, SimulateSewsPanelsAndReportsSeamsAndCrossings) {
  test::TempDir dir;
  write(dir.file("tube.json"), R"({"cloth": {"panels": [
      {"size": [0.2, 0.2], "resolution": [9, 9], "center": [0, 0.06, 0], "normal": [0, 1, 0]},
      {"size": [0.2, 0.2], "resolution": [9, 9], "center": [0, -0.06, 0], "normal": [0, -1, 0]}],
    "fabric": "gray-interlock",
    "seams": [{"chains": [{"panel": 0, "side": "left"}, {"panel": 1, "side": "left", "reverse": true}]},
              {"pairs": [[[0, 8, 0], [1, 8, 8]], [[0, 8, 4], [1, 8, 4]], [[0, 8, 8], [1, 8, 0]]]}]},
    "simulation": {"dt": 0.002, "adaptive": false, "duration": 1.0, "gravity": [0, 0, 0], "air_damping": 1.0,
                   "strain_limit": 0.1}})");
  const CliRun r = run(dir, "simulate " + dir.file("tube.json") + " -o " + dir.file("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto report = nlohmann::json::parse(slurp(dir.file("out/report.json")));
  EXPECT_EQ(report["seams"]["stitches"], 12);
  EXPECT_EQ(report["seams"]["closed"], 12);
  EXPECT_LE(report["seams"]["max_gap_mm"].get<double>(), 1.0);
  EXPECT_TRUE(report["self_collision"].get<bool>());
  EXPECT_EQ(report["intersections"]["max_over_frames"], 0);
  for (const char* phase :
       {"forces_and_assembly", "integrator", "seams", "colliders", "cloth_collisions"})
    EXPECT_TRUE(report["phase_seconds"].contains(phase)) << phase;
  // Welded: the 12 sewn pairs are 12 vertices fewer.
  const TriangleMesh welded = load_mesh(dir.file("out/result.obj"));
  EXPECT_EQ(welded.num_vertices(), 2 * 81 - 12);
}

TEST(Cli, SimulateBadSeamsExit2NamingTheSeam) {
  test::TempDir dir;
  const std::string panel =
      R"("grid": {"size": [0.2, 0.2], "resolution": [5, 5]}, "fabric": "gray-interlock")";
  for (const auto& [seams, expect] : std::vector<std::pair<std::string, std::string>>{
           {R"([{"pairs": [[0, 99]]}])", "out of range"},
           {R"([{"pairs": [[3, 3]]}])", "itself"},
           {R"([{"chains": [[0, 0], [1, 2]]}])", "zero length"},
           {R"([{"chains": [[0], [1, 2]]}])", "two particles"},
           {R"([{"pairs": [[0, 1]], "chains": [[0, 1], [2, 3]]}])", "exactly one"}}) {
    write(dir.file("s.json"), "{\"cloth\": {" + panel + ", \"seams\": " + seams + "}}");
    const CliRun r = run(dir, "simulate " + dir.file("s.json") + " -o " + dir.file("out"));
    EXPECT_EQ(r.code, 2) << seams;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("seams[0]"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
  }
}

// Bad values and bad bodies: one line naming the file, the key and the value (with the units that
// would fit for a body read in the wrong ones), exit 2, no output folder.
TEST(Cli, SimulateBadValuesAndBodiesExit2WithOneLine) {
  test::TempDir dir;
  save_mesh(test::sphere_mesh(Eigen::Vector3d::Zero(), 0.5, 0.05), dir.file("body.ply"));
  write(dir.file("empty.obj"), "");
  write(dir.file("words.obj"), "not a mesh at all\n");
  const std::string cloth = R"("cloth": {"grid": {"size": [0.4, 0.4], "resolution": [6, 6]}, "fabric": "gray-interlock")";
  for (const auto& [body_and_rest, expect] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {R"(}, "colliders": [{"type": "mesh", "path": "body.ply", "units": "mm"}]})",
            {"colliders[0].units", "0.001 m across", "\"units\": \"m\" it would be 1 m"}},
           {R"(}, "colliders": [{"type": "mesh", "path": "body.ply", "units": 1000}]})",
            {"colliders[0].units", "1000 m across", "\"units\": \"m\""}},
           {R"(}, "colliders": [{"type": "mesh", "path": "empty.obj"}]})", {"colliders[0].path", "empty.obj"}},
           {R"(}, "colliders": [{"type": "mesh", "path": "words.obj"}]})", {"colliders[0].path", "words.obj"}},
           {R"(, "total_mass": -1}})", {"cloth.total_mass", "-1"}},
           {R"(}, "simulation": {"dt": 0}})", {"simulation.dt", "0 is outside"}},
           {R"(}, "simulation": {"dt": -0.01}})", {"simulation.dt", "-0.01"}},
           {R"(}, "simulation": {"rest_time": -1}})", {"simulation.rest_time", "-1"}}}) {
    write(dir.file("bad.json"), "{" + cloth + body_and_rest);
    const CliRun r = run(dir, "simulate " + dir.file("bad.json") + " -o " + dir.file("out"));
    EXPECT_EQ(r.code, 2) << body_and_rest << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    for (const std::string& word : expect) EXPECT_NE(r.err.find(word), std::string::npos) << word << " in " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
  }
}

// A body mesh with a hole is reported and its inside taken by the named fallback; a cloth that
// starts deep inside a closed body is pushed out a little each step without blowing up, and
// reported.
TEST(Cli, SimulateOpenBodyAndClothStartingInsideTheBody) {
  test::TempDir dir;
  TriangleMesh ball = test::sphere_mesh(Eigen::Vector3d::Zero(), 0.2, 0.02);
  save_mesh(ball, dir.file("ball.ply"));
  TriangleMesh open = ball;
  open.F.conservativeResize(open.F.rows() - 4, 3);  // four faces short: boundary edges
  save_mesh(open, dir.file("open.ply"));
  const std::string cloth =
      R"("cloth": {"grid": {"size": [0.16, 0.16], "resolution": [9, 9], "center": [0, 0.05, 0]},
    "fabric": "gray-interlock"})";
  write(dir.file("inside.json"),
        "{" + cloth + R"(, "colliders": [{"type": "mesh", "path": "ball.ply"}],
    "simulation": {"dt": 0.002, "duration": 1.5, "gravity": [0, 0, 0], "strain_limit": 0.1}})");
  CliRun r = run(dir, "simulate " + dir.file("inside.json") + " -o " + dir.file("in"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto report = nlohmann::json::parse(slurp(dir.file("in/report.json")));
  EXPECT_EQ(report["bodies"][0]["particles_inside_at_start"], 81);
  EXPECT_EQ(report["bodies"][0]["particles_inside_at_end"], 0);
  EXPECT_GT(report["deep_pushes"].get<int>(), 0);
  EXPECT_LT(report["max_strain"].get<double>(), 0.11);
  write(dir.file("open.json"),
        "{" + cloth + R"(, "colliders": [{"type": "mesh", "path": "open.ply"}],
    "simulation": {"dt": 0.002, "duration": 0.05}})");
  r = run(dir, "simulate " + dir.file("open.json") + " -o " + dir.file("op"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("not watertight"), std::string::npos);
  report = nlohmann::json::parse(slurp(dir.file("op/report.json")));
  EXPECT_FALSE(report["bodies"][0]["closed"].get<bool>());
  EXPECT_NE(report["bodies"][0]["sign_method"].get<std::string>().find("majority"),
            std::string::npos);
}

TEST(Cli, ThicknessPrintsTheIssuesKeysAndTheTenFabrics) {
  test::TempDir dir;
  CliRun r = run(dir, "thickness --fabric gray-interlock --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"thickness_mm", "thickness_min_mm", "thickness_max_mm", "threshold_c"})
    ASSERT_TRUE(j.contains(key)) << key;
  EXPECT_LE(j["thickness_min_mm"].get<double>(), j["thickness_mm"].get<double>());
  EXPECT_LE(j["thickness_mm"].get<double>(), j["thickness_max_mm"].get<double>());
  EXPECT_NEAR(j["thickness_mm"].get<double>(), j["thickness_closed_form_mm"].get<double>(),
              0.005 * j["thickness_mm"].get<double>());

  // The same blend given as a composition gives the same thickness.
  r = run(dir, "thickness --composition cotton=0.6,polyester=0.4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(r.out)["thickness_mm"].get<double>(),
                   j["thickness_mm"].get<double>());

  r = run(dir, "thickness --all-fabrics --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto table = nlohmann::json::parse(r.out);
  ASSERT_EQ(table.size(), 10u);
  EXPECT_EQ(table[0]["fabric"], "ivory-rib-knit");

  r = run(dir, "thickness --composition down=1 --solidity 0.002 --panel-areas 0.1,0.2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto down = nlohmann::json::parse(r.out);
  EXPECT_NEAR(down["down_fill"]["total_kg"].get<double>(),
              0.3 * down["thickness_mm"].get<double>() * 1e-3 * 0.002 * 1310.0, 1e-9);
}

TEST(Cli, ThicknessPlotWritesCsvAndPng) {
  test::TempDir dir;
  const CliRun r = run(dir, "thickness --fabric white-swim-solid --plot " + dir.file("plot"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("plot/temperature.csv")));
  EXPECT_EQ(slurp(dir.file("plot/temperature.png")).substr(1, 3), "PNG");
}

TEST(Cli, ThicknessBadInputExits2WithOneLine) {
  test::TempDir dir;
  for (const char* args :
       {"--composition cotton=0.6,polyester=0.3", "--composition cotton=1.2,wool=-0.2",
        "--composition silk=1", "--fabric velvet", "--fabric gray-interlock --t-skin 20 --t-env 20",
        "--fabric gray-interlock --time 0", "--fabric gray-interlock --cells 0",
        "--fabric gray-interlock --threshold 50", "--fabric gray-interlock --scheme leapfrog"}) {
    const CliRun r = run(dir, std::string("thickness ") + args + " --plot " + dir.file("plot"));
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("plot"))) << args;
  }
  EXPECT_EQ(run(dir, "thickness").code, 64);
  EXPECT_EQ(run(dir, "thickness --fabric gray-interlock --composition cotton=1").code, 64);
}

TEST(Cli, SegmentWritesLabelsInFileOrderColoursAndOnePartPerObj) {
  DRESSKIT_REQUIRE_DATA();
  test::TempDir dir;
  const std::string body = test::data_dir() + "/bodies/mh_woman_young_average.obj";
  const CliRun r =
      run(dir, "segment " + body + " --units dm --up +y --parts 6 -o " + dir.file("seg"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("arm_left"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(dir.file("seg/labels.json")));
  const auto labels = j["vertex_labels"].get<std::vector<int>>();
  const auto names = j["part_names"].get<std::vector<std::string>>();
  // One label per OBJ `v` line, in file order: compare with the ground truth, which is in that
  // order.
  const auto truth =
      nlohmann::json::parse(slurp(test::data_dir() + "/labels/mh_body_part_labels.json"))["labels"]
          .get<std::vector<std::string>>();
  ASSERT_EQ(labels.size(), truth.size());
  int same = 0;
  for (size_t i = 0; i < labels.size(); ++i)
    same += labels[i] >= 0 && (names[labels[i]] == truth[i] ||
                               (names[labels[i]] == "head" && truth[i] == "head_neck"));
  EXPECT_GT(same, 0.9 * labels.size());
  EXPECT_EQ(j["parts"], 6);
  EXPECT_EQ(j["parts_chosen_by"], "given");
  EXPECT_EQ(j["bridged_edges"], 0);  // a closed body has no boundary to bridge
  EXPECT_LT(j["eigen_residual"].get<double>(), 1e-8);
  EXPECT_EQ(j["face_labels"].size(), j["faces"].get<size_t>());
  int part_faces = 0;
  for (const auto& name : names) {
    const TriangleMesh part = load_mesh(dir.file("seg/" + name + ".obj"));
    part_faces += part.num_faces();
  }
  EXPECT_EQ(part_faces, j["faces"].get<int>());
  const TriangleMesh coloured = load_mesh(dir.file("seg/segments.ply"));
  EXPECT_EQ(coloured.num_vertices(), static_cast<int>(labels.size()));

  // Into the same folder in two parts: no part file of the six-part run is left, and a file the
  // tool did not write stays.
  std::ofstream(dir.file("seg/notes.txt")) << "mine\n";
  ASSERT_EQ(run(dir, "segment " + body + " --units dm --up +y --parts 2 -o " + dir.file("seg")).code, 0);
  const auto two = nlohmann::json::parse(slurp(dir.file("seg/labels.json")))["part_names"].get<std::vector<std::string>>();
  std::vector<std::string> objs;
  for (const auto& entry : std::filesystem::directory_iterator(dir.file("seg")))
    if (entry.path().extension() == ".obj") objs.push_back(entry.path().stem().string());
  std::sort(objs.begin(), objs.end());
  std::vector<std::string> expected = two;
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(objs, expected);
  EXPECT_TRUE(std::filesystem::exists(dir.file("seg/notes.txt")));
}

TEST(Cli, SegmentBadInputExits2WithOneLineAndNoOutput) {
  test::TempDir dir;
  save_mesh(fixtures::cube(1.0), dir.file("cube.obj"));
  write(dir.file("empty.obj"), "");
  for (const std::string args :
       {"missing.obj", "empty.obj", "cube.obj --parts 0", "cube.obj --parts 9",
        "cube.obj --affinity nearest", "cube.obj --laplacian weird", "cube.obj --max-parts 0",
        "cube.obj --units furlong", "cube.obj --bridge-gaps -1", "cube.obj --up +y --forward +y",
        "cube.obj --up +z --forward -z", "cube.obj --ncv -5", "cube.obj --over-segmentation -1",
        "cube.obj --symmetry nan"}) {
    const std::string first = args.substr(0, args.find(' '));
    const CliRun r = run(
        dir, "segment " + dir.file(first) + args.substr(first.size()) + " -o " + dir.file("out"));
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << args;
  }
  // A cube in two parts works, and its labels are in the PLY file's order too.
  save_mesh(fixtures::cube(1.0), dir.file("cube.ply"));
  const CliRun ok =
      run(dir, "segment " + dir.file("cube.ply") + " --parts 2 -o " + dir.file("out"));
  ASSERT_EQ(ok.code, 0) << ok.err;
  const auto j = nlohmann::json::parse(slurp(dir.file("out/labels.json")));
  EXPECT_EQ(j["vertex_labels"].size(), 8u);
  EXPECT_EQ(run(dir, "segment " + dir.file("cube.obj")).code, 64);  // no -o
}

// A cloth mesh called result.obj in the output folder would be replaced by the result: refused with
// one line before anything runs, the file left as it was.
TEST(Cli, SimulateRefusesToOverwriteItsClothMesh) {
  test::TempDir dir;
  save_mesh(fixtures::grid(4, 4, 0.05), dir.file("result.obj"));
  const std::string before = slurp(dir.file("result.obj"));
  write(dir.file("scene.json"), R"({"cloth": {"mesh": "result.obj"}, "simulation": {"duration": 0.01}})");
  const CliRun r = run(dir, "simulate " + dir.file("scene.json") + " -o " + dir.path().string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("result.obj"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir.file("result.obj")), before);
  EXPECT_FALSE(std::filesystem::exists(dir.file("report.json")));
}
