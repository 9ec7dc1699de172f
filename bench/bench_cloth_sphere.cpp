// The cloth-onto-a-sphere scene (examples/cloth_on_sphere.json: 1 m square, 64×64
// particles, 0.3 kg of gray-interlock, 0.5 m above a 0.3 m sphere, 2 s at 24 fps) with each
// integrator and setting: CPU seconds per frame against the drape's final strain — the speed goal
// and its price in one table. Time is the stepping thread's CPU time (scene loading and output
// excluded); strain is over the structural springs (max, 99th percentile, mean) and the shear
// springs (max) at the end; closest is the smallest particle distance to the sphere; crossings
// are edge–triangle intersections at the end. The cloth still flaps at 2 s (Blender's too), so one
// frame's largest strain is a sample of a moving quantity: the last 0.5 s (12 frames) give the mean
// and the worst of the per-frame largest strains as well (bench/blender_cloth_on_sphere.py the same).
// Usage: bench_cloth_sphere [OUT.csv] [--scene PATH] [--fabric NAME] [--quick]
//   --quick: only the projective settings (a few seconds).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/scene.h"
#include "dresskit/cloth/run.h"

using namespace dresskit;
using namespace dresskit::cloth;

namespace {

struct Setting {
  std::string name;
  Integrator integrator;
  double dt;
  int iterations;          ///< projective iterations per step
  bool contacts_inside;    ///< projective_collisions
  bool cloth_collisions;   ///< self_collision
  bool adaptive_weights = false;  ///< projective_adaptive_weights
};

struct Strains {
  double max = 0, p99 = 0, mean = 0, shear_max = 0;
};

Strains strains(const SpringSet& s, const Eigen::MatrixX3d& x) {
  std::vector<double> structural;
  Strains out;
  for (int k = 0; k < s.size(); ++k) {
    const double e = (x.row(s.j[k]) - x.row(s.i[k])).norm() / s.rest_length[k] - 1.0;
    if (s.type[k] == SpringType::structural) structural.push_back(e);
    if (s.type[k] == SpringType::shear) out.shear_max = std::max(out.shear_max, e);
  }
  if (structural.empty()) return out;
  std::sort(structural.begin(), structural.end());
  out.max = structural.back();
  out.p99 = structural[static_cast<std::size_t>(0.99 * static_cast<double>(structural.size() - 1))];
  for (double e : structural) out.mean += e;
  out.mean /= static_cast<double>(structural.size());
  return out;
}

int run(int argc, char** argv) {
  std::string csv, scene_path = std::string(DRESSKIT_SOURCE_DIR) + "/examples/cloth_on_sphere.json", fabric;
  bool quick = false;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--quick")) quick = true;
    else if (!std::strcmp(argv[a], "--scene") && a + 1 < argc) scene_path = argv[++a];
    else if (!std::strcmp(argv[a], "--fabric") && a + 1 < argc) fabric = argv[++a];
    else csv = argv[a];
  }
  ClothScene scene = load_cloth_scene(scene_path);
  if (!fabric.empty()) {  // the same grid and mass with another fabric's stiffness
    const double mass = scene.model.mass.sum();
    scene.model = build_cloth(make_grid({1.0, 1.0}, {64, 64}, {0, 0.5, 0}, {0, 1, 0}), fabric_by_name(fabric));
    scene.model.mass *= mass / scene.model.mass.sum();
  }
  const std::string fabric_label = fabric.empty() ? scene.fabric_name : fabric;
  const double h60 = 1.0 / 60, h24 = 1.0 / 24;
  std::vector<Setting> settings = {
      {"projective 1/24 x 5", Integrator::projective, h24, 5, true, false},
      {"projective 1/24 x 10", Integrator::projective, h24, 10, true, false},
      {"projective 1/60 x 5", Integrator::projective, h60, 5, true, false},
      {"projective 1/60 x 10", Integrator::projective, h60, 10, true, false},
      {"projective 1/60 x 30", Integrator::projective, h60, 30, true, false},
      // Small steps with few iterations (Macklin et al. 2019, "Small Steps in Physics Simulation"):
      // the contacts' forces are found anew each step, so the cloth comes to rest on the sphere.
      {"projective 1/100 x 6", Integrator::projective, 1.0 / 100, 6, true, false},
      {"projective 1/200 x 3", Integrator::projective, 1.0 / 200, 3, true, false},
      {"projective 1/300 x 1", Integrator::projective, 1.0 / 300, 1, true, false},
      {"projective 1/400 x 1", Integrator::projective, 1.0 / 400, 1, true, false},
      {"projective 1/500 x 1", Integrator::projective, 1.0 / 500, 1, true, false},
      {"projective 1/60 x 5, adaptive weights", Integrator::projective, h60, 5, true, false, true},
      {"projective 1/60 x 10, adaptive weights", Integrator::projective, h60, 10, true, false, true},
      {"projective 1/60 x 5, contacts after the step", Integrator::projective, h60, 5, false, false},
      {"projective 1/24 x 5 + cloth-cloth", Integrator::projective, h24, 5, true, true},
      {"projective 1/60 x 5 + cloth-cloth", Integrator::projective, h60, 5, true, true},
  };
  if (!quick) {
    settings.push_back({"implicit 5 ms", Integrator::implicit_euler, 0.005, 0, false, false});
    settings.push_back({"implicit 1/60", Integrator::implicit_euler, h60, 0, false, false});
    settings.push_back({"implicit 5 ms + cloth-cloth", Integrator::implicit_euler, 0.005, 0, false, true});
  }
  std::printf("# %s, one thread; scene %s%s%s\n", bench::cpu_model().c_str(), scene_path.c_str(),
              fabric.empty() ? "" : ", fabric ", fabric.c_str());
  std::printf("%-46s %10s %8s %8s %8s %8s %17s %17s %9s %9s\n", "setting", "CPU s/fr", "max", "p99",
              "mean", "shear", "last 0.5 s: mean", "worst", "closest", "crossings");
  std::ofstream out;
  if (!csv.empty()) {
    out.open(csv);
    if (!out) {
      std::fprintf(stderr, "bench_cloth_sphere: %s: cannot write\n", csv.c_str());
      return 3;
    }
    out << "fabric,setting,integrator,dt,iterations,contacts_inside,cloth_collisions,cpu_seconds_per_frame,"
           "max_strain,p99_strain,mean_strain,max_shear_strain,closest_mm,crossings_end,stopped,"
           "late_mean_max_strain,late_mean_max_shear_strain,late_worst_max_strain,"
           "late_worst_max_shear_strain\n";
  }
  const int frames = static_cast<int>(scene.run.duration * scene.run.fps + 0.5);
  for (const Setting& s : settings) {
    SimulationOptions o = scene.simulation;
    o.integrator = s.integrator;
    o.dt = s.dt;
    if (s.iterations > 0) o.projective.iterations = s.iterations;
    o.projective.collisions = s.contacts_inside;
    o.self_collision = s.cloth_collisions;
    o.projective.adaptive_weights = s.adaptive_weights;
    ClothSimulator sim(scene.model, o);
    sim.set_pinned(scene.pins);
    double strain_cpu = 0.0;  // spent measuring frames, not stepping
    Strains late_mean, late_worst;  // over the frames of the last 0.5 s (max and shear_max)
    int late_frames = 0;
    RunOptions run_options = scene.run;
    run_options.rest.enabled = false;
    const double t0 = bench::thread_cpu_seconds();
    const RunResult result = run(sim, run_options, [&](int frame) {
      if (frame <= frames - scene.run.fps / 2 + 0.5) return;  // the last 12 frames (0.5 s), untimed
      const double f0 = bench::thread_cpu_seconds();
      const Strains e = strains(scene.model.springs, sim.positions());
      late_mean.max += e.max, late_mean.shear_max += e.shear_max, ++late_frames;
      late_worst.max = std::max(late_worst.max, e.max);
      late_worst.shear_max = std::max(late_worst.shear_max, e.shear_max);
      strain_cpu += bench::thread_cpu_seconds() - f0;
    });
    const double cpu = bench::thread_cpu_seconds() - t0 - strain_cpu;
    const std::string stopped = result.stopped_reason;
    if (late_frames > 0) late_mean.max /= late_frames, late_mean.shear_max /= late_frames;
    const double per_frame = cpu / frames;
    const Strains e = strains(scene.model.springs, sim.positions());
    double closest = 1e300;
    Eigen::Vector3d n;
    for (int i = 0; i < sim.positions().rows(); ++i)
      closest = std::min(closest, o.colliders.front().distance(sim.positions().row(i).transpose(), &n));
    const int crossings = sim.intersections();
    std::printf("%-46s %10.4f %8.4f %8.4f %8.4f %8.4f %8.4f/%8.4f %8.4f/%8.4f %7.2fmm %9d %s\n",
                s.name.c_str(), per_frame, e.max, e.p99, e.mean, e.shear_max, late_mean.max,
                late_mean.shear_max, late_worst.max, late_worst.shear_max, closest * 1e3, crossings,
                stopped == "duration reached" ? "" : stopped.c_str());
    if (out) {
      out << fabric_label << ",\"" << s.name << "\"," << (s.integrator == Integrator::projective ? "projective" : "implicit") << ','
          << s.dt << ',' << s.iterations << ',' << s.contacts_inside << ',' << s.cloth_collisions << ','
          << per_frame << ',' << e.max << ',' << e.p99 << ',' << e.mean << ',' << e.shear_max << ','
          << closest * 1e3 << ',' << crossings << ",\"" << stopped << "\",";
      if (late_frames > 0)  // a run that failed before the last 0.5 s has no such figures: empty
        out << late_mean.max << ',' << late_mean.shear_max << ',' << late_worst.max << ','
            << late_worst.shear_max;
      else
        out << ",,,";
      out << '\n';
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {  // a bad scene path or fabric name: one line, exit 2
    std::fprintf(stderr, "bench_cloth_sphere: %s\n", e.what());
    return 2;
  }
}
