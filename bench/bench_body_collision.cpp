// Body collision cost: a square cloth (a cape) dropped over the gc_mean_all body (47.5k triangles)
// with 5k, 10k and 20k particles, implicit Euler at 1/240 s; time per step split by phase
// (integrator = forces + solve, constraints, body collision), averaged over the steps after first
// contact. Goal (issue 7): body collision under 1 ms per step for 10k particles on one core.
// Usage: bench_body_collision [--steps N] [--csv FILE]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/mesh/io.h"

using namespace dresskit;

int main(int argc, char** argv) {
  int steps = 240;
  std::string csv;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--steps") && a + 1 < argc) steps = std::atoi(argv[++a]);
    else if (!std::strcmp(argv[a], "--csv") && a + 1 < argc) csv = argv[++a];
  }
  const TriangleMesh body = load_mesh(std::string(DRESSKIT_DEFAULT_DATA_DIR) + "/bodies/gc_mean_all.obj");
  const auto t0 = std::chrono::steady_clock::now();
  auto distance = std::make_shared<const MeshDistance>(body);
  const double build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("body: %d triangles; distance grid %dx%dx%d (cell %.1f mm) built in %.3f s, %.1f MB\n", body.num_faces(),
              distance->report().grid[0], distance->report().grid[1], distance->report().grid[2],
              distance->report().cell * 1e3, build, distance->report().memory_bytes / 1e6);
  std::ofstream out;
  if (!csv.empty()) {
    out.open(csv);
    out << "particles,steps,integrate_ms,constraints_ms,collision_ms,collision_us_per_particle,max_strain\n";
  }
  std::printf("%9s %6s %13s %15s %13s %10s\n", "particles", "steps", "integrate ms", "constraints ms", "collision ms",
              "max strain");
  for (int side : {71, 100, 141}) {
    const TriangleMesh grid = make_grid({0.8, 0.8}, {side, side}, {0.0, 1.78, 0.0}, Eigen::Vector3d::UnitY());
    SimulationOptions o;
    o.dt = 1.0 / 240.0;
    o.air_damping = 0.3;
    o.colliders.push_back(Collider::mesh(distance, 0.5));
    ClothSimulator sim(build_cloth(grid, fabric_by_name("11oz-black-denim")), o);
    double integrate = 0, constraints = 0, collision = 0;
    int counted = 0;
    for (int s = 0; s < steps; ++s) {
      const StepResult r = sim.step();
      if (!r.ok) {
        std::printf("  step %d failed: %s\n", s, r.failure.c_str());
        break;
      }
      if (s < steps / 4) continue;  // falling: no contact yet
      integrate += r.integrate_seconds;
      constraints += r.constraint_seconds;
      collision += r.collision_seconds;
      ++counted;
    }
    const int n = side * side;
    const double c = counted ? 1e3 / counted : 0.0;
    std::printf("%9d %6d %13.3f %15.3f %13.3f %10.3f\n", n, counted, integrate * c, constraints * c, collision * c,
                sim.max_strain());
    if (out) {
      out << n << ',' << counted << ',' << integrate * c << ',' << constraints * c << ',' << collision * c << ','
          << collision * c * 1e3 / n << ',' << sim.max_strain() << '\n';
    }
  }
  return 0;
}
