#include "dress_demo.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/mesh/errors.h"

namespace dresskit::cli {

DressDemoResult dress_demo(const TriangleMesh& body, const BodyShape& shape,
                           const TriangleMesh& trousers, const GarmentOptions& garments,
                           const DressDemoOptions& options) {
  if (!(options.seconds > 0.0)) throw InputError("dress seconds: must be positive");
  if (!(options.dt > 0.0)) throw InputError("dress dt: must be positive");
  if (options.iterations <= 0) throw InputError("dress iterations: must be positive");
  const auto start = std::chrono::steady_clock::now();
  // The t-shirt is worn over the trousers: a little more ease, so that the two start apart where
  // they overlap at the waist.
  GarmentOptions over = garments;
  over.ease += options.over_ease;
  const TriangleMesh tshirt = make_garment(shape, GarmentKind::tshirt, over);

  SimulationOptions sim_options;
  sim_options.integrator = Integrator::projective;
  sim_options.projective_iterations = options.iterations;
  sim_options.adaptive = true;
  sim_options.dt = options.dt;
  sim_options.air_damping = 0.5;
  sim_options.strain_limiting = true;
  sim_options.strain_limit = 0.1;
  sim_options.self_collision = true;
  auto distance = std::make_shared<const MeshDistance>(body);
  sim_options.colliders.push_back(Collider::mesh(distance, 0.5));
  const ClothModel model = stack_layers({build_cloth(trousers, fabric_by_name("11oz-black-denim")),
                                         build_cloth(tshirt, fabric_by_name("gray-interlock"))},
                                        0.003);
  ClothSimulator sim(model, sim_options);
  // Trousers stay up by their waistband (held as by a belt); the t-shirt hangs from the shoulders.
  const double top = trousers.V.col(1).maxCoeff();
  std::vector<int> belt;
  for (Eigen::Index i = 0; i < trousers.V.rows(); ++i)
    if (trousers.V(i, 1) >= top - options.waistband) belt.push_back(static_cast<int>(i));
  sim.set_pinned(belt);

  const int at_start = sim.intersections();
  DressDemoResult result;
  std::string stopped = "duration reached";
  int done = 0, retries = 0;
  double smallest = options.dt;
  while (sim.time() < options.seconds - 1e-9 * options.dt) {
    const StepResult r = sim.step();
    retries += r.retries;
    if (!r.ok) {
      result.ok = false;
      stopped = r.failure;
      break;
    }
    ++done;
    smallest = std::min(smallest, r.dt);
  }
  const Eigen::MatrixX3d& x = sim.positions();
  int inside = 0;
  Eigen::Vector3d n;
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    inside += distance->distance(x.row(i).transpose(), &n) < 0.0;

  TriangleMesh worn_trousers = trousers, worn_tshirt = tshirt;
  worn_trousers.V = x.topRows(trousers.V.rows());
  worn_tshirt.V = x.bottomRows(tshirt.V.rows());
  result.outfit = empty_mesh();
  append_mesh(result.outfit, worn_trousers, "trousers_");
  append_mesh(result.outfit, worn_tshirt, "tshirt_");
  result.dressed = empty_mesh();
  append_mesh(result.dressed, body, "");
  append_mesh(result.dressed, result.outfit, "");
  result.report = {
      {"garments",
       {"trousers (11oz-black-denim, waistband held)", "tshirt (gray-interlock, worn over)"}},
      {"particles", x.rows()},
      {"integrator", to_string(sim_options.integrator)},
      {"projective_iterations", options.iterations},
      {"dt", options.dt},
      {"smallest_dt", smallest},
      {"steps", done},
      {"step_retries", retries},
      {"simulated_seconds", sim.time()},
      {"stopped_reason", stopped},
      {"max_strain", sim.max_strain()},
      {"mean_strain", sim.mean_strain()},
      {"intersections", {{"at_start", at_start}, {"at_end", sim.intersections()}}},
      {"particles_inside_body_at_end", inside},
      {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
  return result;
}

}  // namespace dresskit::cli
