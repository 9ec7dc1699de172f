#pragma once
// A garment's thickness from heat conduction: the depth that the skin's warmth reaches through the
// fabric after an exposure time, i.e. where T(x, t_exposure) crosses a threshold temperature. The
// fabric's conductivity bounds (series and parallel mixes) give the same depth's lower and upper
// limits. Method, figures and the comparison with the thickness paper: docs/thickness.md.
#include <limits>
#include <string>
#include <vector>

#include "dresskit/thickness/fibres.h"
#include "dresskit/thickness/heat1d.h"

namespace dresskit::thickness {

struct ThicknessOptions {
  double t_skin = 37.0;    ///< [°C]
  double t_env = -10.0;    ///< [°C], ≠ t_skin
  /// The fabric's temperature when the exposure starts [°C]; NaN = t_env (a garment put on cold).
  double t_initial = std::numeric_limits<double>::quiet_NaN();
  double exposure = 3600.0;  ///< [s], > 0
  /// [°C], strictly between t_env and t_skin; NaN = the midpoint (T_skin + T_env) / 2, where the
  /// fabric has lost half of the skin-to-air temperature difference.
  double threshold = std::numeric_limits<double>::quiet_NaN();
  /// Fibre volume fraction of the fabric [unitless]. 0.25: knitted and woven apparel fabrics have
  /// 70–80 % pores (docs/thickness.md); a down fill is nearer 0.002.
  double solidity = 0.25;
  /// The slab modelled [m]; 0 = 8 √(α_parallel t), deep enough that the far boundary changes the
  /// crossing by less than 1e-9 of it (the fabric acts as a semi-infinite medium).
  double domain = 0.0;
  HeatOptions heat;  ///< scheme and grid; defaults from the error-against-run-time bench
};

struct ThicknessResult {
  double thickness = 0.0;      ///< [m], nominal conductivity
  double thickness_min = 0.0;  ///< [m], series (lowest) conductivity
  double thickness_max = 0.0;  ///< [m], parallel (highest) conductivity
  double thickness_closed_form = 0.0;  ///< [m], the nominal one from the erfc solution (a check)
  double threshold = 0.0;      ///< [°C] used
  double domain = 0.0;         ///< [m] slab modelled
  FabricThermal fabric;
  HeatResult nominal;          ///< the nominal solve (with its T(x, t) surface when recorded)
  double seconds = 0.0;        ///< wall time of the three solves
};

/// Throws InputError naming the value for a bad composition, T_skin = T_env, a threshold outside
/// (T_env, T_skin), or a non-positive exposure, solidity or grid.
ThicknessResult compute_thickness(const Composition& composition, const ThicknessOptions& options = {});

/// The erfc solution's crossing depth: 2 √(α t) erfc⁻¹((θ − T_env) / (T_skin − T_env)) [m].
double penetration_depth(double diffusivity, double time, double t_skin, double t_env, double threshold);

/// The cloth's own thickness: its mass per area held by fibre at the given solidity,
/// areal_density / (ρ_fibre × solidity) [m] (camel ponte roma, 0.284 kg/m² of polyester and rayon:
/// 0.8 mm). What separates one garment from the next when they are worn in layers. Throws
/// InputError for a bad composition, a non-positive density or solidity.
double sheet_thickness(const Composition& composition, double areal_density, double solidity = 0.25);

/// Down fill of a quilted garment: each panel holds fibre filling its area × thickness at the
/// fabric's solidity, mass = area × thickness × solidity × fibre density. So the fill of a panel is
/// a multiple of its thickness and the total a multiple of the (area-weighted) total thickness.
struct DownFill {
  std::vector<double> panel_kg;  ///< [kg] per panel
  double total_kg = 0.0;
  double fill_density = 0.0;     ///< bulk density of the fill [kg/m³]
};
/// Throws InputError for a negative or non-finite area or a non-positive thickness.
DownFill down_fill(const std::vector<double>& panel_areas_m2, double thickness_m,
                   const FabricThermal& fabric);

/// Writes DIR/temperature.csv (time_s, then T at each depth in mm) and DIR/temperature.png (a
/// heat map: depth across, time downwards, blue = T_env to red = T_skin, the threshold crossing
/// marked in white). Both land together or not at all; throws OutputError otherwise.
void write_temperature_surface(const std::string& dir, const ThicknessResult& result,
                               const ThicknessOptions& options);

}  // namespace dresskit::thickness
