// Stability envelope: for each integrator, spring stiffness k (normalised by particle
// mass, 1e1 … 1e8 N/m per kg) × time step (1/1000 … 1/24 s): a 10×10 cloth of unit-mass particles
// pinned at two corners, without gravity, released from a random perturbation of 10 % of the
// spacing, runs for 1 s undamped (projective dynamics with backward Euler, BDF2, TR-BDF2 and the
// implicit midpoint rule: "projective-bdf2", "projective-tr_bdf2", "projective-midpoint"; TR-BDF2
// with adaptive weights: "projective-tr_bdf2-aw"). Unstable
// = a step fails (NaN, strain over 100 %, solver failure) or the total energy grows beyond 10× its
// initial value (the exact solution keeps it constant). Writes CSV to the given path and prints the
// largest stable step per stiffness. Usage: bench_cloth_stability
// [out.csv=out/bench/stability_envelope.csv]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "dresskit/cloth/run.h"

using namespace dresskit;
using namespace dresskit::cloth;
using namespace dresskit::mesh;

int main(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "out/bench/stability_envelope.csv";
  std::filesystem::create_directories(std::filesystem::path(csv_path).parent_path());
  std::ofstream csv(csv_path);
  csv << "integrator,k_per_mass,dt,stable,reason,steps\n";
  const int n = 10;
  const TriangleMesh grid = make_grid({0.9, 0.9}, {n, n}, {0, 0, 0}, {0, 0, 1});
  ClothModel base = build_cloth(grid, fabric_by_name("gray-interlock"));
  base.mass.setOnes();  // unit masses: k is then k / m
  const double dts[] = {1.0 / 1000, 1.0 / 500, 1.0 / 240, 1.0 / 120, 1.0 / 60, 1.0 / 24};
  struct Variant {
    Integrator integrator;
    TimeScheme scheme;
    bool adaptive_weights = false;
  };
  for (const Variant variant : {Variant{Integrator::symplectic_euler, TimeScheme::backward_euler},
                                Variant{Integrator::implicit_euler, TimeScheme::backward_euler},
                                Variant{Integrator::newton, TimeScheme::backward_euler},
                                Variant{Integrator::projective, TimeScheme::backward_euler},
                                Variant{Integrator::projective, TimeScheme::bdf2},
                                Variant{Integrator::projective, TimeScheme::tr_bdf2},
                                Variant{Integrator::projective, TimeScheme::midpoint},
                                Variant{Integrator::projective, TimeScheme::tr_bdf2, true}}) {
    const Integrator integrator = variant.integrator;
    const std::string name =
        to_string(integrator) +
        (variant.scheme == TimeScheme::backward_euler ? "" : "-" + to_string(variant.scheme)) +
        (variant.adaptive_weights ? "-aw" : "");
    std::printf("%s: largest stable step per stiffness\n", name.c_str());
    for (int e = 1; e <= 8; ++e) {
      const double k = std::pow(10.0, e);
      ClothModel model = base;
      for (int s = 0; s < model.springs.size(); ++s) {
        if (model.springs.type[s] == SpringType::bending) continue;
        model.springs.k_rest[s] = model.springs.k_knee[s] = k;  // linear springs of stiffness k
      }
      double largest = 0.0;
      for (double dt : dts) {
        SimulationOptions o;
        o.integrator = integrator;
        o.projective.time_scheme = variant.scheme;
        o.projective.adaptive_weights = variant.adaptive_weights;
        o.dt = dt;
        o.linear.cg_max_iterations = 2000;
        o.gravity.setZero();
        // The integrator's own stability at this step: no halving of failed steps, and no strain
        // limiting (its corrections of the 10 % perturbation, as velocity, would be the energy).
        o.adaptive = false;
        o.strain_limiting = false;
        ClothSimulator sim(model, o);
        sim.set_pinned({n * (n - 1), n * n - 1});
        Eigen::MatrixX3d x = model.rest_positions;
        std::srand(1);
        for (int i = 0; i < x.rows() - 0; ++i)
          for (int c = 0; c < 3; ++c) x(i, c) += 0.1 * 0.1 * (2.0 * std::rand() / RAND_MAX - 1.0);
        for (int p : {n * (n - 1), n * n - 1}) x.row(p) = model.rest_positions.row(p);
        sim.set_state(x, Eigen::MatrixX3d::Zero(x.rows(), 3));
        const double e0 = sim.kinetic_energy() + sim.elastic_energy();
        const double bound = 10.0 * e0;
        RunOptions run_options;
        run_options.duration = 1.0;
        run_options.rest.enabled = false;
        run_options.fail_if = [&] {
          return sim.kinetic_energy() + sim.elastic_energy() > bound ? "energy blow-up" : "";
        };
        const RunResult result = run(sim, run_options);
        const bool stable = result.ok;
        std::string reason = result.ok ? "ok" : result.failure;
        const int done = result.totals.steps;
        for (char& c : reason) c = c == ',' ? ';' : c;
        csv << name << "," << k << "," << dt << "," << stable << "," << reason << "," << done
            << "\n";
        if (stable) largest = std::max(largest, dt);
      }
      std::printf("  k/m = 1e%d: %s\n", e,
                  largest > 0 ? ("dt <= 1/" + std::to_string(std::lround(1 / largest))).c_str()
                              : "no step stable");
    }
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
