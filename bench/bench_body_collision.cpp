// Collision cost: time per step split by phase — forces (and the implicit system's
// assembly), solve, layer guard and length limits, seams, body collision, cloth–cloth collision —
// for (1) a square denim cape dropped over the gc_mean_all body (47.5k triangles) with 5k, 10k and
// 20k particles, and (2) the sewn tube of examples/collisions at three resolutions (its seams
// phase). Implicit Euler; the means are over the steps after the first quarter (the cape is falling
// before). Goal: body collision under 1 ms per step for 10k particles on one core. Usage:
// bench_body_collision [--steps N] [--capes 71,100,141] [--tubes 1,2,3] [--csv FILE] (cape sides in
// particles, tube resolution multiples; "none" leaves a kind out)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/run.h"
#include "dresskit/cloth/scene.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/mesh/io.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace {

struct Phases {
  double forces = 0, solve = 0, limits = 0, seams = 0, body = 0, self = 0;
  int steps = 0, failed_at = -1;
  std::string failure;
};

// The phases of the steps after the first quarter of `steps` steps of the simulator's dt.
Phases run_steps(ClothSimulator& sim, int steps) {
  Phases p;
  RunOptions o;
  o.duration = steps * sim.options().dt;
  o.rest.enabled = false;
  int taken = 0;
  const RunResult result = run(sim, o, {}, [&](const StepResult& r) {
    if (taken++ < steps / 4) return;
    p.forces += r.force_seconds;
    p.solve += r.integrate_seconds - r.force_seconds;
    p.limits += r.constraint_seconds;
    p.seams += r.seam_seconds;
    p.body += r.collision_seconds;
    p.self += r.self_collision_seconds;
    ++p.steps;
  });
  if (!result.ok) {
    p.failed_at = taken;
    p.failure = result.failure;
  }
  return p;
}

void print(std::ofstream& out, const char* scene, int n, const Phases& p, const ClothSimulator& sim,
           int inside) {
  const double c = p.steps ? 1e3 / p.steps : 0.0;
  std::printf("%-6s %9d %6d %9.2f %9.2f %9.2f %9.3f %9.3f %9.2f %8.3f %6d %6d%s\n", scene, n,
              p.steps, p.forces * c, p.solve * c, p.limits * c, p.seams * c, p.body * c, p.self * c,
              sim.max_strain(), sim.intersections(), inside,
              p.failed_at >= 0
                  ? ("  failed at step " + std::to_string(p.failed_at) + ": " + p.failure).c_str()
                  : "");
  if (out) {
    out << scene << ',' << n << ',' << p.steps << ',' << p.forces * c << ',' << p.solve * c << ','
        << p.limits * c << ',' << p.seams * c << ',' << p.body * c << ',' << p.self * c << ','
        << sim.max_strain() << ',' << sim.intersections() << ',' << inside << '\n';
  }
}

/// "71,100" -> {71, 100}; "" or "none" -> {}.
std::vector<int> parse_list(const std::string& text) {
  std::vector<int> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const int v = std::atoi(text.substr(start, end - start).c_str());
    if (v > 0) out.push_back(v);
    start = end + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 240;
  std::string csv;
  std::vector<int> capes = {71, 100, 141}, tubes = {1, 2, 3};
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--steps") && a + 1 < argc)
      steps = std::atoi(argv[++a]);
    else if (!std::strcmp(argv[a], "--capes") && a + 1 < argc)
      capes = parse_list(argv[++a]);
    else if (!std::strcmp(argv[a], "--tubes") && a + 1 < argc)
      tubes = parse_list(argv[++a]);
    else if (!std::strcmp(argv[a], "--csv") && a + 1 < argc)
      csv = argv[++a];
  }
  const TriangleMesh body =
      load_mesh(std::string(DRESSKIT_DEFAULT_DATA_DIR) + "/bodies/gc_mean_all.obj");
  const auto t0 = std::chrono::steady_clock::now();
  auto distance = std::make_shared<const MeshDistance>(body);
  const double build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "body: %d triangles; distance grid %dx%dx%d (cell %.1f mm) built in %.3f s, %.1f MB\n",
      body.num_faces(), distance->report().grid[0], distance->report().grid[1],
      distance->report().grid[2], distance->report().cell * 1e3, build,
      distance->report().memory_bytes / 1e6);
  std::ofstream out;
  if (!csv.empty()) {
    out.open(csv);
    out << "scene,particles,steps,forces_ms,solve_ms,limits_ms,seams_ms,body_collision_ms,cloth_"
           "collision_ms,"
           "max_strain,intersections,inside_body\n";
  }
  std::printf("ms per step; inside = particles inside the body by its distance at the end\n");
  std::printf("%-6s %9s %6s %9s %9s %9s %9s %9s %9s %8s %6s %6s\n", "scene", "particles", "steps",
              "forces", "solve", "limits", "seams", "body", "cloth", "strain", "cross", "inside");
  for (int side : capes) {
    const TriangleMesh grid =
        make_grid({0.8, 0.8}, {side, side}, {0.0, 1.78, 0.0}, Eigen::Vector3d::UnitY());
    SimulationOptions o;
    o.dt = 1.0 / 240.0;
    o.air_damping = 0.3;
    o.strain_limiting = true;
    o.self_collision = true;
    o.colliders.push_back(Collider::mesh(distance, 0.5));
    ClothSimulator sim(build_cloth(grid, fabric_by_name("11oz-black-denim")), o);
    const Phases p = run_steps(sim, steps);
    int inside = 0;
    Eigen::Vector3d n;
    for (int i = 0; i < sim.positions().rows(); ++i)
      inside += distance->distance(sim.positions().row(i).transpose(), &n) < 0.0;
    print(out, "cape", side * side, p, sim, inside);
  }
  // The sewn tube at three resolutions: the same panels, finer grids.
  for (int scale : tubes) {
    ClothScene scene =
        load_cloth_scene(std::string(DRESSKIT_SOURCE_DIR) + "/examples/collisions/sewn_tube.json");
    if (scale > 1) {
      // Rebuild the two panels with `scale`× the resolution and sew their sides again.
      const int nx = 36 * scale + 1, ny = 40 * scale + 1;
      TriangleMesh both;
      const TriangleMesh top =
          make_grid({0.36, 0.4}, {nx, ny}, {0, 0.62, 0}, Eigen::Vector3d::UnitY());
      const TriangleMesh bottom =
          make_grid({0.36, 0.4}, {nx, ny}, {0, 0.38, 0}, -Eigen::Vector3d::UnitY());
      const int half = static_cast<int>(top.V.rows());
      both.V.resize(2 * half, 3);
      both.V << top.V, bottom.V;
      both.F.resize(2 * top.F.rows(), 3);
      both.F << top.F, (bottom.F.array() + half).matrix();
      both.quads.resize(2 * top.quads.rows(), 4);
      both.quads << top.quads, (bottom.quads.array() + half).matrix();
      scene.model = build_cloth(both, fabric_by_name("gray-interlock"));
      for (int side : {0, nx - 1}) {
        std::vector<int> a, b;
        for (int j = 0; j < ny; ++j)
          a.push_back(j * nx + side), b.push_back(half + (ny - 1 - j) * nx + side);
        const int first = scene.model.seams.size();
        add_seam_chains(scene.model.seams, scene.model.rest_positions, a, b,
                        {default_stitch_stiffness(scene.model.springs), 1.0});
        cap_stitches_by_acceleration(scene.model.seams, first, scene.model.mass, 20.0);
      }
    }
    ClothSimulator sim(scene.model, scene.simulation);
    const Phases p = run_steps(sim, steps);
    print(out, "tube", static_cast<int>(scene.model.rest_positions.rows()), p, sim, 0);
  }
  return 0;
}
