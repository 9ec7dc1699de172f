#pragma once
// Raw measured fabric records, exactly as published (see fabric_table.cpp for the source).
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace dresskit::cloth::detail {

struct FabricRecord {
  std::string name, common_use;
  std::vector<std::pair<std::string, double>> composition;  ///< fibre → mass fraction
  double areal_density;                                     ///< [kg/m²]
  std::array<std::array<double, 4>, 6> stretching;          ///< [N/m]
  std::array<std::array<double, 5>, 3> bending;             ///< [N m]
};

const std::vector<FabricRecord>& fabric_table();

}  // namespace dresskit::cloth::detail
