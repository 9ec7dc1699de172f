// ClothSimulator's options: integrator names, checks of the values.
#include "dresskit/mesh/names.h"
#include "dresskit/cloth/simulator.h"

#include <cmath>
#include <string>

#include "dresskit/mesh/errors.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {

const NameTable<Integrator> kIntegrators = {{"symplectic", Integrator::symplectic_euler},
    {"symplectic_euler", Integrator::symplectic_euler}, {"implicit", Integrator::implicit_euler},
    {"implicit_euler", Integrator::implicit_euler}, {"newton", Integrator::newton},
    {"projective", Integrator::projective}};
Integrator parse_integrator(const std::string& text) { return parse_name(text, kIntegrators, "integrator"); }
std::string to_string(Integrator integrator) { return name_of(integrator, kIntegrators); }

void check_options(const SimulationOptions& o) {
  auto need = [](bool ok, const std::string& what) {
    if (!ok) throw InputError(what);
  };
  need(std::isfinite(o.dt) && o.dt > 0.0, "dt: must be a positive number of seconds");
  need(o.gravity.allFinite(), "gravity: must be finite");
  need(std::isfinite(o.air_damping) && o.air_damping >= 0.0, "air_damping: must be ≥ 0");
  need(std::isfinite(o.spring_damping) && o.spring_damping >= 0.0, "spring_damping: must be ≥ 0");
  // Newton's and projective dynamics' minimisations have no term for it: refused, not ignored.
  need(o.spring_damping == 0.0 ||
           (o.integrator != Integrator::newton && o.integrator != Integrator::projective),
       "spring_damping: the newton and projective integrators do not model it (use implicit or "
       "symplectic, or set it to 0)");
  need(std::isfinite(o.strain_limit) && o.strain_limit > 0.0, "strain_limit: must be positive");
  need(o.strain_limit_iterations > 0, "strain_limit_iterations: must be positive");
  need(std::isfinite(o.strain_limit_tolerance) && o.strain_limit_tolerance > 0.0,
       "strain_limit_tolerance: must be positive");
  need(std::isfinite(o.linear.cg_tolerance) && o.linear.cg_tolerance > 0.0, "cg_tolerance: must be positive");
  need(o.wind.allFinite() && std::isfinite(o.gust_amplitude) && std::isfinite(o.gust_frequency),
       "wind: must be finite");
  need(std::isfinite(o.collision_margin) && o.collision_margin >= 0.0, "collision_margin: must be ≥ 0");
  need(std::isfinite(o.penalty_thickness) && o.penalty_thickness > 0.0, "penalty_thickness: must be positive");
  for (const Collider& c : o.colliders) {
    need(std::isfinite(c.friction) && c.friction >= 0.0, "collider friction: must be ≥ 0");
    need(std::isfinite(c.static_friction), "collider static_friction: must be finite");
    need(std::isfinite(c.penalty) && c.penalty >= 0.0, "collider penalty: must be ≥ 0");
  }
  need(o.linear.cg_max_iterations > 0, "cg_max_iterations: must be positive");
  need(o.newton.iterations > 0, "newton_iterations: must be positive");
  need(o.projective.iterations > 0, "projective_iterations: must be positive");
  need(o.projective.lbfgs_history >= 0, "projective_lbfgs_history: must be ≥ 0");
  need(std::isfinite(o.iteration_tolerance) && o.iteration_tolerance > 0.0, "newton_tolerance: must be positive");
  need(std::isfinite(o.dt_min) && o.dt_min > 0.0 && o.dt_min <= o.dt, "dt_min: must be positive and at most dt");
  need(std::isfinite(o.max_strain_change) && o.max_strain_change > 0.0, "max_strain_change: must be positive");
  const SelfCollisionOptions& sc = o.self_collision_options;
  need(std::isfinite(sc.thickness) && sc.thickness > 0.0, "cloth_thickness: must be positive");
  need(std::isfinite(sc.friction) && sc.friction >= 0.0, "cloth_friction: must be ≥ 0");
  need(sc.impulse_passes > 0 && sc.zone_passes > 0, "self-collision passes: must be positive");
  need(std::isfinite(o.seam_tolerance) && o.seam_tolerance > 0.0, "seam_tolerance: must be positive");
  need(std::isfinite(o.seam_closing_speed) && o.seam_closing_speed >= 0.0,
       "seam_closing_speed: must be zero or positive");
}

}  // namespace dresskit::cloth
