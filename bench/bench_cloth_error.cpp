// Error against run time: the 81×81 hanging cloth (6,561 vertices, 1 m, gray-interlock,
// pinned at its two top corners) simulated for 1 s by each integrator over a range of time steps
// and solver tolerances (projective dynamics: iterations per step). Error = RMS distance of the
// vertices from a reference run (implicit Euler at 1/4800 s, CG tolerance 1e-10) at t = 1 s, over
// the cloth's size (1 m). Cost = wall time per 1/60 s of simulated time, one core (wall, and the
// process's CPU time, which a loaded machine inflates less). Writes CSV. Projective dynamics runs
// with backward Euler and with BDF2 (CSV integrator "projective-bdf2"), and with its
// double-precision solve for comparison ("projective-double"). Usage: bench_cloth_error
// [out.csv=out/bench/error_vs_time.csv] [--quick] [--only INTEGRATOR]
//        [--reference FILE]  (reads the reference positions from FILE, or computes and writes them
//        there)
//        [--schemes a,b] [--dts 60,120] [--iterations 3,5] [--lbfgs 0,5]
//        (projective dynamics' sweep: time schemes backward_euler, bdf2, midpoint, tr_bdf2; steps
//        as 1/dt; iterations per step; L-BFGS history, 0 = local/global iterations; CSV
//        integrator "projective[-scheme][-lbfgsM]")
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dresskit/cloth/run.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace {
struct Run {
  Eigen::MatrixX3d x;
  double wall = 0.0;
  double cpu =
      0.0;  ///< process CPU time [s]: what one core spent, whatever else ran on the machine
  bool ok = true;
  std::string failure;
};

template <typename T>
std::vector<T> parse_list(const char* text) {
  std::vector<T> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(static_cast<T>(std::stod(item)));
  return out;
}

Run simulate(const ClothModel& model, const std::vector<int>& pins, SimulationOptions o) {
  ClothSimulator sim(model, o);
  sim.set_pinned(pins);
  RunOptions run_options;
  run_options.duration = static_cast<double>(std::lround(1.0 / o.dt)) * o.dt;  // 1 s in whole steps
  run_options.rest.enabled = false;
  Run run;
  const std::clock_t c0 = std::clock();
  const auto t0 = std::chrono::steady_clock::now();
  const RunResult result = dresskit::cloth::run(sim, run_options);
  run.ok = result.ok;
  run.failure = result.failure;
  run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run.cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  run.x = sim.positions();
  return run;
}
}  // namespace

int main(int argc, char** argv) {
  std::string csv_path = "out/bench/error_vs_time.csv";
  bool quick = false;
  std::string only;  // --only NAME: just that integrator's runs (and the reference)
  std::string reference_path;
  std::vector<TimeScheme> schemes = {TimeScheme::backward_euler, TimeScheme::bdf2,
                                     TimeScheme::tr_bdf2};
  std::vector<int> dts = {30, 60, 120, 240, 480}, iteration_counts = {3, 5, 10, 20, 40};
  std::vector<int> histories = {0};
  std::vector<int> adaptive_weights = {0};
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--quick") == 0)
      quick = true;
    else if (std::strcmp(argv[a], "--only") == 0 && a + 1 < argc)
      only = argv[++a];
    else if (std::strcmp(argv[a], "--reference") == 0 && a + 1 < argc)
      reference_path = argv[++a];
    else if (std::strcmp(argv[a], "--schemes") == 0 && a + 1 < argc) {
      schemes.clear();
      std::stringstream in(argv[++a]);
      std::string item;
      while (std::getline(in, item, ',')) schemes.push_back(parse_time_scheme(item));
    } else if (std::strcmp(argv[a], "--dts") == 0 && a + 1 < argc)
      dts = parse_list<int>(argv[++a]);
    else if (std::strcmp(argv[a], "--iterations") == 0 && a + 1 < argc)
      iteration_counts = parse_list<int>(argv[++a]);
    else if (std::strcmp(argv[a], "--adaptive-weights") == 0 && a + 1 < argc)
      adaptive_weights = parse_list<int>(argv[++a]);
    else if (std::strcmp(argv[a], "--lbfgs") == 0 && a + 1 < argc)
      histories = parse_list<int>(argv[++a]);

    else
      csv_path = argv[a];
  }
  const int n = 81;
  const TriangleMesh grid = make_grid({1.0, 1.0}, {n, n}, {0, 0, 0}, {0, 0, 1});
  const ClothModel model = build_cloth(grid, fabric_by_name("gray-interlock"));
  const std::vector<int> pins = {n * (n - 1), n * n - 1};
  // The integrators alone: fixed steps, no length limits (the library's defaults adapt the step and
  // limit strain, which would measure those instead); implicit Euler unless a run names another.
  SimulationOptions base;
  base.integrator = Integrator::implicit_euler;
  base.adaptive = false;
  base.strain_limiting = false;
  base.air_damping = 0.1;

  SimulationOptions ref = base;
  ref.dt = quick ? 1.0 / 1200 : 1.0 / 4800;
  ref.linear.cg_tolerance = 1e-10;
  Run reference;
  std::ifstream cached(reference_path, std::ios::binary);
  if (!reference_path.empty() && cached) {
    reference.x.resize(n * n, 3);
    cached.read(reinterpret_cast<char*>(reference.x.data()),
                static_cast<std::streamsize>(sizeof(double) * 3 * n * n));
    if (!cached) {
      std::fprintf(stderr, "%s: not a reference of this cloth\n", reference_path.c_str());
      return 2;
    }
    std::printf("reference: read from %s\n", reference_path.c_str());
  } else {
    reference = simulate(model, pins, ref);
    std::printf("reference: implicit dt 1/%ld, %.1f s wall%s\n", std::lround(1 / ref.dt),
                reference.wall, reference.ok ? "" : (" FAILED: " + reference.failure).c_str());
    if (!reference_path.empty()) {
      std::ofstream out(reference_path, std::ios::binary);
      out.write(reinterpret_cast<const char*>(reference.x.data()),
                static_cast<std::streamsize>(sizeof(double) * 3 * n * n));
    }
  }

  std::filesystem::create_directories(std::filesystem::path(csv_path).parent_path());
  std::ofstream csv(csv_path);
  csv << "integrator,label,dt,cg_tolerance,wall_seconds,ms_per_frame,cpu_ms_per_frame,relative_"
         "error,stable\n";
  auto record = [&](const SimulationOptions& o, const std::string& label) {
    std::string name = to_string(o.integrator);
    if (o.integrator == Integrator::projective && o.projective.time_scheme != TimeScheme::backward_euler)
      name += "-" + to_string(o.projective.time_scheme);
    if (o.integrator == Integrator::projective && o.projective.lbfgs_history > 0)
      name += "-lbfgs" + std::to_string(o.projective.lbfgs_history);
    if (o.integrator == Integrator::projective && o.projective.adaptive_weights) name += "-aw";

    if (o.integrator == Integrator::projective && !o.projective.single_precision) name += "-double";
    if (!only.empty() && name.rfind(only, 0) != 0) return;
    const Run r = simulate(model, pins, o);
    const double error =
        r.ok ? std::sqrt((r.x - reference.x).rowwise().squaredNorm().mean()) / 1.0 : NAN;
    const double ms_per_frame = r.wall / 60.0 * 1e3, cpu_ms_per_frame = r.cpu / 60.0 * 1e3;
    csv << name << "," << label << "," << o.dt << "," << o.linear.cg_tolerance << "," << r.wall << ","
        << ms_per_frame << "," << cpu_ms_per_frame << "," << error << "," << r.ok << "\n";
    csv.flush();
    std::printf("%-17s %-22s %8.2f ms/frame (CPU %8.2f)  error %.2e %s\n", name.c_str(),
                label.c_str(), ms_per_frame, cpu_ms_per_frame, error,
                r.ok ? "" : ("unstable: " + r.failure).c_str());
    std::fflush(stdout);
  };
  for (int inv : {4800, 2400, 1200, 600}) {
    if (quick && inv == 4800) continue;
    SimulationOptions o = base;
    o.integrator = Integrator::symplectic_euler;
    o.dt = 1.0 / inv;
    record(o, "dt 1/" + std::to_string(inv));
  }
  for (int inv : {60, 120, 240, 480, 960}) {
    for (double tol : {1e-3, 1e-5, 1e-8}) {
      if (quick && tol == 1e-5) continue;
      SimulationOptions o = base;
      o.dt = 1.0 / inv;
      o.linear.cg_tolerance = tol;
      char label[64];
      std::snprintf(label, sizeof label, "dt 1/%d tol %.0e", inv, tol);
      record(o, label);
    }
  }
  for (int inv : {60, 120, 240}) {
    SimulationOptions o = base;
    o.integrator = Integrator::newton;
    o.dt = 1.0 / inv;
    o.linear.cg_tolerance = 1e-3;
    o.iteration_tolerance = 1e-5;
    o.newton.iterations = 4;
    char label[64];
    std::snprintf(label, sizeof label, "dt 1/%d tol %.0e", inv, o.linear.cg_tolerance);
    record(o, label);
  }
  for (int adaptive : adaptive_weights)
    for (int history : histories) {
      for (TimeScheme scheme : schemes) {
        for (int inv : dts) {
          for (int iterations : iteration_counts) {
            SimulationOptions o = base;
            o.integrator = Integrator::projective;
            o.projective.time_scheme = scheme;
            o.dt = 1.0 / inv;
            o.projective.iterations = iterations;
            o.projective.lbfgs_history = history;
            o.projective.adaptive_weights = adaptive != 0;
            o.iteration_tolerance = 1e-7;
            char label[64];
            std::snprintf(label, sizeof label, "dt 1/%d it %d", inv, iterations);
            record(o, label);
            if (scheme == TimeScheme::backward_euler && inv == 60 && history == 0 &&
                adaptive == 0) {  // the double-precision solve, for comparison
              o.projective.single_precision = false;
              record(o, label);
            }
          }
        }
      }
    }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
