#pragma once
// The nonlinear spring law: a secant stiffness k(ε) [N/m] that is piecewise linear in the strain
// ε = L/L0 − 1 with four segments for ε ≥ 0, so F = k(ε) (L − L0) (the form of methods.md §1).
// Pure functions; value, derivative and energy side by side.
#include <algorithm>
#include <array>

namespace dresskit::cloth {

struct StiffnessLaw {
  /// Knots at ε = 0, knee/3, 2·knee/3, knee; k at the knots; segment 4 continues past the knee with
  /// `slope_beyond` [N/m per unit strain]. In compression (ε < 0) k stays at k(0).
  std::array<double, 4> knot_strain{};
  std::array<double, 4> knot_k{};
  double slope_beyond = 0.0;

  /// A constant stiffness k (a linear spring).
  static StiffnessLaw linear(double k);
  /// From the stiffness at rest k0 and at the knee strain k_knee (measured at 1/6): the knots follow
  /// k0 + (k_knee − k0)(i/3)², a convex ramp; beyond the knee the slope is the larger of the ramp's
  /// end slope and k_knee per knee strain, so the spring stiffens past the knee as fabric does. A
  /// measured k_knee below k0 is raised to k0 (no softening).
  static StiffnessLaw fitted(double k0, double k_knee, double knee_strain);

  double k(double strain) const;       ///< secant stiffness [N/m]
  double dk(double strain) const;      ///< dk/dε [N/m]
  /// Elastic energy [J] of a spring of rest length L0 at length L: L0² ∫₀^ε k(s) s ds.
  double energy(double L, double L0) const;
  /// Tension [N] = dE/dL = k(ε) ε L0 (positive when stretched).
  double tension(double L, double L0) const;
  /// d tension / dL [N/m] = k'(ε) ε + k(ε).
  double tension_derivative(double L, double L0) const;
};

/// k(ε) of StiffnessLaw::fitted(k0, k_knee, knee_strain) without building the law: the segment comes
/// from ε directly (the knots are evenly spaced), so the explicit force loop needs neither the law
/// object nor a search. Equal to the law's k up to rounding (tests/cloth/test_stiffness_law.cpp).
inline double fitted_k(double k0, double k_knee, double knee_strain, double e) {
  if (e <= 0.0) return k0;
  const double per_strain = 1.0 / knee_strain;  // folded to a constant when knee_strain is one
  const double rise = std::max(k_knee - k0, 0.0);
  const double u = 3.0 * per_strain * e;  // position in knot intervals
  // !(u < 3): a NaN strain takes this branch instead of converting NaN to int below.
  if (!(u < 3.0)) return k0 + rise + std::max(2.0 * rise, k0 + rise) * per_strain * (e - knee_strain);
  const int s = static_cast<int>(u);
  // Knots k0 + rise (s/3)²; between knots s and s+1 the rise grows by (2s + 1)/9 linearly.
  return k0 + rise * (1.0 / 9.0) * (s * s + (u - s) * (2 * s + 1));
}

/// The tangent stiffness d(k(ε) ε)/dε = k + ε k' [N/m] of the same law (= StiffnessLaw's
/// tension_derivative): what a step's stability sees.
inline double fitted_tangent(double k0, double k_knee, double knee_strain, double e) {
  if (e <= 0.0) return k0;
  const double per_strain = 1.0 / knee_strain;
  const double rise = std::max(k_knee - k0, 0.0);
  const double u = 3.0 * per_strain * e;
  const double slope = !(u < 3.0) ? std::max(2.0 * rise, k0 + rise) * per_strain
                                  : rise * (1.0 / 9.0) * (2 * static_cast<int>(u) + 1) * 3.0 * per_strain;
  return fitted_k(k0, k_knee, knee_strain, e) + e * slope;
}

}  // namespace dresskit::cloth
