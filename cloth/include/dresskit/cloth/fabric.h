#pragma once
// Fabrics: the ten measured fabrics built in (by name), and user fabrics from JSON files in the same
// layout as ../shared/data/fabrics/fabrics.json. Derivation of spring stiffness: docs/cloth.md.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace dresskit::cloth {

struct Fabric {
  std::string name, common_use;
  std::vector<std::pair<std::string, double>> composition;  ///< fibre → mass fraction
  double areal_density = 0.0;  ///< [kg/m²]
  /// Planar stiffness (C11, C12, C22, C33) [N/m], negative entries clamped to 0 and doubled as in the
  /// measurements' model. Row 0: at zero strain; rows 1–5: at 1/6 strain along 0°, 22.5°, 45°,
  /// 67.5°, 90° from warp.
  Eigen::Matrix<double, 6, 4> stretching = Eigen::Matrix<double, 6, 4>::Zero();
  /// Bending stiffness [N m] along 0°, 45°, 90° from warp, 5 samples from low to high curvature.
  Eigen::Matrix<double, 3, 5> bending = Eigen::Matrix<double, 3, 5>::Zero();

  /// Membrane stiffness [N/m] for a uniaxial stretch along the direction at angle theta [rad] from
  /// warp, at rest: n·C·n = C11 c⁴ + 2 (C12 + 2 C33) c² s² + C22 s⁴ with row 0.
  double stiffness_at_rest(double theta) const;
  /// The same at 1/6 strain: each measured direction uses its own row; other angles interpolate
  /// linearly between the two nearest measured directions (orthotropic: folded into [0°, 90°]).
  double stiffness_at_knee(double theta) const;
  /// In-plane shear stiffness C33 at rest [N/m].
  double shear_stiffness() const { return stretching(0, 3); }
  /// Bending stiffness at low curvature [N m], interpolated between 0°, 45° and 90°.
  double bending_stiffness(double theta) const;
};

/// The strain at which the measured large-strain stiffness applies (1/6 of stretch beyond rest).
constexpr double kKneeStrain = 1.0 / 6.0;

/// Names of the built-in fabrics, e.g. "gray-interlock", "11oz-black-denim".
std::vector<std::string> fabric_names();
/// A built-in fabric; throws InputError listing the known names for an unknown one.
Fabric fabric_by_name(const std::string& name);
/// Fabrics from a JSON file shaped like ../shared/data/fabrics/fabrics.json ({"fabrics": [...]}).
/// Throws InputError naming the file and the field for a missing, malformed or non-positive value.
std::vector<Fabric> load_fabrics(const std::string& path);

}  // namespace dresskit::cloth
