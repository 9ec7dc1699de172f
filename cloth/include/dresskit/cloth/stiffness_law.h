#pragma once
// The nonlinear spring law: a secant stiffness k(ε) [N/m] that is piecewise linear in the strain
// ε = L/L0 − 1 with four segments for ε ≥ 0, so F = k(ε) (L − L0) (the form of methods.md §1).
// Pure functions; value, derivative and energy side by side.
#include <array>

namespace dresskit {

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

}  // namespace dresskit
