#include "dresskit/thickness/fibres.h"

#include <cmath>
#include <sstream>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/names.h"


namespace dresskit::thickness {
namespace {

// Sources, abbreviated (full references and the reasoning behind each choice: docs/thickness.md):
//   MH  = Morton & Hearle, Physical Properties of Textile Fibres, 4th ed. (2008): densities (ch. 1
//         tables) and specific heats of dry fibres (Table 6.1, midpoints of the ranges given);
//   KW  = Kawabata, J. Text. Mach. Soc. Japan 39 (1986): conductivity across single fibres;
//   BX  = Baxter, Proc. Phys. Soc. 58 (1946) 105: keratin 4.62e-4 cal/(cm s K) = 0.193 W/(m K);
//   PH  = polymer handbook values for the bulk polymer (no across-fibre measurement found);
//   INC = Incropera et al., Fundamentals of Heat and Mass Transfer, Table A.4, air at 300 K.
const std::vector<Fibre> kFibres = {
    {"cotton", 1540.0, 1285.0, 0.243, "MH density and c (1.22-1.35 J/gK); KW k across fibre"},
    {"polyester", 1380.0, 1030.0, 0.157, "MH density and c (PET 1.03 J/gK); KW k across fibre"},
    {"spandex", 1210.0, 1700.0, 0.20, "MH density (elastane); PH c and k of polyurethane elastomer"},
    {"nylon", 1140.0, 1460.0, 0.25, "MH density and c (nylon 6,6 1.46 J/gK); PH k of bulk PA66"},
    {"rayon", 1520.0, 1470.0, 0.243, "MH density and c (1.35-1.59 J/gK); k taken as cotton's (both cellulose)"},
    {"wool", 1310.0, 1360.0, 0.193, "MH density and c (1.36 J/gK); BX k of keratin at 0.7% regain"},
    {"down", 1310.0, 1360.0, 0.193, "feather keratin, taken equal to wool keratin (MH, BX)"},
    {"air", 1.1614, 1007.0, 0.0263, "INC air at 300 K"},
};

const std::vector<std::pair<std::string, std::string>> kAliases = {
    {"elastane", "spandex"}, {"nylon-6,6", "nylon"}, {"nylon66", "nylon"}, {"nylon-66", "nylon"},
    {"viscose", "rayon"},    {"pet", "polyester"}};

std::string known_names() {
  std::string names;
  for (const Fibre& f : kFibres) names += (names.empty() ? "" : ", ") + f.name;
  return names;
}

}  // namespace

const std::vector<Fibre>& fibre_table() { return kFibres; }

const Fibre& fibre_by_name(const std::string& name) {
  std::string key = name;
  for (const auto& [alias, target] : kAliases)
    if (name == alias) key = target;
  for (const Fibre& f : kFibres)
    if (f.name == key) return f;
  throw InputError("unknown fibre '" + name + "' (known: " + known_names() + ")");
}

Composition parse_composition(const std::string& text) {
  Composition composition;
  std::stringstream entries(text);
  std::string entry;
  while (std::getline(entries, entry, ',')) {
    const auto eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size())
      throw InputError("composition entry '" + entry + "' is not fibre=fraction");
    const std::string value = entry.substr(eq + 1);
    const std::optional<double> fraction = parse_number(value);
    if (!fraction) throw InputError("composition entry '" + entry + "': '" + value + "' is not a number");
    composition.emplace_back(entry.substr(0, eq), *fraction);
  }
  if (composition.empty()) throw InputError("composition '" + text + "' is empty");
  return composition;
}

void check_composition(const Composition& composition) {
  if (composition.empty()) throw InputError("composition is empty");
  double sum = 0.0;
  for (std::size_t a = 0; a < composition.size(); ++a) {
    const auto& [name, fraction] = composition[a];
    const Fibre& fibre = fibre_by_name(name);
    if (fibre.name == "air")
      throw InputError("composition: air is not a fibre here; the pores are set by the solidity");
    if (!std::isfinite(fraction) || fraction < 0.0)
      throw InputError("composition: mass fraction of " + name + " is " + std::to_string(fraction) +
                       " (must be ≥ 0)");
    for (std::size_t b = 0; b < a; ++b)
      if (fibre_by_name(composition[b].first).name == fibre.name)
        throw InputError("composition: fibre " + name + " is given twice");
    sum += fraction;
  }
  if (std::abs(sum - 1.0) > 1e-6) {
    std::ostringstream out;
    out << "composition: mass fractions sum to " << sum << ", not 1 (± 1e-6)";
    throw InputError(out.str());
  }
}

FabricThermal fabric_thermal(const Composition& composition, double solidity) {
  check_composition(composition);
  if (!(solidity > 0.0 && solidity <= 1.0))
    throw InputError("solidity " + std::to_string(solidity) + " is not in (0, 1]");
  const Fibre& air = fibre_by_name("air");
  // Volume per kilogram of fibre blend → each fibre's share of the fibre volume.
  double volume_per_kg = 0.0;
  for (const auto& [name, w] : composition) volume_per_kg += w / fibre_by_name(name).density;

  FabricThermal t;
  t.solidity = solidity;
  t.fibre_density = 1.0 / volume_per_kg;
  const double air_share = 1.0 - solidity;
  double rho_c = air_share * air.density * air.specific_heat;
  double parallel = air_share * air.conductivity;
  double resistance = air_share / air.conductivity;
  double maxwell_sum = 0.0;  // Σ v_i (k_i − k_air)/(k_i + k_air)
  for (const auto& [name, w] : composition) {
    const Fibre& f = fibre_by_name(name);
    const double v = solidity * (w / f.density) / volume_per_kg;  // volume fraction in the fabric
    rho_c += v * f.density * f.specific_heat;
    parallel += v * f.conductivity;
    resistance += v / f.conductivity;
    maxwell_sum += v * (f.conductivity - air.conductivity) / (f.conductivity + air.conductivity);
  }
  t.volumetric_heat_capacity = rho_c;
  t.density = solidity * t.fibre_density + air_share * air.density;
  t.conductivity_parallel = parallel;
  t.conductivity_series = 1.0 / resistance;
  // Maxwell–Garnett in two dimensions: parallel cylinders (fibres in the fabric's plane) in an air
  // matrix with the heat flowing across them. Air is the lowest-conductivity phase, so this is the
  // Hashin–Shtrikman lower bound of the mix and lies between the series and parallel bounds.
  t.conductivity_nominal = air.conductivity * (1.0 + maxwell_sum) / (1.0 - maxwell_sum);
  return t;
}

}  // namespace dresskit::thickness
