#include "dresskit/mesh/names.h"
#include "dresskit/thickness/heat1d.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "dresskit/mesh/errors.h"


namespace dresskit::thickness {
namespace {

void require_positive(double value, const char* field) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    std::ostringstream out;
    out << "heat problem: " << field << " = " << value << " (must be a positive number)";
    throw InputError(out.str());
  }
}

/// One step of the θ-scheme for the interior nodes: (1 + 2θr) T'_i − θr (T'_{i−1} + T'_{i+1}) =
/// T_i + (1 − θ) r (T_{i−1} − 2 T_i + T_{i+1}); θ = 0 explicit, 1 implicit, 1/2 Crank–Nicolson.
/// The boundary nodes 0 and N hold their values.
class ThetaStepper {
 public:
  ThetaStepper(int cells, double r, double theta) : r_(r), theta_(theta) {
    const int n = cells - 1;
    sub_ = Eigen::VectorXd::Constant(n, -theta * r);
    diag_ = Eigen::VectorXd::Constant(n, 1.0 + 2.0 * theta * r);
    sup_ = sub_;
    rhs_.resize(n);
  }
  void step(Eigen::VectorXd& T) {
    const int n = static_cast<int>(rhs_.size());
    for (int k = 0; k < n; ++k) {
      const int i = k + 1;
      rhs_[k] = T[i] + (1.0 - theta_) * r_ * (T[i - 1] - 2.0 * T[i] + T[i + 1]);
    }
    if (theta_ == 0.0) {
      T.segment(1, n) = rhs_;
      return;
    }
    rhs_[0] += theta_ * r_ * T[0];
    rhs_[n - 1] += theta_ * r_ * T[n + 1];
    solve_tridiagonal(sub_, diag_, sup_, rhs_);
    T.segment(1, n) = rhs_;
  }

 private:
  double r_, theta_;
  Eigen::VectorXd sub_, diag_, sup_, rhs_;
};

}  // namespace

const NameTable<HeatScheme> kHeatSchemes = {{"explicit", HeatScheme::explicit_euler},
    {"implicit", HeatScheme::implicit_euler}, {"crank-nicolson", HeatScheme::crank_nicolson},
    {"cn", HeatScheme::crank_nicolson}};
HeatScheme parse_heat_scheme(const std::string& text) { return parse_name(text, kHeatSchemes, "heat scheme"); }
std::string to_string(HeatScheme scheme) { return name_of(scheme, kHeatSchemes); }

void solve_tridiagonal(const Eigen::VectorXd& sub, const Eigen::VectorXd& diag,
                       const Eigen::VectorXd& sup, Eigen::VectorXd& rhs) {
  const Eigen::Index n = diag.size();
  Eigen::VectorXd c(n);  // modified super-diagonal
  double pivot = diag[0];
  c[0] = sup[0] / pivot;
  rhs[0] /= pivot;
  for (Eigen::Index i = 1; i < n; ++i) {
    pivot = diag[i] - sub[i] * c[i - 1];
    c[i] = sup[i] / pivot;
    rhs[i] = (rhs[i] - sub[i] * rhs[i - 1]) / pivot;
  }
  for (Eigen::Index i = n - 2; i >= 0; --i) rhs[i] -= c[i] * rhs[i + 1];
}

HeatResult solve_heat(const HeatProblem& p, const HeatOptions& o) {
  require_positive(p.diffusivity, "diffusivity");
  require_positive(p.length, "length");
  require_positive(p.duration, "duration");
  if (o.cells < 2) throw InputError("heat grid: cells = " + std::to_string(o.cells) + " (must be ≥ 2)");
  if (o.steps < 1) throw InputError("heat grid: steps = " + std::to_string(o.steps) + " (must be ≥ 1)");
  for (double t : {p.t_skin, p.t_env, p.t_initial})
    if (!std::isfinite(t)) throw InputError("heat problem: a temperature is not a finite number");

  const auto start = std::chrono::steady_clock::now();
  const double dx = p.length / o.cells;
  double dt = p.duration / o.steps;
  int substeps = 1;
  double r = p.diffusivity * dt / (dx * dx);
  if (o.scheme == HeatScheme::explicit_euler && r > 0.5) {
    if (!o.explicit_substep) {
      std::ostringstream out;
      out << "explicit heat step: α Δt / Δx² = " << r
          << " is beyond the stability limit 1/2 (more steps, fewer cells or another scheme)";
      throw InputError(out.str());
    }
    substeps = static_cast<int>(std::ceil(r / 0.5));
    r /= substeps;
  }

  HeatResult result;
  result.x = Eigen::VectorXd::LinSpaced(o.cells + 1, 0.0, p.length);
  Eigen::VectorXd T = Eigen::VectorXd::Constant(o.cells + 1, p.t_initial);
  T[0] = p.t_skin;
  T[o.cells] = p.t_env;
  std::vector<Eigen::VectorXd> recorded;
  if (o.record_every > 0) {
    result.times.push_back(0.0);
    recorded.push_back(T);
  }

  const double theta = o.scheme == HeatScheme::explicit_euler   ? 0.0
                       : o.scheme == HeatScheme::implicit_euler ? 1.0
                                                                : 0.5;
  ThetaStepper stepper(o.cells, r, theta);
  int startup = o.scheme == HeatScheme::crank_nicolson ? std::max(0, o.startup_half_steps) : 0;
  startup -= startup % 2;  // whole steps only
  ThetaStepper half_implicit(o.cells, 0.5 * r, 1.0);
  for (int s = 1; s <= o.steps; ++s) {
    if (2 * s <= startup) {
      half_implicit.step(T);
      half_implicit.step(T);
      result.steps_taken += 2;
    } else {
      for (int k = 0; k < substeps; ++k) stepper.step(T);
      result.steps_taken += substeps;
    }
    if (o.record_every > 0 && (s % o.record_every == 0 || s == o.steps)) {
      result.times.push_back(s * dt);
      recorded.push_back(T);
    }
  }
  result.temperature = T;
  result.courant = r;
  if (!recorded.empty()) {
    result.surface.resize(static_cast<Eigen::Index>(recorded.size()), o.cells + 1);
    for (std::size_t k = 0; k < recorded.size(); ++k)
      result.surface.row(static_cast<Eigen::Index>(k)) = recorded[k].transpose();
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

double heat_semi_infinite(const HeatProblem& p, double x, double t) {
  if (t <= 0.0) return x <= 0.0 ? p.t_skin : p.t_initial;
  return p.t_initial + (p.t_skin - p.t_initial) * std::erfc(x / (2.0 * std::sqrt(p.diffusivity * t)));
}

double heat_finite_slab(const HeatProblem& p, double x, double t) {
  // T = steady line + Σ b_n sin(nπx/L) exp(−α (nπ/L)² t), with
  // b_n = 2/(nπ) [(T_initial − T_skin)(1 − (−1)^n) + (T_env − T_skin)(−1)^n].
  const double L = p.length;
  double T = p.t_skin + (p.t_env - p.t_skin) * x / L;
  const double range = std::abs(p.t_skin - p.t_env) + std::abs(p.t_initial - p.t_skin) + 1e-300;
  for (int n = 1; n < 1000000; ++n) {
    const double sign = n % 2 == 0 ? 1.0 : -1.0;
    const double b = 2.0 / (n * M_PI) *
                     ((p.t_initial - p.t_skin) * (1.0 - sign) + (p.t_env - p.t_skin) * sign);
    const double decay = std::exp(-p.diffusivity * std::pow(n * M_PI / L, 2) * t);
    T += b * std::sin(n * M_PI * x / L) * decay;
    if (std::abs(b) * decay < 1e-14 * range && n > 2) break;
  }
  return T;
}

double crossing_depth(const Eigen::VectorXd& x, const Eigen::VectorXd& T, double threshold) {
  for (Eigen::Index i = 0; i + 1 < x.size(); ++i) {
    const double a = T[i] - threshold, b = T[i + 1] - threshold;
    if (a != b && ((a >= 0.0 && b < 0.0) || (a <= 0.0 && b > 0.0))) {
      const double f = (T[i] - threshold) / (T[i] - T[i + 1]);
      return x[i] + f * (x[i + 1] - x[i]);
    }
  }
  return -1.0;
}

}  // namespace dresskit::thickness
