#pragma once
// Squares of cloth dropped onto real bodies (../shared/data): what a new user tries first, named
// only by what a user knows (the cloth, its fabric, the body and the units), and the checks that a
// drape must pass, made without the simulator's own distance grid.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "dresskit/cloth/run.h"

namespace dresskit::testing {

struct DropCase {
  std::string name;
  std::string body;           ///< file under data_dir()/bodies
  std::string units = "m";    ///< the scene's length unit
  std::string body_units = "m";
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< cloth centre [units]
  double size = 0.8;          ///< side of the square [units]
  int resolution = 40;        ///< vertices per side
  std::string fabric = "gray-interlock";
};

/// The standard cases: onto the head (gc_mean_all, m), onto a shoulder, over a T-pose arm
/// (gc_mean_all_tpose), onto the head from 3.5 m, the stiffest fabric onto the head, onto a
/// MakeHuman man's head in decimetres, onto a MakeHuman woman's head with the scene in centimetres
/// and the body in decimetres. `resolution` scales the cloth (vertices per side for
/// the 0.8 m squares; the smaller squares keep their spacing).
std::vector<DropCase> drop_cases(int resolution = 40);
const DropCase& drop_case(const std::string& name, int resolution = 40);

/// The scene's JSON: the cloth, fabric, the body collider and the units; `simulation` is the
/// scene's "simulation" object (e.g. {"integrator": "newton"}), "{}" for the defaults.
std::string drop_scene(const DropCase& c, const std::string& simulation = "{}", double duration = 2.0);

struct DropOutcome {
  cloth::RunResult run;
  int steps = 0;
  double simulated = 0.0;       ///< [s]
  double seconds = 0.0;         ///< CPU time of the run (stepping thread) [s]
  int inside = 0;               ///< cloth vertices deeper than 2 mm inside the body (mesh/inside.h)
  double deepest = 0.0;         ///< deepest vertex inside the body [m]
  int crossings = 0;            ///< edge–triangle crossings of the cloth at the end
  double max_strain = 0.0;      ///< largest structural strain at the end
  double drop = 0.0;            ///< how far the cloth's centre of mass fell [m]
  bool passed() const;          ///< ok, nothing inside, no crossing, strain ≤ 12 %, fell ≥ 2 cm
};

/// Writes the scene into `dir`, loads it as `dress-a-mesh simulate` does, runs it for `duration`
/// (stopping at rest as a scene does by default) and checks the end state.
DropOutcome run_drop(const DropCase& c, const std::string& simulation, const std::string& dir,
                     double duration = 2.0);

}  // namespace dresskit::testing
