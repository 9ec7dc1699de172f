#include "dresskit/pattern/sew.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/simulator.h"

using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace dresskit::pattern {

SewResult sew_pattern(const Pattern& pattern, const CutPattern& cut, const TriangleMesh& body,
                      const SewOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  SewResult r;
  // The panels as placed: each one is its flat shape turned and moved, so the springs' rest lengths
  // are the flat pattern's.
  TriangleMesh panels = placed_mesh(pattern, cut);
  ClothModel model = build_cloth(panels, fabric_by_name(options.fabric));
  const StitchLaw law{default_stitch_stiffness(model.springs), 1.0};
  const int nv = int(cut.placed.rows());
  for (std::size_t s = 0, k = 0; s < pattern.stitches.size(); ++s) {
    std::vector<std::array<int, 2>> pairs;
    for (; k < cut.stitch_pairs.size() && cut.stitch_of_pair[k] == int(s); ++k)
      pairs.push_back(cut.stitch_pairs[k]);
    if (pairs.empty()) continue;
    const int first = model.seams.size();
    add_seam_pairs(model.seams, pairs, nv, law);
    cap_stitches_by_acceleration(model.seams, first, model.mass, options.stitch_acceleration);
  }
  SimulationOptions o;
  o.gravity = options.gravity;
  o.air_damping = options.air_damping;
  o.seam_tolerance = options.tolerance;
  o.self_collision = options.self_collision;
  o.max_strain_change = options.max_strain_change;
  if (options.body_collider)
    o.colliders.push_back(
        Collider::mesh(std::make_shared<const MeshDistance>(body), options.friction));
  ClothSimulator sim(model, o);
  r.stitch_pairs = model.seams.size();
  r.stopped = "time limit";
  // Gaps are checked every few steps: sewing stops once every pair is within the tolerance.
  for (;;) {
    const StepResult step = sim.step();
    if (!step.ok) {
      r.stopped = "failed: " + step.failure;
      break;
    }
    ++r.steps;
    if (r.steps % 5 == 0 || sim.time() >= options.max_seconds) {
      const SeamGaps g = seam_gaps(sim.model().seams, sim.positions(), options.tolerance);
      if (g.closed == g.stitches) {
        r.stopped = "closed";
        break;
      }
      if (sim.time() >= options.max_seconds) break;
    }
    if (r.steps >= options.max_steps) {
      r.stopped = "step limit";
      break;
    }
  }
  r.sewn = sim.positions();
  r.simulated_seconds = sim.time();
  const SeamGaps g = seam_gaps(sim.model().seams, r.sewn, options.tolerance);
  r.closed_pairs = g.closed;
  r.closed = g.closed == g.stitches;
  r.max_gap = g.max;
  r.stitch_gap.assign(pattern.stitches.size(), 0.0);
  for (std::size_t k = 0; k < cut.stitch_pairs.size(); ++k) {
    double& gap = r.stitch_gap[std::size_t(cut.stitch_of_pair[k])];
    gap = std::max(
        gap, (r.sewn.row(cut.stitch_pairs[k][0]) - r.sewn.row(cut.stitch_pairs[k][1])).norm());
  }
  r.mean_gap = g.mean;
  // Weld: closed pairs become single vertices; the panel labels follow their vertices.
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  weld_seams(r.sewn, model.faces, sim.model().seams, options.tolerance, V, F, r.welded_vertex);
  r.garment.V = V;
  r.garment.F = F;
  r.garment.labels = Eigen::VectorXi::Constant(V.rows(), -1);
  for (int v = 0; v < nv; ++v) r.garment.labels[r.welded_vertex[v]] = cut.panel_of_vertex[v];
  for (const Panel& p : pattern.panels) r.garment.label_names.push_back(p.name);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace dresskit::pattern
