// Error against run time for the heat solver: the thickness problem of gray-interlock
// (37 °C skin, −10 °C air, 3600 s, solidity 0.25, the default domain) solved by each scheme over a
// grid of cells × time steps. Errors against the erfc closed form of the semi-infinite medium (the
// domain is 8 √(α_parallel t) deep, so the far boundary changes the answer by < 1e-20): the
// thickness (threshold crossing) relative to the exact depth, and the largest temperature error [K].
// Wall time per solve is the median of repeated solves, one core. Writes CSV and prints a summary.
// Usage: bench_heat_error [out.csv=out/bench/heat_error_vs_time.csv]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "dresskit/thickness/thickness.h"

using namespace dresskit;
using namespace dresskit::thickness;

int main(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "out/bench/heat_error_vs_time.csv";
  const ThicknessOptions defaults;
  const FabricThermal fabric = fabric_thermal(parse_composition("cotton=0.6,polyester=0.4"), defaults.solidity);
  HeatProblem p;
  p.diffusivity = fabric.diffusivity_nominal();
  p.length = 8.0 * std::sqrt(fabric.diffusivity_parallel() * defaults.exposure);
  p.t_skin = defaults.t_skin;
  p.t_env = defaults.t_env;
  p.t_initial = defaults.t_env;
  p.duration = defaults.exposure;
  const double threshold = 0.5 * (p.t_skin + p.t_env);
  const double exact = penetration_depth(p.diffusivity, p.duration, p.t_skin, p.t_env, threshold);

  std::filesystem::create_directories(std::filesystem::path(csv_path).parent_path());
  std::ofstream csv(csv_path);
  csv << "scheme,cells,steps,steps_taken,courant,seconds,thickness_relative_error,max_temperature_error_k\n";
  std::printf("exact depth %.4f mm (α = %.3e m²/s, domain %.1f mm)\n", exact * 1e3, p.diffusivity, p.length * 1e3);
  std::map<std::string, std::pair<double, std::string>> cheapest;  // scheme → fastest within 0.01 K
  for (HeatScheme scheme : {HeatScheme::explicit_euler, HeatScheme::implicit_euler, HeatScheme::crank_nicolson}) {
    for (int cells : {25, 50, 100, 200, 400, 800}) {
      for (int steps : {10, 25, 50, 100, 200, 400, 800, 1600, 3200}) {
        HeatOptions o;
        o.scheme = scheme;
        o.cells = cells;
        o.steps = steps;
        std::vector<double> times;
        HeatResult r;
        const auto t0 = std::chrono::steady_clock::now();
        do {
          r = solve_heat(p, o);
          times.push_back(r.seconds);
        } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 0.02 &&
                 times.size() < 200);
        std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
        const double seconds = times[times.size() / 2];
        const double depth = crossing_depth(r.x, r.temperature, threshold);
        const double depth_error = std::abs(depth - exact) / exact;
        double t_error = 0.0;
        for (Eigen::Index i = 0; i < r.x.size(); ++i)
          t_error = std::max(t_error, std::abs(r.temperature[i] - heat_semi_infinite(p, r.x[i], p.duration)));
        csv << to_string(scheme) << "," << cells << "," << steps << "," << r.steps_taken << "," << r.courant
            << "," << seconds << "," << depth_error << "," << t_error << "\n";
        auto& best = cheapest[to_string(scheme)];
        if (t_error < 0.01 && (best.second.empty() || seconds < best.first)) {
          char text[160];
          std::snprintf(text, sizeof text, "%d cells × %d steps (%d taken): %.1f µs, thickness error %.2e, T error %.2e K",
                        cells, steps, r.steps_taken, seconds * 1e6, depth_error, t_error);
          best = {seconds, text};
        }
      }
    }
  }
  for (const auto& [scheme, best] : cheapest)
    std::printf("cheapest %s within 0.01 K everywhere: %s\n", scheme.c_str(), best.second.c_str());
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
