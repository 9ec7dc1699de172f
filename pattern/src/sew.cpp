#include "dresskit/pattern/sew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/mesh/errors.h"

using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace dresskit::pattern {

namespace {

// One sewing run from the placed panels: drawn at the closing speed, or pulled by seam forces (each
// stitch's pairs together at most acceleration × the cloth's mass). Where `first` marks some
// stitches, those are sewn first and the others from where that leaves the panels.
SewResult sew_once(const Pattern& pattern, const CutPattern& cut, const TriangleMesh& panels,
                   const std::shared_ptr<const MeshDistance>& body, const SewOptions& options,
                   double acceleration, const std::vector<char>& first) {
  SewResult r;
  ClothModel model = build_cloth(panels, fabric_by_name(options.fabric));
  const double k = default_stitch_stiffness(model.springs);
  const int nv = int(cut.placed.rows());
  // The stitches for which `take` holds, in the pattern's order (their pairs are contiguous).
  auto stitches = [&](const std::function<bool(std::size_t)>& take) {
    SeamSet seams;
    for (std::size_t s = 0, p = 0; s < pattern.stitches.size(); ++s) {
      std::vector<std::array<int, 2>> pairs;
      for (; p < cut.stitch_pairs.size() && cut.stitch_of_pair[p] == int(s); ++p)
        pairs.push_back(cut.stitch_pairs[p]);
      if (pairs.empty() || !take(s)) continue;
      const int start = seams.size();
      add_seam_pairs(seams, pairs, nv, {k, 0.0});
      if (acceleration > 0.0) cap_stitches_by_acceleration(seams, start, model.mass, acceleration);
    }
    return seams;
  };
  model.seams = stitches([](std::size_t) { return true; });
  SimulationOptions o;
  o.gravity = options.gravity;
  o.air_damping = options.air_damping;
  o.seam_tolerance = options.tolerance;
  o.seam_closing_speed = acceleration > 0.0 ? 0.0 : options.closing_speed;
  o.self_collision = options.self_collision;
  o.max_strain_change = options.max_strain_change;
  if (body)
    o.colliders.push_back(
        Collider::mesh(body, acceleration > 0.0 ? options.fallback_friction : options.friction));
  r.stitch_pairs = model.seams.size();
  // Sewing stops once the simulator holds every pair (each came within the tolerance), or at the
  // limits, which both stages share.
  double simulated = 0.0;
  const double contact_budget =
      options.max_contacts_per_step * static_cast<double>(options.max_steps) * static_cast<double>(nv);
  auto sew = [&](ClothSimulator& sim) {
    for (;;) {
      const StepResult step = sim.step();
      if (!step.ok) {
        r.stopped = "failed: " + step.failure;
        return false;
      }
      ++r.steps;
      r.contacts += step.self.proximity_pairs + step.self.ccd_collisions + step.self.zone_particles;
      if (options.on_step) options.on_step(simulated + sim.time(), options.max_seconds);
      if (std::all_of(sim.sewn().begin(), sim.sewn().end(), [](char c) { return c != 0; })) {
        r.stopped = "closed";
        return true;
      }
      if (simulated + sim.time() >= options.max_seconds) {
        r.stopped = "time limit";
        return false;
      }
      if (r.steps >= options.max_steps) {
        r.stopped = "step limit";
        return false;
      }
      if (contact_budget > 0.0 && static_cast<double>(r.contacts) > contact_budget) {
        r.stopped = "contact limit";
        return false;
      }
    }
  };
  ClothSimulator sim(model, o);
  bool go_on = true;
  if (std::find(first.begin(), first.end(), 1) != first.end()) {
    ClothModel hanging = model;
    hanging.seams = stitches([&](std::size_t s) { return first[s] != 0; });
    ClothSimulator before(hanging, o);
    go_on = sew(before);
    simulated = before.time();
    sim.set_state(before.positions(), before.velocities());
  }
  if (go_on) {
    sew(sim);
  } else {
    const std::string stopped = r.stopped;
    sim.step();  // sews every pair within the tolerance, so that the result counts and welds them
    r.stopped = stopped;
  }
  r.sewn = sim.positions();
  r.simulated_seconds = simulated + sim.time();
  r.stitch_gap.assign(pattern.stitches.size(), 0.0);
  // The pairs to weld: those the simulator holds, and those left open within the weld gap.
  std::vector<char> weld(cut.stitch_pairs.size(), 0);
  for (std::size_t p = 0; p < cut.stitch_pairs.size(); ++p) {
    const double gap =
        (r.sewn.row(cut.stitch_pairs[p][0]) - r.sewn.row(cut.stitch_pairs[p][1])).norm();
    double& widest = r.stitch_gap[std::size_t(cut.stitch_of_pair[p])];
    widest = std::max(widest, gap);
    r.max_gap = std::max(r.max_gap, gap);
    r.mean_gap += gap / double(cut.stitch_pairs.size());
    weld[p] = sim.sewn()[p] || gap <= options.weld_gap;
    r.closed_pairs += sim.sewn()[p] != 0;
  }
  r.closed = r.closed_pairs == r.stitch_pairs;
  // Weld: sewn pairs, and pairs left open within the weld gap, become single vertices; the panel
  // labels follow their vertices. A held pair may lie up to a millimetre or two apart with a fold
  // of cloth between its sides, where several panels meet (the cloth–cloth pass keeps the fold
  // from the sides): welding it there makes the garment cross itself (the shirt's armpits, 6
  // times). The pairs of welded vertices in a crossing are left unwelded, a few rounds while that
  // lowers the crossings, and the sewn ones among them kept in r.unwelded.
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  auto weld_held = [&] {
    SeamSet held;
    for (std::size_t p = 0; p < cut.stitch_pairs.size(); ++p)
      if (weld[p]) add_seam_pairs(held, {cut.stitch_pairs[p]}, nv, {k, 0.0});
    weld_seams(r.sewn, model.faces, held, std::numeric_limits<double>::infinity(), V, F,
               r.welded_vertex);
  };
  weld_held();
  for (int crossings = count_intersections(V, F), round = 0; crossings > 0 && round < 4; ++round) {
    const std::vector<int> crossing = crossing_vertices(V, F);
    std::vector<char> before = weld;
    for (std::size_t p = 0; p < cut.stitch_pairs.size(); ++p)
      if (weld[p] && std::binary_search(crossing.begin(), crossing.end(),
                                        r.welded_vertex[std::size_t(cut.stitch_pairs[p][0])]))
        weld[p] = 0;
    if (weld == before) break;
    weld_held();
    const int now = count_intersections(V, F);
    if (now >= crossings) {  // no better: welded as before
      weld = before;
      weld_held();
      break;
    }
    crossings = now;
  }
  for (std::size_t p = 0; p < cut.stitch_pairs.size(); ++p) {
    const int a = r.welded_vertex[std::size_t(cut.stitch_pairs[p][0])];
    const int b = r.welded_vertex[std::size_t(cut.stitch_pairs[p][1])];
    if (sim.sewn()[p] && !weld[p] && a != b) r.unwelded.push_back({a, b});  // (joined by others)
    r.welded_open += !sim.sewn()[p] && weld[p];
  }
  r.garment.V = V;
  r.garment.F = F;
  r.garment.labels = Eigen::VectorXi::Constant(V.rows(), -1);
  for (int v = 0; v < nv; ++v) r.garment.labels[r.welded_vertex[v]] = cut.panel_of_vertex[v];
  for (const Panel& p : pattern.panels) r.garment.label_names.push_back(p.name);
  return r;
}

// The panels moved together from the pattern's body's frame to this body's
// (SewOptions::pattern_body): by the difference of the origins, and up or down so that their
// centroid's height over the floor scales with the bodies' heights. One move for all keeps the
// panels' places relative to each other: seams that meet as placed still meet.
Eigen::RowVector3d move_panels(TriangleMesh& panels, const BodyFrame& from, const BodyFrame& to) {
  const Eigen::RowVector3d c = panels.V.colwise().mean();
  Eigen::RowVector3d d = (to.origin - from.origin).transpose();
  d.y() += (to.height / from.height - 1.0) * (c.y() - from.origin.y());
  panels.V.rowwise() += d;
  return d;
}

// Panels carried to a larger body may lie in it: each such panel is moved out along its normal
// (its faces point away from the body) in steps of the clearance until every point of it is that
// far outside, or half a metre out. Returns the panels moved.
int move_panels_out(TriangleMesh& panels, const CutPattern& cut, int count,
                    const MeshDistance& body, double clearance) {
  Eigen::MatrixX3d normal = Eigen::MatrixX3d::Zero(count, 3);
  for (Eigen::Index f = 0; f < panels.F.rows(); ++f) {
    const Eigen::RowVector3d a = panels.V.row(panels.F(f, 0));
    normal.row(cut.panel_of_face[f]) +=
        (panels.V.row(panels.F(f, 1)) - a).cross(panels.V.row(panels.F(f, 2)) - a);
  }
  int moved = 0;
  for (int q = 0; q < count; ++q) {
    const Eigen::RowVector3d n = normal.row(q).normalized();
    auto clear = [&](double t) {
      for (Eigen::Index v = 0; v < panels.V.rows(); ++v) {
        Eigen::Vector3d unused;
        if (panels.labels[v] == q &&
            body.distance((panels.V.row(v) + t * n).transpose(), &unused) < clearance)
          return false;
      }
      return true;
    };
    double t = 0.0;
    while (t < 0.5 && !clear(t)) t += clearance;
    if (t == 0.0) continue;
    for (Eigen::Index v = 0; v < panels.V.rows(); ++v)
      if (panels.labels[v] == q) panels.V.row(v) += t * n;
    ++moved;
  }
  return moved;
}

}  // namespace

BodyFrame body_frame(const TriangleMesh& body) {
  BodyFrame f;
  const double floor = body.V.col(1).minCoeff();
  f.height = body.V.col(1).maxCoeff() - floor;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (Eigen::Index v = 0; v < body.V.rows(); ++v) {
    const double y = body.V(v, 1) - floor;
    if (y < 0.55 * f.height || y > 0.7 * f.height) continue;
    lo = lo.cwiseMin(body.V.row(v).transpose());
    hi = hi.cwiseMax(body.V.row(v).transpose());
  }
  if (!(lo.x() <= hi.x())) {  // no vertex in that band (a coarse mesh): its whole bounding box
    lo = body.V.colwise().minCoeff().transpose();
    hi = body.V.colwise().maxCoeff().transpose();
  }
  f.origin = 0.5 * (lo + hi);
  f.origin.y() = floor;
  return f;
}

SewResult sew_pattern(const Pattern& pattern, const CutPattern& cut, const TriangleMesh& body,
                      const SewOptions& options, std::shared_ptr<const MeshDistance> body_distance) {
  const auto t0 = std::chrono::steady_clock::now();
  // The panels as placed: each one is its flat shape turned and moved, so the springs' rest lengths
  // are the flat pattern's.
  TriangleMesh panels = placed_mesh(pattern, cut);
  // Carried to this body where it stands elsewhere than the pattern's or is of another height.
  Eigen::RowVector3d moved = Eigen::RowVector3d::Zero();
  bool carried = false;
  int moved_out = 0;
  const BodyFrame here = body.V.rows() > 0 ? body_frame(body) : BodyFrame{};
  if (!options.panel_moves.empty()) {
    if (options.panel_moves.size() != pattern.panels.size())
      throw std::invalid_argument("sew_pattern: " + std::to_string(options.panel_moves.size()) +
                                  " panel moves for " + std::to_string(pattern.panels.size()) + " panels");
    const Eigen::MatrixX3d before = panels.V;
    for (Eigen::Index v = 0; v < panels.V.rows(); ++v) {
      const Eigen::Matrix4d& T = options.panel_moves[std::size_t(cut.panel_of_vertex[v])];
      panels.V.row(v) = (T.topLeftCorner<3, 3>() * before.row(v).transpose() + T.topRightCorner<3, 1>()).transpose();
    }
    if (panels.V.rows() > 0) moved = (panels.V - before).colwise().mean();
    carried = true;
  } else if (body.V.rows() > 0) {
    const BodyFrame& from = options.pattern_body;
    if (!(from.height > 0.0))
      throw InputError("the pattern's body height " + std::to_string(from.height) +
                       " m is not positive");
    carried = (here.origin - from.origin).norm() > options.frame_tolerance ||
              std::abs(here.height / from.height - 1.0) > 0.02;
    if (carried) moved = move_panels(panels, from, here);
  }
  std::shared_ptr<const MeshDistance> distance;
  if (options.body_collider) {
    distance = body_distance ? std::move(body_distance) : std::make_shared<const MeshDistance>(body);
    if (carried)
      moved_out =
          move_panels_out(panels, cut, int(pattern.panels.size()), *distance, options.clearance);
    // Panels that the pattern places inside this body cannot be sewn around it.
    int inside = 0;
    for (Eigen::Index v = 0; v < panels.V.rows(); ++v) {
      Eigen::Vector3d n;
      inside += distance->distance(panels.V.row(v).transpose(), &n) < -options.inside_depth;
    }
    if (inside > options.max_inside_fraction * double(panels.V.rows()))
      throw InputError("the pattern places " + std::to_string(inside) + " of its " +
                       std::to_string(panels.V.rows()) + " panel points more than " +
                       std::to_string(int(std::lround(1e3 * options.inside_depth))) +
                       " mm inside the body: it is placed for another body");
  }
  // The stitches that hold the garment up, above the given share of the body's height, are sewn
  // first where some lie below it.
  std::vector<char> first(pattern.stitches.size(), 0);
  if (body.V.rows() > 0 && options.first_above > 0.0) {
    const double above = here.origin.y() + options.first_above * here.height;
    std::vector<double> height(first.size(), 0.0), points(first.size(), 0.0);
    for (std::size_t p = 0; p < cut.stitch_pairs.size(); ++p) {
      const std::size_t s = std::size_t(cut.stitch_of_pair[p]);
      height[s] += panels.V(cut.stitch_pairs[p][0], 1) + panels.V(cut.stitch_pairs[p][1], 1);
      points[s] += 2.0;
    }
    for (std::size_t s = 0; s < first.size(); ++s)
      first[s] = points[s] > 0.0 && height[s] / points[s] > above;
    if (std::count(first.begin(), first.end(), 1) + std::count(points.begin(), points.end(), 0.0) ==
        std::ptrdiff_t(first.size()))
      first.assign(first.size(), 0);  // none below: all at once
  }
  SewResult r = sew_once(pattern, cut, panels, distance, options, 0.0, first);
  r.method = "drawn";
  // Pairs left open within the weld gap are welded (sew_once); seam forces are for the farther.
  if (!r.closed && r.max_gap > options.weld_gap && options.fallback_acceleration > 0.0) {
    SewResult pulled =
        sew_once(pattern, cut, panels, distance, options, options.fallback_acceleration, first);
    pulled.method = "seam forces";
    const int steps = r.steps + pulled.steps;
    const long long contacts = r.contacts + pulled.contacts;
    // Kept where it closes, or comes closer without crossing itself more (seam forces can tangle
    // the panels where drawing left a seam open).
    const auto crossings = [](const SewResult& s) {
      return count_intersections(s.garment.V, s.garment.F);
    };
    if (pulled.closed || (pulled.max_gap < r.max_gap && crossings(pulled) <= crossings(r)))
      r = std::move(pulled);
    r.steps = steps;
    r.contacts = contacts;
  }
  r.moved_by = moved.transpose();
  r.panels_moved_out = moved_out;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace dresskit::pattern
