// Projective dynamics' global solve by L-BFGS on the incremental potential (projective_internal.h).
#include <algorithm>
#include <cmath>
#include <vector>

#include "dresskit/cloth/simulator.h"
#include "dresskit/mesh/errors.h"
#include "projective_internal.h"
#include "simulator_internal.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {
using namespace pd;

// Quasi-Newton (L-BFGS) on the same incremental potential, with the projective matrix as the
// initial Hessian (Liu, Bouaziz & Kavan 2017, "Quasi-Newton Methods for Real-Time Simulation of
// Hyperelastic Materials"): the direction is the two-loop recursion over the last m pairs of
// iterate and gradient changes around one solve with the prefactored matrix, and a backtracking
// (Armijo) line search on the potential keeps every iteration a descent. Without history the
// direction −A⁻¹∇G is exactly a local/global iteration, so this is projective dynamics with the
// curvature it misses (the softer-than-w springs of a lightly stretched cloth, the stiffer ones
// past the knee) learnt from the last iterations.
int ProjectiveDynamics::lbfgs(const ClothSimulator& sim, const Eigen::MatrixX3d& target,
                              const Eigen::MatrixX3d& air_base, const Eigen::Vector3d& wind,
                              const Eigen::MatrixX3d& x0, RowX3& X) {
  const ProjectiveFactor& P = *current_;
  const double h = P.h, c = sim.options_.air_damping;
  const int n = static_cast<int>(sim.x_.rows());
  // G(x) = Σ a/2 |x|² − b·x + E(x) (+ a constant) with a = m/h² + c m/h and
  // b = m/h² target + c m/h (air_base + h wind) + m g.
  RowX3 b(n, 3);
  for (int v = 0; v < n; ++v) {
    const double m = sim.model_.mass(v);
    b.row(v) = (m / (h * h)) * target.row(v) +
               (c * m / h) * (air_base.row(v) + h * wind.transpose()) +
               m * sim.options_.gravity.transpose();
    if (sim.pinned_[v]) X.row(v) = x0.row(v);
  }
  const double beyond = sim.options_.dynamic_stiffness ? 1.0 + sim.options_.strain_limit : HUGE_VAL;
  const double* rest = sim.model_.rest_positions.data();
  const bool seams = sim.model_.seams.size() > 0;
  auto energy_gradient = [&](const RowX3& Xc, RowX3& g) {
    const double* x = Xc.data();
    double* G = g.data();
    double energy = 0.0;
    for (int v = 0; v < n; ++v) {
      const double a = P.inertia[v];
      for (int d = 0; d < 3; ++d) {  // a/2 |x − b/a|²: no cancellation against the large |x|²
        const double r = a * x[3 * v + d] - b(v, d);
        G[3 * v + d] = r;
        energy += 0.5 * r * r / a;
      }
    }
    for (const LocalSpring& q : P.springs) {
      const int i = q.i, j = q.j;
      double e[3] = {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]};
      const double L = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      const double strain = L * q.inv_L0 - 1.0;
      energy += law_energy(q, strain);
      double t = law_k(q, strain) * strain * q.L0;
      if (L > beyond * q.L0) {
        // Dynamic stiffness: tension × L/L0 beyond the limit, a function of L alone; its extra
        // energy ∫ t(s)(s/L0 − 1) ds from the limit, by two-point Gauss.
        const double lo = beyond * q.L0, mid = 0.5 * (L + lo),
                     half = 0.5 * (L - lo) / std::sqrt(3.0);
        for (double s_ : {mid - half, mid + half}) {
          const double es = s_ * q.inv_L0 - 1.0;
          energy += 0.5 * (L - lo) * law_k(q, es) * es * q.L0 * es;
        }
        t *= L * q.inv_L0;
      }
      if (L < 1e-12) continue;  // no direction: no force
      const double scale = t / L;
      for (int a = 0; a < 3; ++a) {
        G[3 * j + a] += scale * e[a];
        G[3 * i + a] -= scale * e[a];
      }
    }
    (void)rest;
    if (seams) {
      const Eigen::MatrixX3d xs = Xc;
      Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(n, 3);
      add_seam_forces(sim.model_.seams, xs, f);
      g -= f;
      energy += seam_energy(sim.model_.seams, xs);
    }
    for (int v : P.pinned_list) g.row(v).setZero();
    return energy;
  };
  const int m = sim.options_.projective.lbfgs_history;
  std::vector<RowX3> S(static_cast<std::size_t>(m)), Y(static_cast<std::size_t>(m));
  std::vector<double> inv_sy(static_cast<std::size_t>(m)), alpha(static_cast<std::size_t>(m));
  int stored = 0, newest = -1;
  RowX3 g(n, 3), g_new(n, 3), p(n, 3), X_new(n, 3);
  double G = energy_gradient(X, g);
  int iterations = 0;
  for (int it = 0; it < sim.options_.projective.iterations; ++it) {
    // Two-loop recursion: p = −H ∇G with H the L-BFGS inverse Hessian around A⁻¹.
    p = -g;
    for (int k = 0; k < stored; ++k) {
      const int slot = (newest - k + m) % m;
      alpha[slot] = inv_sy[slot] * (S[slot].array() * p.array()).sum();
      p -= alpha[slot] * Y[slot];
    }
    if (P.single_precision)
      P.single.solve_in_place(p.data());
    else
      P.full.solve_in_place(p.data());
    for (int k = stored - 1; k >= 0; --k) {
      const int slot = (newest - k + m) % m;
      const double beta = inv_sy[slot] * (Y[slot].array() * p.array()).sum();
      p += (alpha[slot] - beta) * S[slot];
    }
    for (int v : P.pinned_list) p.row(v).setZero();
    double slope = (g.array() * p.array()).sum();
    if (!(slope < 0.0)) {  // not a descent direction: forget the history, take the plain step
      stored = 0;
      p = -g;
      if (P.single_precision)
        P.single.solve_in_place(p.data());
      else
        P.full.solve_in_place(p.data());
      for (int v : P.pinned_list) p.row(v).setZero();
      slope = (g.array() * p.array()).sum();
    }
    double step = 1.0, G_new = G;
    for (int search = 0; search < 10; ++search) {
      X_new = X + step * p;
      G_new = energy_gradient(X_new, g_new);
      // Armijo, with the potential's rounding (a few ulps of its terms) counted as no change.
      if (G_new <= G + 1e-4 * step * slope + 1e-13 * std::abs(G)) break;
      step *= 0.5;
    }
    iterations = it + 1;
    if (!(G_new <= G + 1e-13 * std::abs(G))) break;  // no decrease: X is as good as it gets
    const double moved = std::abs(step) * p.rowwise().norm().maxCoeff();
    // History: s = step p, y = ∇G change; kept when the curvature s·y is positive.
    const int slot = (newest + 1) % m;
    S[slot] = step * p;
    Y[slot] = g_new - g;
    const double sy = (S[slot].array() * Y[slot].array()).sum();
    if (sy > 1e-300) {
      inv_sy[slot] = 1.0 / sy;
      newest = slot;
      stored = std::min(stored + 1, m);
    }
    X.swap(X_new);
    g.swap(g_new);
    G = G_new;
    if (moved < sim.options_.iteration_tolerance) break;
  }
  return iterations;
}

}  // namespace dresskit::cloth
