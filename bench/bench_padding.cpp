// Padded garments dressed as double layers on real bodies from ../shared/data, with the defaults:
// the whole run's and the padding stage's seconds, its steps and why it stopped, the thickness
// asked, the shells' distances recounted from the positions (5th percentile, median, vertices
// closer than the lower limit), the double layer's crossings recounted, and vertices of either
// shell deeper than 2 mm inside the body (CGAL's inside test). Writes OUT.csv.
//   bench_padding OUT.csv [--cases a,b]
#include <algorithm>
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
using namespace dresskit::dressing;
using namespace dresskit::mesh;

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::cerr << "usage: bench_padding OUT.csv [--cases a,b]\n";
    return 64;
  }
  std::vector<std::string> only;
  for (int a = 2; a + 1 < argc; a += 2) {
    if (std::string(argv[a]) != "--cases") {
      std::cerr << "bench_padding: unknown option " << argv[a] << "\n";
      return 64;
    }
    std::stringstream in(argv[a + 1]);
    for (std::string item; std::getline(in, item, ',');) only.push_back(item);
  }
  struct Case {
    std::string name, body, body_units, garment, fabric;
  };
  const std::vector<Case> cases{
      {"casualsuit_on_child", "bodies/mh_girl_child_11y.obj", "dm", "garments/mh_female_casualsuit01.obj", ""},
      {"casualsuit_camel_on_gc_mean", "bodies/gc_mean_all.obj", "m", "garments/mh_female_casualsuit01.obj",
       "camel-ponte-roma"},
      {"male_casualsuit_on_woman", "bodies/mh_woman_young_average.obj", "dm", "garments/mh_male_casualsuit02.obj", ""},
  };
  const std::string data = testing::data_dir();
  std::ofstream out(argv[1]);
  out << "case,seconds,padding_s,steps,stopped,thickness_mm,min_mm,gap_p5_mm,gap_median_mm,below_min,vertices,"
         "start_at_full,crossings_start,crossings_dressed,inside_2mm\n";
  for (const Case& c : cases) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
    MeshFile body = MeshFile::file(data + "/" + c.body);
    body.load.units = Units::parse(c.body_units);
    GarmentFile garment{MeshFile::file(data + "/" + c.garment), c.fabric};
    garment.file.load.units = Units::parse("dm");
    garment.padded = true;
    const DressResult r = dress(body, {garment});
    const DressedGarment& g = r.garments[0];
    double padding_s = 0.0;
    for (const DressStage& s : r.stages)
      if (s.name == "padding") padding_s = s.seconds;
    const Eigen::VectorXd gap = (g.dressed_outer - g.dressed).rowwise().norm();
    std::vector<double> d(gap.data(), gap.data() + gap.size());
    std::sort(d.begin(), d.end());
    const long below = std::count_if(d.begin(), d.end(), [&](double x) { return x < g.padding.min; });
    Eigen::MatrixX3i faces(2 * g.mesh.num_faces(), 3);
    faces << g.mesh.F, g.mesh.F.array() + g.mesh.num_vertices();
    Eigen::MatrixX3d both(2 * g.dressed.rows(), 3);
    both << g.dressed, g.dressed_outer;
    const InsideTest inside(r.body);
    out << c.name << ',' << r.seconds << ',' << padding_s << ',' << r.padding_settle.totals.steps << ",\""
        << r.padding_settle.stopped_reason << "\"," << 1e3 * g.padding.thickness << ',' << 1e3 * g.padding.min << ','
        << 1e3 * d[d.size() / 20] << ',' << 1e3 * d[d.size() / 2] << ',' << below << ',' << d.size() << ','
        << g.padding.start_at_full << ',' << g.padding.crossings_start << ','
        << cloth::count_intersections(both, faces) << ',' << inside.count_deeper(both, 0.002) << '\n';
    out.flush();
    std::cerr << c.name << ": " << r.seconds << " s (padding " << padding_s << " s, " << r.padding_settle.stopped_reason
              << "), median " << 1e3 * d[d.size() / 2] << " mm, " << below << " of " << d.size()
              << " below the lower limit\n";
  }
}
