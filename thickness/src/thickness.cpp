#include "dresskit/thickness/thickness.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "dresskit/mesh/errors.h"


namespace dresskit::thickness {
namespace {

/// erfc⁻¹(y) for 0 < y < 1 by bisection on the monotone erfc over [0, 10]: 80 halvings reach
/// double precision; this runs a handful of times per thickness, so speed does not matter.
double inverse_erfc(double y) {
  double lo = 0.0, hi = 10.0;
  for (int k = 0; k < 80; ++k) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid) > y ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double fabric_depth(double diffusivity, const ThicknessOptions& o, double domain, double threshold,
                    HeatResult* keep) {
  HeatProblem problem;
  problem.diffusivity = diffusivity;
  problem.length = domain;
  problem.t_skin = o.t_skin;
  problem.t_env = o.t_env;
  problem.t_initial = std::isnan(o.t_initial) ? o.t_env : o.t_initial;
  problem.duration = o.exposure;
  HeatResult solved = solve_heat(problem, o.heat);
  const double depth = crossing_depth(solved.x, solved.temperature, threshold);
  if (keep) *keep = std::move(solved);
  return depth;
}

}  // namespace

double sheet_thickness(const Composition& composition, double areal_density, double solidity) {
  if (!(areal_density > 0.0) || !std::isfinite(areal_density))
    throw InputError("areal density: must be a positive number of kg/m²");
  const FabricThermal f = fabric_thermal(composition, solidity);
  return areal_density / (f.fibre_density * solidity);
}

double penetration_depth(double diffusivity, double time, double t_skin, double t_env,
                         double threshold) {
  return 2.0 * std::sqrt(diffusivity * time) * inverse_erfc((threshold - t_env) / (t_skin - t_env));
}

ThicknessResult compute_thickness(const Composition& composition, const ThicknessOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (!std::isfinite(o.t_skin) || !std::isfinite(o.t_env) || o.t_skin == o.t_env) {
    std::ostringstream out;
    out << "T_skin = " << o.t_skin << " °C and T_env = " << o.t_env
        << " °C: they must be finite and differ (no heat flows otherwise)";
    throw InputError(out.str());
  }
  if (!(o.exposure > 0.0) || !std::isfinite(o.exposure))
    throw InputError("exposure time " + std::to_string(o.exposure) + " s is not positive");
  if (!(o.domain >= 0.0) || !std::isfinite(o.domain))
    throw InputError("domain " + std::to_string(o.domain) + " m is negative");

  ThicknessResult r;
  r.fabric = fabric_thermal(composition, o.solidity);
  r.threshold = std::isnan(o.threshold) ? 0.5 * (o.t_skin + o.t_env) : o.threshold;
  const double lo = std::min(o.t_skin, o.t_env), hi = std::max(o.t_skin, o.t_env);
  if (!(r.threshold > lo && r.threshold < hi)) {
    std::ostringstream out;
    out << "threshold " << r.threshold << " °C is not strictly between T_env = " << o.t_env
        << " °C and T_skin = " << o.t_skin << " °C";
    throw InputError(out.str());
  }
  r.domain = o.domain > 0.0 ? o.domain
                            : 8.0 * std::sqrt(r.fabric.diffusivity_parallel() * o.exposure);
  r.thickness = fabric_depth(r.fabric.diffusivity_nominal(), o, r.domain, r.threshold, &r.nominal);
  r.thickness_min = fabric_depth(r.fabric.diffusivity_series(), o, r.domain, r.threshold, nullptr);
  r.thickness_max = fabric_depth(r.fabric.diffusivity_parallel(), o, r.domain, r.threshold, nullptr);
  r.thickness_closed_form = penetration_depth(r.fabric.diffusivity_nominal(), o.exposure, o.t_skin,
                                              o.t_env, r.threshold);
  if (r.thickness < 0.0 || r.thickness_min < 0.0 || r.thickness_max < 0.0)
    throw InputError("the threshold " + std::to_string(r.threshold) +
                     " °C is not crossed inside the slab (domain too short)");
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

DownFill down_fill(const std::vector<double>& areas, double thickness, const FabricThermal& fabric) {
  if (!(thickness > 0.0) || !std::isfinite(thickness))
    throw InputError("down fill: thickness " + std::to_string(thickness) + " m is not positive");
  DownFill fill;
  fill.fill_density = fabric.solidity * fabric.fibre_density;
  for (double area : areas) {
    if (!(area >= 0.0) || !std::isfinite(area))
      throw InputError("down fill: panel area " + std::to_string(area) + " m² is negative");
    fill.panel_kg.push_back(area * thickness * fill.fill_density);
    fill.total_kg += fill.panel_kg.back();
  }
  return fill;
}

}  // namespace dresskit::thickness
