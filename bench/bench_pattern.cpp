// Sewing patterns dressed on a body: for each shared GarmentCode pattern on gc_mean_all, the whole
// dressing (what `dress-a-mesh dress BODY PATTERN.json` runs) and its parts — reading and cutting,
// sewing (seam forces until every stitch pair is within 1 mm), settling — in wall-clock seconds,
// the number of triangles, and the result: largest stitch gap, the sewn garment's own crossings,
// vertices deeper than 2 mm inside the body, crossings once dressed, the share of vertices within 8
// cm of the body, and the largest change of a panel's area. One row per pattern and trial; writes
// OUT.csv. Sewing and settling are chaotic: a change of the input far below any tolerance (a
// picometre) leads to another run, faster or slower, so a figure is a distribution. Trial 0 dresses
// the body as read; trial t > 0 moves each body vertex by t picometres along one axis, times a sine
// of its index. --body dresses another of the shared bodies (a name under bodies/, in its units),
// with the panels carried by frames, or by parts with --pattern-body (the pattern's own body); a
// pattern refused on that body (dress throws InputError) makes a row whose outcome says so.
// --first-trial runs trials from that one on (one trial of a distribution again). --generated dresses
// every pattern under patterns/generated/ instead, each on the body it was made for (gc_mean_all, or
// gc_mean_all_tpose for a `_tpose_` file). Each row says whether the run passes: dressed, every
// stitch closed to 1 mm, nothing deeper than 2 mm inside the body, no crossings, at least 95 % of the
// garment within 8 cm of the body, at most 30 s; the pass rate is printed at the end.
//   bench_pattern OUT.csv [--edge 0.02] [--patterns a,b] [--generated] [--trials 1] [--first-trial 0]
//                 [--body gc_mean_all] [--body-units m] [--pattern-body NAME]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/inside.h"
#include "dresskit/mesh/io.h"
#include "dresskit/testing/data.h"

using namespace dresskit::cloth;
using namespace dresskit::dressing;
using namespace dresskit::mesh;

using namespace dresskit;

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::cerr << "usage: bench_pattern OUT.csv [--edge 0.02] [--patterns gc_shirt_mean,...] [--generated] "
                 "[--trials 1] [--first-trial 0] [--body gc_mean_all] [--body-units m] [--pattern-body NAME]\n";
    return 64;
  }
  double edge = 0.02;
  int trials = 1, first_trial = 0;
  std::vector<std::string> patterns = {"gc_shirt_mean", "gc_hoody_mean", "gc_dress_pencil"};
  std::string body_name = "gc_mean_all", pattern_body;
  LoadOptions body_load;
  bool generated = false;
  for (int i = 2; i < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--generated") {
      generated = true;
      --i;
      continue;
    }
    if (i + 1 >= argc) {
      std::cerr << key << ": no value\n";
      return 64;
    }
    const std::string value = argv[i + 1];
    if (key == "--edge") {
      edge = std::stod(value);
    } else if (key == "--trials") {
      trials = std::stoi(value);
    } else if (key == "--first-trial") {
      first_trial = std::stoi(value);
    } else if (key == "--body") {
      body_name = value;
    } else if (key == "--body-units") {
      body_load.units = Units::parse(value);
    } else if (key == "--pattern-body") {
      pattern_body = value;
    } else if (key == "--patterns") {
      patterns.clear();
      std::stringstream s(value);
      for (std::string p; std::getline(s, p, ',');) patterns.push_back(p);
    } else {
      std::cerr << "unknown option " << key << "\n";
      return 64;
    }
  }
  const std::string data = testing::data_dir();
  // Each pattern's file (under patterns/) and body.
  std::vector<std::pair<std::string, std::string>> runs;
  if (generated) {
    for (const auto& e : std::filesystem::directory_iterator(data + "/patterns/generated")) {
      const std::string file = e.path().filename().string();
      if (file.size() < 24 || file.substr(file.size() - 19) != "_specification.json") continue;
      runs.emplace_back("generated/" + file.substr(0, file.size() - 19),
                        file.find("_tpose_") != std::string::npos ? "gc_mean_all_tpose" : "gc_mean_all");
    }
    std::sort(runs.begin(), runs.end());
  } else {
    for (const std::string& name : patterns) runs.emplace_back(name, body_name);
  }
  std::ofstream csv(argv[1]);
  std::map<std::string, TriangleMesh> bodies;
  csv << "body,pattern,trial,edge_m,triangles,seconds_total,seconds_cut,seconds_sew,seconds_settle,"
         "sew_simulated_s,max_gap_mm,unwelded_pairs,sewn_crossings,inside_2mm,dressed_crossings,near_8cm_fraction,"
         "max_panel_area_change,outcome,pass\n";
  std::cout << "CPU: " << bench::cpu_model() << "\n";
  int rows = 0, passed = 0;
  for (const auto& [name, run_body] : runs)
    for (int trial = first_trial; trial < first_trial + trials; ++trial) {
      const std::string body_path = data + "/bodies/" + run_body + ".obj";
      if (!bodies.count(run_body)) bodies[run_body] = load_mesh(body_path, body_load);
      const TriangleMesh& body_as_read = bodies[run_body];
      ++rows;
      TriangleMesh jittered = body_as_read;
      for (Eigen::Index v = 0; v < jittered.V.rows(); ++v)
        jittered.V(v, (v * 7) % 3) += trial * 1e-12 * std::sin(1.7 * static_cast<double>(v));
      GarmentFile g;
      g.file = MeshFile::file(data + "/patterns/" + name + "_specification.json");
      if (!pattern_body.empty()) g.pattern_body = MeshFile::file(data + "/bodies/" + pattern_body + ".obj");
      DressOptions o;
      o.pattern_edge_length = edge;
      const auto start = std::chrono::steady_clock::now();
      DressResult r;
      try {
        r = dress(MeshFile::given(body_path, jittered), {g}, o);
      } catch (const InputError& e) {  // a pattern that does not sew on this body: a row that says so
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        csv << run_body << "," << name << "," << trial << "," << edge << ",," << seconds
            << ",,,,,,,,,,,,refused,0\n";
        std::cout << name << " (trial " << trial << "): refused after " << seconds << " s: " << e.what()
                  << std::endl;
        continue;
      }
      const DressedGarment& d = r.garments[0];
      double settle = 0.0;
      std::string settled;
      for (const DressStage& s : r.stages)
        if (s.name == "settle") settle = s.seconds, settled = s.reason;
      const TriangleBvh body(r.body.V, r.body.F);
      int near = 0;
      for (Eigen::Index i = 0; i < d.dressed.rows(); ++i) {
        double d2 = 0.0;
        Eigen::Vector3d q;
        body.closest(d.dressed.row(i).transpose(), &q, &d2);
        near += d2 <= 0.08 * 0.08;
      }
      double area_change = 0.0;
      for (std::size_t k = 0; k < d.pattern.panel_area_dressed.size(); ++k)
        area_change = std::max(
            area_change, std::abs(d.pattern.panel_area_dressed[k] / d.pattern.panel_area[k] - 1.0));
      csv << run_body << "," << name << "," << trial << "," << edge << "," << d.pattern.triangles << "," << r.seconds
          << "," << d.pattern.cut_seconds << "," << d.pattern.sew_seconds << "," << settle << ","
          << d.pattern.sew_simulated << "," << 1e3 * d.pattern.max_gap << ","
          << d.pattern.unwelded.size() << "," << d.crossings_authored << "," << d.inside_dressed
          << "," << d.crossings_dressed << "," << double(near) / double(d.dressed.rows()) << ","
          << area_change << ",dressed,";
      const bool pass = d.pattern.max_gap <= 0.001 && d.pattern.unwelded.empty() && d.inside_dressed == 0 &&
                        d.crossings_dressed == 0 && near >= 0.95 * static_cast<double>(d.dressed.rows()) && r.seconds <= 30.0;
      passed += pass;
      csv << pass << "\n";
      std::cout << name << " (trial " << trial << "): " << r.seconds << " s (cut "
                << d.pattern.cut_seconds << ", sew " << d.pattern.sew_seconds << ", settle "
                << settle << "), " << d.pattern.triangles << " triangles, gap "
                << 1e3 * d.pattern.max_gap << " mm, " << d.pattern.unwelded.size()
                << " pairs unwelded, crossings sewn " << d.crossings_authored << " dressed "
                << d.crossings_dressed << ", inside " << d.inside_dressed << ", near "
                << double(near) / double(d.dressed.rows()) << ", area change " << area_change
                << "; settle: " << settled << (pass ? "; pass" : "; fail") << std::endl;
    }
  std::cout << "passed " << passed << " of " << rows << "\n";
  return 0;
}
