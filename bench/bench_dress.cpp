// The dressing pipeline on real bodies and garments from ../shared/data, with the defaults and no
// label files: seconds per stage and for the whole run, and the result measured independently —
// vertices deeper than 2 mm inside the body (CGAL's inside test), the garment's own crossings (as
// authored, as fitted by the part-wise placement, handed to settling, settled), the
// largest strain, and where a reference refit exists the mean vertex distance to it in % of the
// body's height (placed and dressed). One row per case and quality. Writes OUT.csv.
//   bench_dress OUT.csv [--qualities fast,balanced] [--cases a,b]
// Plot of error against time for the cases with a reference:
//   /usr/bin/python3 scripts/plot_bench.py dress OUT.csv OUT.png
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "dresskit/cloth/self_collision.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/inside.h"
#include "dresskit/testing/data.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::dressing;
using namespace dresskit::mesh;

namespace {

struct Case {
  std::string name, body, body_units, garment, garment_units, fabric, reference;
};

double distance_percent(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, const TriangleMesh& body) {
  const double height = body.V.col(1).maxCoeff() - body.V.col(1).minCoeff();
  return 100.0 * (a - b).rowwise().norm().mean() / height;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::cerr << "usage: bench_dress OUT.csv [--qualities fast,balanced]\n";
    return 64;
  }
  auto split = [](const std::string& text) {
    std::vector<std::string> items;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) items.push_back(item);
    return items;
  };
  std::vector<std::string> qualities{"fast", "balanced"}, only;
  for (int a = 2; a + 1 < argc; a += 2) {
    const std::string key = argv[a];
    if (key == "--qualities") qualities = split(argv[a + 1]);
    else if (key == "--cases") only = split(argv[a + 1]);
    else {
      std::cerr << "bench_dress: unknown option " << key << "\n";
      return 64;
    }
  }
  const std::string data = testing::data_dir();
  const std::vector<Case> cases{
      {"casualsuit_on_child", "bodies/mh_girl_child_11y.obj", "dm", "garments/mh_female_casualsuit01.obj", "dm", "",
       "reference/female_casualsuit01__on__mh_girl_child_11y.obj"},
      {"casualsuit_dm_on_gc_mean_m", "bodies/gc_mean_all.obj", "m", "garments/mh_female_casualsuit01.obj", "dm", "", ""},
      {"casualsuit_denim_on_gc_mean", "bodies/gc_mean_all.obj", "m", "garments/mh_female_casualsuit01.obj", "dm",
       "11oz-black-denim", ""},
      {"male_casualsuit_on_woman", "bodies/mh_woman_young_average.obj", "dm", "garments/mh_male_casualsuit02.obj", "dm",
       "", ""},
  };
  std::ofstream out(argv[1]);
  out << "case,quality,ok,seconds,load_s,segmentation_s,placement_s,settle_s,steps,stopped,inside_2mm,crossings_authored,"
         "crossings_fitted,crossings_placed,crossings_dressed,max_strain,placed_error_pct,dressed_error_pct\n";
  for (const Case& c : cases) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
    for (const std::string& q : qualities) {
      MeshFile body;
      body.path = data + "/" + c.body;
      body.load.units = Units::parse(c.body_units);
      GarmentFile garment;
      garment.file.path = data + "/" + c.garment;
      garment.file.load.units = Units::parse(c.garment_units);
      garment.fabric = c.fabric;
      DressOptions o;
      o.quality = parse_quality(q);
      std::ostringstream row;
      try {
        const DressResult r = dress(body, {garment}, o);
        const DressedGarment& g = r.garments[0];
        auto seconds = [&](const std::string& name) {
          for (const DressStage& s : r.stages)
            if (s.name == name) return s.seconds;
          return 0.0;
        };
        double placed_error = -1.0, dressed_error = -1.0;
        if (!c.reference.empty()) {
          LoadOptions lo;
          lo.units = Units::parse(c.garment_units);
          const TriangleMesh reference = load_mesh(data + "/" + c.reference, lo);
          placed_error = distance_percent(g.placed, reference.V, r.body);
          dressed_error = distance_percent(g.dressed, reference.V, r.body);
        }
        row << c.name << ',' << q << ",1," << r.seconds << ',' << seconds("load") << ',' << seconds("segmentation")
            << ',' << seconds("placement") << ',' << seconds("settle") << ',' << r.settle.totals.steps << ",\""
            << r.settle.stopped_reason << "\"," << InsideTest(r.body).count_deeper(g.dressed, 0.002) << ','
            << g.crossings_authored << ',' << g.crossings_fitted << ',' << count_intersections(g.placed, g.mesh.F)
            << ',' << count_intersections(g.dressed, g.mesh.F) << ','
            << g.max_strain_dressed << ',' << placed_error << ',' << dressed_error;
      } catch (const std::exception& e) {
        row << c.name << ',' << q << ",0,,,,,,,\"" << e.what() << "\",,,,,,,,";
      }
      out << row.str() << '\n' << std::flush;
      std::cout << row.str() << std::endl;
    }
  }
  return 0;
}
