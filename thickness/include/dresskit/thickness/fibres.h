#pragma once
// Fibres and fabrics as heat conductors. A fabric is a blend of fibres (by mass fraction) and air;
// the share of the fabric's volume taken by fibre is its solidity. Its volumetric heat capacity is
// exact (a volume average); its conductivity is known only between two bounds, the series (Wiener
// lower) and parallel (Wiener upper) mixes of every phase, with a nominal value in between from
// Maxwell's formula for fibres lying across the heat flow. Figures and sources: docs/thickness.md.
#include <string>
#include <utility>
#include <vector>

namespace dresskit::thickness {

struct Fibre {
  std::string name;
  double density = 0.0;        ///< ρ [kg/m³]
  double specific_heat = 0.0;  ///< c [J/(kg K)]
  double conductivity = 0.0;   ///< k [W/(m K)], across the fibre where known
  std::string source;          ///< where the figures come from
};

/// cotton, polyester, spandex, nylon, rayon, wool, down and air.
const std::vector<Fibre>& fibre_table();
/// A fibre by name or alias (elastane = spandex, nylon-6,6 = nylon, viscose = rayon); throws
/// InputError listing the known names otherwise.
const Fibre& fibre_by_name(const std::string& name);

/// fibre → mass fraction.
using Composition = std::vector<std::pair<std::string, double>>;

/// Parses "cotton=0.6,polyester=0.4". Throws InputError naming the entry when it is malformed.
Composition parse_composition(const std::string& text);
/// Throws InputError naming the value when a fraction is negative or not finite, a fibre unknown or
/// repeated, or the fractions do not sum to 1 (± 1e-6).
void check_composition(const Composition& composition);

struct FabricThermal {
  double solidity = 0.0;               ///< fibre volume fraction [unitless]
  double volumetric_heat_capacity = 0.0;  ///< ρc of the fibre/air mix [J/(m³ K)]
  double density = 0.0;                ///< bulk density of the fabric [kg/m³]
  double fibre_density = 0.0;          ///< density of the fibre blend alone [kg/m³]
  double conductivity_series = 0.0;    ///< lower bound [W/(m K)]
  double conductivity_nominal = 0.0;   ///< Maxwell, fibres across the flow [W/(m K)]
  double conductivity_parallel = 0.0;  ///< upper bound [W/(m K)]
  /// α = k / ρc for each conductivity [m²/s].
  double diffusivity_series() const { return conductivity_series / volumetric_heat_capacity; }
  double diffusivity_nominal() const { return conductivity_nominal / volumetric_heat_capacity; }
  double diffusivity_parallel() const { return conductivity_parallel / volumetric_heat_capacity; }
};

/// Thermal properties of a fibre blend with air at the given solidity (0 < solidity ≤ 1).
/// Throws InputError for a bad composition or solidity.
FabricThermal fabric_thermal(const Composition& composition, double solidity);

}  // namespace dresskit::thickness
