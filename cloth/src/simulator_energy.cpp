// ClothSimulator's measures (energies, strains, blow-up reports, static residual) and settling.
#include "dresskit/cloth/simulator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/spring_kernels.h"
#include "simulator_internal.h"

namespace dresskit::cloth {
using detail::row;

double ClothSimulator::elastic_energy() const {
  const SpringSet& s = model_.springs;
  double e = 0.0;
  for (int k = 0; k < s.size(); ++k) e += spring_energy(s.law(k), s.rest_length[k], row(x_, s.i[k]), row(x_, s.j[k]));
  return e + seam_energy(model_.seams, x_);
}

double ClothSimulator::kinetic_energy() const {
  return 0.5 * (model_.mass.array() * v_.rowwise().squaredNorm().array()).sum();
}

double ClothSimulator::gravity_energy() const { return -(model_.mass.transpose() * (x_ * options_.gravity))(0); }

namespace {
template <typename Reduce>
double over_structural_strains(const SpringSet& s, const Eigen::MatrixX3d& x, double init, Reduce reduce) {
  double acc = init;
  for (int k = 0; k < s.size(); ++k) {
    if (s.type[k] != SpringType::structural) continue;
    acc = reduce(acc, (x.row(s.j[k]) - x.row(s.i[k])).norm() / s.rest_length[k] - 1.0);
  }
  return acc;
}
}  // namespace

double ClothSimulator::max_strain() const {
  return over_structural_strains(model_.springs, x_, 0.0, [](double a, double e) { return std::max(a, e); });
}

namespace {
/// The structural spring stretched most at x as blow-up judges it (elongation over the larger of
/// its rest length and `floor`): index and that stretch (−1 and 0 without any).
std::pair<int, double> worst_structural(const SpringSet& s, const Eigen::MatrixX3d& x, double floor) {
  std::pair<int, double> worst{-1, 0.0};
  for (int k = 0; k < s.size(); ++k) {
    if (s.type[k] != SpringType::structural) continue;
    const double e = ((x.row(s.j[k]) - x.row(s.i[k])).norm() - s.rest_length[k]) / std::max(s.rest_length[k], floor);
    if (worst.first < 0 || e > worst.second) worst = {k, e};
  }
  return worst;
}

std::string fixed(double value, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, value);
  return buf;
}
}  // namespace

double blow_up_stretch(const ClothModel& model, const Eigen::MatrixX3d& x) {
  double sum = 0.0;
  for (double L : model.springs.rest_length) sum += L;
  const double floor = 0.25 * sum / std::max(1, model.springs.size());
  return worst_structural(model.springs, x, floor).second;
}

double ClothSimulator::blow_up_stretch(const Eigen::MatrixX3d& x) const {
  return worst_structural(model_.springs, x, blow_up_length_).second;
}

std::string ClothSimulator::blow_up_report(const Eigen::MatrixX3d& x_integrated, double t) const {
  const SpringSet& s = model_.springs;
  const int k = worst_structural(s, x_, blow_up_length_).first;
  const double strain = (x_.row(s.j[k]) - x_.row(s.i[k])).norm() / s.rest_length[k] - 1.0;
  const double after_integrator = (x_integrated.row(s.j[k]) - x_integrated.row(s.i[k])).norm() / s.rest_length[k] - 1.0;
  const bool by_integrator = after_integrator > options_.blow_up_strain;
  return "blow-up at t = " + fixed(t, 4) + " s: structural spring " + std::to_string(k) + " (particles " +
         std::to_string(s.i[k]) + "–" + std::to_string(s.j[k]) + ", rest length " +
         fixed(s.rest_length[k] * 1e3, 2) + " mm) strained " + fixed(100.0 * strain, 1) + " %, beyond " +
         fixed(100.0 * options_.blow_up_strain, 0) + " % (" +
         (by_integrator ? "by the integrator's step"
                        : "by the constraint and contact passes after the integrator (" +
                              fixed(100.0 * after_integrator, 1) + " % before them)") +
         ")";
}

double ClothSimulator::mean_strain() const {
  const int n = model_.springs.count(SpringType::structural);
  if (n == 0) return 0.0;
  return over_structural_strains(model_.springs, x_, 0.0, [](double a, double e) { return a + e; }) / n;
}

// Position-based strain limiting: Gauss–Seidel sweeps that bring each violated spring back to its
// bound (a pinned end stays, free ends move half-way each) until none is violated or the sweep cap
// is reached; velocities follow the corrections. Two kinds of bound: (1 + limit) L0 on the cloth's
// structural and shear springs (with options_.strain_limiting), and the explicit [min, max] of the
// listed springs (a double layer's inter-layer springs: always). Plain Gauss–Seidel converges slowly
// when many springs are taut at once: the heavy hanging cloth of the tests needs up to ~470 sweeps in
// its first fall (ordering the springs by distance from the pins gained only 3 %).
double ClothSimulator::static_residual() const {
  Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(x_.rows(), 3);
  add_spring_forces(x_, Eigen::MatrixX3d::Zero(x_.rows(), 3), f);
  add_penalty_forces(f);
  double worst = 0.0;
  for (int i = 0; i < x_.rows(); ++i) {
    if (pinned_[i]) continue;
    Eigen::Vector3d fi = row(f, i) + model_.mass(i) * options_.gravity;
    // A particle resting on a collider is held by it: only the tangential residual counts.
    for (const Collider& c : options_.colliders) {
      Eigen::Vector3d n;
      if (c.distance(row(x_, i), &n) <= options_.collision_margin * 1.01 && fi.dot(n) < 0.0) {
        fi -= fi.dot(n) * n;
      }
    }
    worst = std::max(worst, fi.norm());
  }
  const double weight = model_.mass.maxCoeff() * std::max(options_.gravity.norm(), 1e-12);
  return worst / weight;
}

SettleResult ClothSimulator::settle(const SettleOptions& o) {
  SettleResult result;
  double previous = elastic_energy(), next_record = 0.0;
  while (result.time < o.max_time) {
    const StepResult r = step();
    if (!r.ok) {
      result.stopped_reason = r.failure;
      break;
    }
    ++result.steps;
    result.time += r.dt;
    const double e = elastic_energy();
    if (result.time >= next_record) {
      result.energy_history.push_back(e);
      next_record += o.record_every;
    }
    const bool calm = std::abs(e - previous) <= o.energy_tolerance * std::abs(e) + 1e-12;
    previous = e;
    if (calm && static_residual() <= o.force_tolerance) {
      result.converged = true;
      result.stopped_reason = "converged";
      break;
    }
  }
  if (result.stopped_reason.empty()) result.stopped_reason = "max_time";
  result.final_residual = static_residual();
  return result;
}

}  // namespace dresskit::cloth
