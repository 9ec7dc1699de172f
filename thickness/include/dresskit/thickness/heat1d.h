#pragma once
// One-dimensional transient heat conduction through a slab, perpendicular to the skin:
//   ∂T/∂t = α ∂²T/∂x²,  0 < x < L,  T(0, t) = T_skin,  T(L, t) = T_env,  T(x, 0) = T_initial,
// by finite differences on a uniform grid (nodes x_i = i L / N), with three schemes: explicit
// (forward Euler in time), implicit (backward Euler) and Crank–Nicolson. Closed forms for checking:
// the erfc solution of a semi-infinite medium and the Fourier series of a finite slab.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace dresskit::thickness {

enum class HeatScheme { explicit_euler, implicit_euler, crank_nicolson };
/// "explicit", "implicit", "crank-nicolson" (or "cn"); throws InputError naming the value otherwise.
HeatScheme parse_heat_scheme(const std::string& text);
std::string to_string(HeatScheme scheme);

struct HeatProblem {
  double diffusivity = 0.0;  ///< α [m²/s], > 0
  double length = 0.0;       ///< L [m], > 0
  double t_skin = 37.0;      ///< boundary at x = 0 [°C]
  double t_env = -10.0;      ///< boundary at x = L [°C]
  double t_initial = -10.0;  ///< initial temperature inside [°C]
  double duration = 3600.0;  ///< [s], > 0
};

struct HeatOptions {
  HeatScheme scheme = HeatScheme::crank_nicolson;
  int cells = 200;   ///< N, grid cells along x (≥ 2)
  int steps = 200;   ///< time steps over the duration (≥ 1)
  /// Crank–Nicolson only: backward Euler half-steps first (Rannacher start-up), which damp the
  /// oscillation that the jump between T_skin and T_initial at x = 0 excites otherwise [count].
  int startup_half_steps = 4;
  /// Explicit only: when α Δt / Δx² exceeds 1/2 (the stability limit), split each step into
  /// enough equal sub-steps to respect it; false = refuse with an InputError naming the ratio.
  bool explicit_substep = true;
  int record_every = 0;  ///< keep T every this many steps for a T(x, t) surface; 0 = only the end
};

struct HeatResult {
  Eigen::VectorXd x;            ///< node positions [m], N + 1
  Eigen::VectorXd temperature;  ///< T at the end [°C], N + 1
  std::vector<double> times;    ///< recorded times [s] (with record_every), starting with 0
  Eigen::MatrixXd surface;      ///< recorded T, one row per time in `times` [°C]
  double courant = 0.0;         ///< α Δt / Δx² of one (sub-)step
  int steps_taken = 0;          ///< time steps including explicit sub-steps
  double seconds = 0.0;         ///< wall time of the solve
};

/// Throws InputError naming the field for a non-positive diffusivity, length, duration, cells or
/// steps, and for an explicit step beyond its stability limit when sub-stepping is off.
HeatResult solve_heat(const HeatProblem& problem, const HeatOptions& options = {});

/// Semi-infinite medium at T_initial, face held at T_skin from t = 0:
/// T = T_initial + (T_skin − T_initial) erfc(x / (2 √(α t))). T_env plays no part.
double heat_semi_infinite(const HeatProblem& problem, double x, double t);
/// The finite slab's Fourier series, summed until terms fall under 1e-14 of the temperature range.
double heat_finite_slab(const HeatProblem& problem, double x, double t);

/// The first depth at which the profile (T at nodes `x`) crosses `threshold`, by linear
/// interpolation between nodes; −1 when it never does.
double crossing_depth(const Eigen::VectorXd& x, const Eigen::VectorXd& temperature, double threshold);

/// Solves a tridiagonal system in place (Thomas algorithm): sub[i] T[i−1] + diag[i] T[i] +
/// sup[i] T[i+1] = rhs[i]. `rhs` becomes the solution. Needs a diagonally dominant matrix.
void solve_tridiagonal(const Eigen::VectorXd& sub, const Eigen::VectorXd& diag,
                       const Eigen::VectorXd& sup, Eigen::VectorXd& rhs);

}  // namespace dresskit::thickness
