#include "dresskit/cloth/stiffness_law.h"

#include <algorithm>

namespace dresskit::cloth {

StiffnessLaw StiffnessLaw::linear(double k) {
  StiffnessLaw law;
  law.knot_strain = {0.0, 1.0 / 18, 2.0 / 18, 3.0 / 18};
  law.knot_k = {k, k, k, k};
  return law;
}

StiffnessLaw StiffnessLaw::fitted(double k0, double k_knee, double knee_strain) {
  k_knee = std::max(k_knee, k0);
  StiffnessLaw law;
  for (int i = 0; i < 4; ++i) {
    const double t = i / 3.0;
    law.knot_strain[i] = t * knee_strain;
    law.knot_k[i] = k0 + (k_knee - k0) * t * t;
  }
  law.slope_beyond = std::max(2.0 * (k_knee - k0), k_knee) / knee_strain;
  return law;
}

double StiffnessLaw::k(double e) const {
  if (e <= 0.0) return knot_k[0];
  for (int s = 0; s < 3; ++s) {
    if (e < knot_strain[s + 1]) {
      const double t = (e - knot_strain[s]) / (knot_strain[s + 1] - knot_strain[s]);
      return knot_k[s] + t * (knot_k[s + 1] - knot_k[s]);
    }
  }
  return knot_k[3] + slope_beyond * (e - knot_strain[3]);
}

double StiffnessLaw::dk(double e) const {
  if (e <= 0.0) return 0.0;
  for (int s = 0; s < 3; ++s) {
    if (e < knot_strain[s + 1]) return (knot_k[s + 1] - knot_k[s]) / (knot_strain[s + 1] - knot_strain[s]);
  }
  return slope_beyond;
}

double StiffnessLaw::energy(double L, double L0) const {
  const double e = L / L0 - 1.0;
  if (e <= 0.0) return 0.5 * knot_k[0] * e * e * L0 * L0;
  // ∫ k(s) s ds over each linear piece k(s) = ka + m (s − a) from a to b.
  auto piece = [](double a, double b, double ka, double m) {
    return (ka - m * a) * (b * b - a * a) / 2.0 + m * (b * b * b - a * a * a) / 3.0;
  };
  double g = 0.0;
  for (int s = 0; s < 3; ++s) {
    const double a = knot_strain[s], b = std::min(e, knot_strain[s + 1]);
    if (b <= a) break;
    g += piece(a, b, knot_k[s], (knot_k[s + 1] - knot_k[s]) / (knot_strain[s + 1] - knot_strain[s]));
  }
  if (e > knot_strain[3]) g += piece(knot_strain[3], e, knot_k[3], slope_beyond);
  return g * L0 * L0;
}

double StiffnessLaw::tension(double L, double L0) const {
  const double e = L / L0 - 1.0;
  return k(e) * e * L0;
}

double StiffnessLaw::tension_derivative(double L, double L0) const {
  const double e = L / L0 - 1.0;
  return dk(e) * e + k(e);
}

}  // namespace dresskit::cloth
