// Cloth dropped onto real bodies (testing/drops.h) under a grid of settings: which hold, at what
// cost. Each row: case, setting, whether the run held (finished, nothing deeper than 2 mm inside the
// body by an independent test, no crossings, strain ≤ 12 %, the cloth fell), CPU seconds, steps and
// the measures. Writes OUT.csv.
//   bench_drape OUT.csv [--resolution N] [--duration S] [--cases a,b] [--settings NAME=JSON;...]
// Without --settings: the defaults and every integrator named, at 1/30 … 1/240 s with and without
// adaptive stepping (the contact stability envelope, docs/benchmarks.md).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "dresskit/mesh/errors.h"
#include "dresskit/testing/data.h"
#include "dresskit/testing/drops.h"

using namespace dresskit::cloth;

using namespace dresskit;
using namespace dresskit::mesh;

namespace {
std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::cerr << "usage: bench_drape OUT.csv [--resolution N] [--duration S] [--cases a,b] [--settings NAME=JSON;...]\n";
    return 64;
  }
  const std::string out_path = argv[1];
  int resolution = 40;
  double duration = 2.0;
  std::vector<std::string> only;
  std::vector<std::pair<std::string, std::string>> settings;
  for (int a = 2; a + 1 < argc; a += 2) {
    const std::string key = argv[a], value = argv[a + 1];
    if (key == "--resolution") resolution = std::stoi(value);
    else if (key == "--duration") duration = std::stod(value);
    else if (key == "--cases") only = split(value, ',');
    else if (key == "--settings") {
      for (const std::string& s : split(value, ';')) {
        const auto eq = s.find('=');
        settings.emplace_back(s.substr(0, eq), s.substr(eq + 1));
      }
    } else {
      std::cerr << "bench_drape: unknown option " << key << "\n";
      return 64;
    }
  }
  if (settings.empty()) {
    settings.emplace_back("defaults", "{}");
    for (const char* integrator : {"projective", "implicit", "newton", "symplectic"})
      settings.emplace_back(integrator, std::string("{\"integrator\": \"") + integrator + "\"}");
    for (const char* integrator : {"projective", "implicit"}) {
      for (int hz : {30, 60, 120, 240}) {
        for (bool adaptive : {true, false}) {
          settings.emplace_back(std::string(integrator) + " 1/" + std::to_string(hz) + (adaptive ? " adaptive" : " fixed"),
                                std::string("{\"integrator\": \"") + integrator + "\", \"dt\": " +
                                    std::to_string(1.0 / hz) + ", \"adaptive\": " + (adaptive ? "true" : "false") + "}");
        }
      }
    }
  }
  if (!std::filesystem::is_directory(testing::data_dir())) {
    std::cerr << "bench_drape: data folder not found: " << testing::data_dir() << " (set DRESSKIT_DATA_DIR)\n";
    return 2;
  }
  const std::string work = (std::filesystem::temp_directory_path() / "dresskit_bench_drape").string();
  std::ofstream csv(out_path);
  csv << "case,setting,held,stopped,cpu_seconds,steps,simulated_s,inside_2mm,deepest_mm,crossings,max_strain,fell_m,"
         "smallest_dt,retries\n";
  for (const testing::DropCase& c : testing::drop_cases(resolution)) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
    for (const auto& [name, json] : settings) {
      testing::DropOutcome o;
      try {
        o = testing::run_drop(c, json, work, duration);
      } catch (const InputError& e) {
        std::cerr << c.name << " / " << name << ": " << e.what() << "\n";
        continue;
      }
      char line[512];
      std::snprintf(line, sizeof line, "%s,\"%s\",%d,\"%s\",%.3f,%d,%.3f,%d,%.2f,%d,%.4f,%.3f,%.2e,%d\n", c.name.c_str(),
                    name.c_str(), o.passed() ? 1 : 0, o.run.stopped_reason.substr(0, 60).c_str(), o.seconds,
                    o.steps, o.simulated, o.inside, 1e3 * o.deepest, o.crossings, o.max_strain, o.drop,
                    o.run.totals.smallest_dt, o.run.totals.retries);
      csv << line << std::flush;
      std::cout << line << std::flush;
    }
  }
  std::filesystem::remove_all(work);
  return 0;
}
