// Explicit force throughput: spring force evaluations per second on one core for about a
// million springs, double precision, through ClothSimulator::forces() (springs plus per-particle
// terms, into a reused buffer) on a 410×410 grid with structural, shear and bending springs.
// Usage: bench_cloth_throughput [repetitions=20]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "dresskit/cloth/simulator.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  // 410×410 vertices: about 0.33 M springs of each kind, 1.0 M in all.
  const TriangleMesh grid = make_grid({1.0, 1.0}, {410, 410}, {0, 0, 0}, {0, 0, 1});
  ClothModel model = build_cloth(grid, fabric_by_name("gray-interlock"));
  SimulationOptions o;
  ClothSimulator sim(model, o);
  // Stretch the cloth a little so that every spring is in a non-trivial segment of its law.
  Eigen::MatrixX3d x = model.rest_positions * 1.05;
  sim.set_state(x, Eigen::MatrixX3d::Zero(x.rows(), 3));
  const int springs = model.springs.size();
  std::vector<double> seconds;
  double checksum = 0.0;
  Eigen::MatrixX3d f;  // reused, as a stepper does
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    sim.forces(f);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    checksum += f.sum();
  }
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  std::printf("vertices %ld, springs %d (structural %d, shear %d, bending %d)\n", static_cast<long>(x.rows()), springs,
              model.springs.count(SpringType::structural), model.springs.count(SpringType::shear),
              model.springs.count(SpringType::bending));
  std::printf("forces(): median %.2f ms over %d runs -> %.1f M spring evaluations per second (goal 100)\n",
              median * 1e3, reps, springs / median / 1e6);
  std::printf("(checksum %.3g)\n", checksum);
  return 0;
}
