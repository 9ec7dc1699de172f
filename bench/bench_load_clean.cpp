// Load + clean benchmark: milliseconds per phase for the real bodies in ../shared/data.
// Usage: bench_load_clean [repetitions=7]; data from DRESSKIT_DATA_DIR or ../shared/data.
// Prints the median of the repetitions for each phase, and the machine's CPU model.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/io.h"

using namespace dresskit;
using namespace dresskit::mesh;

using bench::cpu_model;
using bench::median;

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  const char* env = std::getenv("DRESSKIT_DATA_DIR");
  const std::string data = env ? env : DRESSKIT_DEFAULT_DATA_DIR;
  struct Case {
    const char* file;
    const char* units;
  };
  const Case cases[] = {{"bodies/gc_mean_all.obj", "m"}, {"bodies/mh_woman_young_average.obj", "dm"}};
  std::printf("machine: %s, one thread; median of %d runs\n", cpu_model().c_str(), reps);
  std::printf("%-36s %8s %8s %8s %8s %8s %8s %8s\n", "mesh", "verts", "load", "soup", "mesh",
              "attrib", "clean", "total");
  for (const Case& c : cases) {
    std::vector<double> load, soup, halfedge, attrib, clean, total;
    int vertices = 0;
    for (int r = 0; r < reps; ++r) {
      LoadOptions options;
      options.units = Units::parse(c.units);
      const auto t0 = std::chrono::steady_clock::now();
      const TriangleMesh mesh = load_mesh(data + "/" + c.file, options);
      const auto t1 = std::chrono::steady_clock::now();
      const CleanupResult result = cleanup_mesh(mesh);
      const auto t2 = std::chrono::steady_clock::now();
      vertices = mesh.num_vertices();
      load.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      clean.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
      total.push_back(std::chrono::duration<double, std::milli>(t2 - t0).count());
      soup.push_back(result.seconds_soup * 1e3);
      halfedge.push_back(result.seconds_mesh * 1e3);
      attrib.push_back(result.seconds_attributes * 1e3);
    }
    std::printf("%-36s %8d %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f\n", c.file, vertices, median(load),
                median(soup), median(halfedge), median(attrib), median(clean), median(total));
  }
  std::printf("(ms; goal: total under 300 ms for bodies/gc_mean_all.obj)\n");
  return 0;
}
