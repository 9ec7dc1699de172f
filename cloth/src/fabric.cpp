#include "dresskit/cloth/fabric.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dresskit/mesh/errors.h"
#include "fabric_table.h"


namespace dresskit::cloth {
namespace {

// Orthotropic: the stiffness along θ equals that along −θ and π − θ; fold into [0, π/2].
double fold(double theta) {
  double t = std::fmod(std::abs(theta), M_PI);
  return t > M_PI / 2 ? M_PI - t : t;
}

double directional(const Eigen::Matrix<double, 1, 4>& c, double theta) {
  const double cs = std::cos(theta), sn = std::sin(theta);
  const double c2 = cs * cs, s2 = sn * sn;
  return c(0) * c2 * c2 + 2.0 * (c(1) + 2.0 * c(3)) * c2 * s2 + c(2) * s2 * s2;
}

// Linear interpolation of samples taken at equally spaced angles over [0, π/2].
template <typename Values>
double interpolate(const Values& v, int n, double folded) {
  const double x = folded / (M_PI / 2) * (n - 1);
  const int i = std::min(static_cast<int>(x), n - 2);
  const double t = x - i;
  return (1 - t) * v(i) + t * v(i + 1);
}

Fabric from_record(const detail::FabricRecord& r) {
  Fabric f;
  f.name = r.name;
  f.common_use = r.common_use;
  f.composition = r.composition;
  f.areal_density = r.areal_density;
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 4; ++k) f.stretching(i, k) = 2.0 * std::max(0.0, r.stretching[i][k]);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 5; ++k) f.bending(i, k) = r.bending[i][k];
  return f;
}

}  // namespace

double Fabric::stiffness_at_rest(double theta) const { return directional(stretching.row(0), theta); }

double Fabric::stiffness_at_knee(double theta) const {
  Eigen::Matrix<double, 5, 1> along;
  for (int i = 0; i < 5; ++i) along(i) = directional(stretching.row(i + 1), i * M_PI / 8);
  return interpolate(along, 5, fold(theta));
}

double Fabric::bending_stiffness(double theta) const {
  const Eigen::Vector3d low = bending.col(0);
  return interpolate(low, 3, fold(theta));
}

std::vector<std::string> fabric_names() {
  std::vector<std::string> names;
  for (const auto& r : detail::fabric_table()) names.push_back(r.name);
  return names;
}

Fabric fabric_by_name(const std::string& name) {
  for (const auto& r : detail::fabric_table()) {
    if (r.name == name) return from_record(r);
  }
  std::string known;
  for (const auto& n : fabric_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("fabric: unknown name '" + name + "' (known: " + known + ")");
}

std::vector<Fabric> load_fabrics(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(path + ": fabric file is not a regular file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open fabric file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  if (!j.is_object() || !j.contains("fabrics") || !j["fabrics"].is_array()) {
    throw InputError(path + ": expected an object with a \"fabrics\" array");
  }
  std::vector<Fabric> fabrics;
  for (size_t n = 0; n < j["fabrics"].size(); ++n) {
    const auto& e = j["fabrics"][n];
    const std::string where = path + ": fabrics[" + std::to_string(n) + "]";
    auto number = [&](const nlohmann::json& v, const std::string& field) {
      if (!v.is_number()) throw InputError(where + "." + field + " is not a number");
      const double x = v.get<double>();
      if (!std::isfinite(x)) throw InputError(where + "." + field + " is not finite");
      return x;
    };
    detail::FabricRecord r;
    if (!e.contains("name") || !e["name"].is_string()) throw InputError(where + ".name is missing");
    r.name = e["name"].get<std::string>();
    r.common_use = e.value("common_use", "");
    if (e.contains("composition_mass_fraction") && e["composition_mass_fraction"].is_object()) {
      for (const auto& [fibre, fraction] : e["composition_mass_fraction"].items()) {
        r.composition.emplace_back(fibre, number(fraction, "composition_mass_fraction." + fibre));
      }
    }
    if (!e.contains("areal_density_kg_per_m2")) throw InputError(where + ".areal_density_kg_per_m2 is missing");
    r.areal_density = number(e["areal_density_kg_per_m2"], "areal_density_kg_per_m2");
    if (r.areal_density <= 0) {
      throw InputError(where + ".areal_density_kg_per_m2 must be positive, not " +
                       std::to_string(r.areal_density));
    }
    auto table = [&](const char* field, auto& out, size_t rows, size_t cols) {
      if (!e.contains(field) || !e[field].is_array() || e[field].size() != rows) {
        throw InputError(where + "." + field + " must be " + std::to_string(rows) + " rows");
      }
      for (size_t i = 0; i < rows; ++i) {
        const auto& row = e[field][i];
        if (!row.is_array() || row.size() != cols) {
          throw InputError(where + "." + field + "[" + std::to_string(i) + "] must hold " +
                           std::to_string(cols) + " numbers");
        }
        for (size_t k = 0; k < cols; ++k) {
          out[i][k] = number(row[k], std::string(field) + "[" + std::to_string(i) + "][" +
                                         std::to_string(k) + "]");
        }
      }
    };
    table("stretching", r.stretching, 6, 4);
    table("bending", r.bending, 3, 5);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 5; ++k)
        if (r.bending[i][k] < 0.0)
          throw InputError(where + ".bending[" + std::to_string(i) + "][" + std::to_string(k) +
                           "] is negative: " + std::to_string(r.bending[i][k]));
    // The stretching coefficients are fits and may be negative one by one (they are clamped at 0),
    // but the cloth needs a positive stiffness along warp and weft, at rest and at the knee.
    const Fabric f = from_record(r);
    for (double theta : {0.0, M_PI / 2})
      if (!(f.stiffness_at_rest(theta) > 0.0) || !(f.stiffness_at_knee(theta) > 0.0))
        throw InputError(where + ".stretching gives no positive stiffness along the " +
                         (theta == 0.0 ? "warp" : "weft"));
    fabrics.push_back(f);
  }
  return fabrics;
}

}  // namespace dresskit::cloth
