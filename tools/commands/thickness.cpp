#include "commands/thickness.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "dresskit/cloth/fabric.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/names.h"

namespace dresskit::cli {
namespace {

std::string composition_text(const Composition& c) {
  std::ostringstream out;
  for (std::size_t k = 0; k < c.size(); ++k)
    out << (k ? ", " : "") << c[k].first << " " << c[k].second;
  return out.str();
}

json result_json(const std::string& name, const Composition& c, const ThicknessResult& r,
                 const ThicknessOptions& o) {
  json composition = json::object();
  for (const auto& [fibre, fraction] : c) composition[fibre] = fraction;
  return {{"fabric", name},
          {"composition", composition},
          {"thickness_mm", r.thickness * 1e3},
          {"thickness_min_mm", r.thickness_min * 1e3},
          {"thickness_max_mm", r.thickness_max * 1e3},
          {"thickness_closed_form_mm", r.thickness_closed_form * 1e3},
          {"threshold_c", r.threshold},
          {"t_skin_c", o.t_skin},
          {"t_env_c", o.t_env},
          {"t_initial_c", std::isnan(o.t_initial) ? o.t_env : o.t_initial},
          {"time_s", o.exposure},
          {"solidity", o.solidity},
          {"conductivity_w_per_m_k",
           {{"series", r.fabric.conductivity_series},
            {"nominal", r.fabric.conductivity_nominal},
            {"parallel", r.fabric.conductivity_parallel}}},
          {"volumetric_heat_capacity_j_per_m3_k", r.fabric.volumetric_heat_capacity},
          {"diffusivity_m2_per_s", r.fabric.diffusivity_nominal()},
          {"scheme", to_string(o.heat.scheme)},
          {"cells", o.heat.cells},
          {"steps", o.heat.steps},
          {"domain_mm", r.domain * 1e3},
          {"seconds", r.seconds}};
}

std::vector<double> parse_areas(const std::string& text) {
  std::vector<double> areas;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const std::optional<double> value = parse_number(item);
    if (!value) throw InputError("--panel-areas: '" + item + "' is not a number");
    areas.push_back(*value);
  }
  return areas;
}

}  // namespace

void ThicknessCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("thickness", "a fabric's thickness from heat conduction through it, "
                                            "with its lower and upper limits (docs/thickness.md)");
  auto* by_name = command->add_option("--fabric", fabric, "a built-in fabric (e.g. gray-interlock) or "
                                                          "one in --fabric-file");
  auto* by_mix = command->add_option("--composition", composition,
                                     "fibre mass fractions, e.g. cotton=0.6,polyester=0.4");
  auto* all = command->add_flag("--all-fabrics", all_fabrics, "a table for the ten built-in fabrics");
  by_name->excludes(by_mix)->excludes(all);
  by_mix->excludes(all);
  command->add_option("--fabric-file", fabric_file, "fabrics JSON (layout of fabrics.json)")->needs(by_name);
  option_with_default(command, "--t-skin", options.t_skin, "skin temperature [°C]");
  option_with_default(command, "--t-env", options.t_env, "outside temperature [°C]");
  option_with_default(command, "--time", options.exposure, "exposure time [s]");
  command->add_option("--t-initial", options.t_initial,
                      "the fabric's temperature at the start [°C]; default: --t-env");
  command->add_option("--threshold", options.threshold,
                      "threshold temperature [°C]; default: midway between --t-skin and --t-env");
  option_with_default(command, "--solidity", options.solidity,
                      "fibre volume fraction of the fabric");
  option_with_default(command, "--scheme", scheme, "explicit, implicit or crank-nicolson");
  option_with_default(command, "--cells", options.heat.cells, "grid cells through the slab");
  option_with_default(command, "--steps", options.heat.steps, "time steps");
  command->add_option("--panel-areas", panel_areas,
                      "down fill: comma-separated panel areas [m²]; prints each panel's fill mass");
  command->add_option("--plot", plot_dir, "write temperature.csv and temperature.png (T(x, t)) here");
  command->add_flag("--json", as_json, "print JSON");
}

int ThicknessCommand::run() {
  if (fabric.empty() && composition.empty() && !all_fabrics)
    throw CLI::ValidationError("thickness", "give --fabric, --composition or --all-fabrics");
  options.heat.scheme = parse_heat_scheme(scheme);
  if (!plot_dir.empty()) options.heat.record_every = std::max(1, options.heat.steps / 100);

  std::vector<std::pair<std::string, Composition>> fabrics;
  if (all_fabrics) {
    for (const std::string& name : fabric_names()) fabrics.emplace_back(name, fabric_by_name(name).composition);
  } else if (!composition.empty()) {
    fabrics.emplace_back("custom", parse_composition(composition));
  } else if (!fabric_file.empty()) {
    const std::vector<Fabric> file = load_fabrics(fabric_file);
    const auto it = std::find_if(file.begin(), file.end(), [&](const Fabric& f) { return f.name == fabric; });
    if (it == file.end()) throw InputError(fabric_file + ": no fabric named '" + fabric + "'");
    fabrics.emplace_back(it->name, it->composition);
  } else {
    fabrics.emplace_back(fabric, fabric_by_name(fabric).composition);
  }

  // Compute everything first: nothing is printed or written unless all of it succeeded.
  std::vector<ThicknessResult> results;
  for (const auto& [name, mix] : fabrics) {
    try {
      results.push_back(compute_thickness(mix, options));
    } catch (const InputError& e) {
      throw InputError("fabric " + name + ": " + e.what());
    }
  }
  DownFill fill;
  const bool with_fill = !panel_areas.empty();
  if (with_fill) {
    if (results.size() != 1) throw InputError("--panel-areas needs one fabric, not --all-fabrics");
    fill = down_fill(parse_areas(panel_areas), results[0].thickness, results[0].fabric);
  }
  if (!plot_dir.empty()) {
    if (results.size() != 1) throw InputError("--plot needs one fabric, not --all-fabrics");
    write_temperature_surface(plot_dir, results[0], options);
  }

  if (as_json) {
    json out = json::array();
    for (std::size_t k = 0; k < results.size(); ++k)
      out.push_back(result_json(fabrics[k].first, fabrics[k].second, results[k], options));
    if (with_fill)
      out[0]["down_fill"] = {{"panel_kg", fill.panel_kg}, {"total_kg", fill.total_kg},
                             {"fill_density_kg_per_m3", fill.fill_density}};
    std::cout << (all_fabrics ? out : out[0]).dump(2) << "\n";
    return 0;
  }
  std::printf("T_skin %g °C, T_env %g °C, %g s, threshold %g °C, solidity %g (%s, %d cells × %d steps)\n",
              options.t_skin, options.t_env, options.exposure, results[0].threshold, options.solidity,
              to_string(options.heat.scheme).c_str(), options.heat.cells, options.heat.steps);
  std::printf("%-20s %-28s %9s %9s %9s\n", "fabric", "composition", "min [mm]", "thickness", "max [mm]");
  for (std::size_t k = 0; k < results.size(); ++k)
    std::printf("%-20s %-28s %9.2f %9.2f %9.2f\n", fabrics[k].first.c_str(),
                composition_text(fabrics[k].second).c_str(), results[k].thickness_min * 1e3,
                results[k].thickness * 1e3, results[k].thickness_max * 1e3);
  if (with_fill) {
    for (std::size_t p = 0; p < fill.panel_kg.size(); ++p)
      std::printf("panel %zu: %.1f g of fill\n", p, fill.panel_kg[p] * 1e3);
    std::printf("total fill %.1f g (fill density %.2f kg/m³)\n", fill.total_kg * 1e3, fill.fill_density);
  }
  if (!plot_dir.empty()) std::printf("wrote %s/temperature.csv and temperature.png\n", plot_dir.c_str());
  return 0;
}

}  // namespace dresskit::cli
