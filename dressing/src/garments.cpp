#include "garments.h"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unordered_map>
#include <utility>

#include "dresskit/cloth/geometry.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "dresskit/mesh/arap.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/names.h"
#include "dresskit/mesh/topology.h"

using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace dresskit::dressing::detail {
namespace {

/// Weight of a vertex held at a position in an as-rigid-as-possible fit (arap_fit): moving it one
/// mean edge costs as much as stretching 100 edges by 100 %.
constexpr double kHeld = 100.0;

/// An as-rigid-as-possible fit of a garment's rest shape to its placed positions, vertices of
/// weight 0 free, the others held, that stays out of the body: with `push`, free vertices the fit
/// takes into the body are first held `clearance` outside it along its normal; then any still
/// inside are held at their positions in g.placed (outside it: placement pushed them out, and a
/// fit kept earlier left none deep). Returns the positions and how many
/// vertices lie deeper than 5 mm inside the body.
std::pair<Eigen::MatrixX3d, int> fit_outside(const DressedGarment& g, const Eigen::MatrixX3d& rest, Eigen::VectorXd weight,
                                             const MeshDistance& body, double clearance, bool push) {
  Eigen::MatrixX3d target = g.placed;
  Eigen::MatrixX3d x = arap_fit(rest, g.mesh.F, target, weight);
  auto depth = [&](Eigen::Index v) {
    Eigen::Vector3d n;
    const double d = body.distance(x.row(v).transpose(), &n);
    return std::make_pair(clearance - d, n);
  };
  for (int round = 0, pushes = push ? 8 : 0; round < pushes + 4; ++round) {
    const bool pushing = round < pushes;
    int moved = 0;
    for (Eigen::Index v = 0; v < x.rows(); ++v) {
      const auto [under, n] = depth(v);
      if (under <= 0.0 || weight(v) >= kHeld) continue;
      target.row(v) = pushing ? Eigen::RowVector3d(x.row(v) + under * n.transpose()) : g.placed.row(v);
      weight(v) = pushing ? 1.0 : kHeld;
      ++moved;
    }
    if (moved > 0) x = arap_fit(rest, g.mesh.F, target, weight);
    else if (pushing) round = pushes - 1;  // nothing inside: on to the holding rounds
    else break;
  }
  int deep = 0;
  for (Eigen::Index v = 0; v < x.rows(); ++v) deep += depth(v).first > clearance + 0.005;
  return {x, deep};
}

}  // namespace

std::vector<std::string> dressed_warnings(const DressedGarment& g, const std::string& padding_stalled) {
  std::vector<std::string> w;
  if (g.crossings_dressed > g.crossings_authored)
    w.push_back(g.name + " crosses itself " + counted(g.crossings_dressed, "time", "times") + " (" +
                std::to_string(g.crossings_authored) + (g.from_pattern ? " as sewn)" : " as authored)"));
  if (g.inside_dressed > 0)
    w.push_back(g.name + " has " + counted(g.inside_dressed, "vertex", "vertices") + " deeper than 2 mm inside the body");
  const SewnPattern& p = g.pattern;
  if (g.from_pattern && p.sewn_pairs < p.stitch_pairs) {
    char gap[32];
    std::snprintf(gap, sizeof gap, "%.3g", 1e3 * p.max_gap);
    const int open = p.stitch_pairs - p.sewn_pairs;
    w.push_back(g.name + ": " + std::to_string(open) + " of " + counted(p.stitch_pairs, "stitch pair", "stitch pairs") +
                " not sewn, the widest " + gap + " mm open" +
                (p.welded_open_pairs == 0      ? ""
                 : p.welded_open_pairs == open ? "; welded shut"
                                               : "; " + std::to_string(p.welded_open_pairs) + " of them welded shut"));
  }
  for (std::size_t k = 0; k < p.panel_area_dressed.size() && k < p.panel_area.size(); ++k) {
    const double change = p.panel_area_dressed[k] / p.panel_area[k] - 1.0;
    if (!(std::abs(change) <= kPanelAreaChange)) {
      char percent[32];
      std::snprintf(percent, sizeof percent, "%.3g", 100.0 * std::abs(change));
      w.push_back(g.name + ": panel '" + p.panels[k] + "' " + (change > 0.0 ? "grew" : "shrank") + " by " + percent +
                  " % of its flat area");
    }
  }
  if (g.padded && !padding_stalled.empty()) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.3g", 1e3 * g.padding.min);
    w.push_back(g.name + ": the padding " + padding_stalled + "; kept where it stopped, " +
                counted(g.padding.below_min, "vertex", "vertices") + " below its lower limit of " + limit + " mm");
  }
  return w;
}

TriangleMesh rest_shape(const DressedGarment& g) {
  TriangleMesh rest = g.mesh;
  if (g.rest.rows() == rest.V.rows()) rest.V = g.rest;
  return rest;
}

Eigen::MatrixX3d loosened_rest(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& placed,
                               double strain_limit, double largest, int* grown) {
  const Eigen::Index n = rest.rows();
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(F, static_cast<int>(n));
  std::vector<std::array<int, 2>> edges;
  std::vector<double> growth;  // each edge's rest vector's scale
  // An edge's placed length over the longest the limit allows it at positions x.
  const auto over = [&](const Eigen::MatrixX3d& x, std::size_t e) {
    const auto [a, b] = edges[e];
    return (placed.row(a) - placed.row(b)).norm() / ((1.0 + strain_limit) * (x.row(a) - x.row(b)).norm());
  };
  for (Eigen::Index a = 0; a < n; ++a)
    for (int b : neighbours[static_cast<std::size_t>(a)])
      if (b > a && (rest.row(a) - rest.row(b)).norm() > 0.0) edges.push_back({static_cast<int>(a), b});
  int stretched = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    growth.push_back(std::clamp(over(rest, e), 1.0, largest));
    stretched += growth.back() > 1.0;
  }
  if (grown) *grown = stretched;
  if (stretched == 0) return rest;
  // Normal equations of Σ_e w_e |(x_a − x_b) − s_e (r_a − r_b)|² + ε Σ_v |x_v − r_v|²: the grown
  // edge vectors with weights w_e = 1 / L0² (each edge's relative change counts alike); the tiny
  // ε keeps each piece where it was.
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> w(edges.size());
  double h = 0.0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    const double L0 = (rest.row(a) - rest.row(b)).norm();
    w[e] = 1.0 / (L0 * L0);
    triplets.emplace_back(a, a, w[e]);
    triplets.emplace_back(b, b, w[e]);
    triplets.emplace_back(a, b, -w[e]);
    triplets.emplace_back(b, a, -w[e]);
    h += L0 / static_cast<double>(edges.size());
  }
  const double anchor = 1e-6 / (h * h);
  for (Eigen::Index v = 0; v < n; ++v) triplets.emplace_back(v, v, anchor);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) return rest;
  // A grown edge shares its vertices with edges that are not (a ring's diagonals), so the least-
  // squares shape grows it less than asked: the edges still over the limit are asked for more, a
  // few times, never beyond `largest`.
  Eigen::MatrixX3d x = rest;
  constexpr int kRounds = 4;
  for (int round = 0; round < kRounds; ++round) {
    Eigen::MatrixX3d rhs = anchor * rest;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [a, b] = edges[e];
      const Eigen::RowVector3d g = w[e] * growth[e] * (rest.row(a) - rest.row(b));
      rhs.row(a) += g;
      rhs.row(b) -= g;
    }
    const Eigen::MatrixX3d next = solver.solve(rhs);
    if (!next.allFinite()) break;
    x = next;
    if (round + 1 == kRounds) break;
    for (std::size_t e = 0; e < edges.size(); ++e)
      if (growth[e] > 1.0) growth[e] = std::min(largest, growth[e] * std::max(1.0, over(x, e)));
  }
  return x;
}

cloth::ClothModel garment_cloth(const DressedGarment& g, const cloth::Fabric& fabric) {
  cloth::ClothModel model = cloth::build_cloth(rest_shape(g), fabric);
  const SewnPattern& p = g.pattern;
  if (!g.from_pattern) return model;
  if (!p.unwelded.empty()) {  // sewn, not welded: held by seams pulling at most 40 m/s² × the mass
    cloth::add_seam_pairs(model.seams, p.unwelded, static_cast<int>(model.rest_positions.rows()),
                          {cloth::default_stitch_stiffness(model.springs), 0.0});
    cloth::cap_stitches_by_acceleration(model.seams, 0, model.mass, 40.0);
  }
  if (p.flat_edges.empty()) return model;
  cloth::SpringSet& s = model.springs;
  for (int k = 0; k < s.size(); ++k) {
    if (s.type[k] != cloth::SpringType::structural) continue;
    const std::array<int, 2> edge{std::min(s.i[k], s.j[k]), std::max(s.i[k], s.j[k])};
    const auto it = std::lower_bound(p.flat_edges.begin(), p.flat_edges.end(), edge);
    if (it == p.flat_edges.end() || *it != edge) continue;
    const double L = p.flat_edge_length[std::size_t(it - p.flat_edges.begin())];
    const double scale = (s.rest_length[k] / L) * (s.rest_length[k] / L);  // k ∝ 1 / L0²
    s.rest_length[k] = L;
    s.k_rest[k] *= scale;
    s.k_knee[k] *= scale;
  }
  return model;
}

int crossings_between(const std::vector<DressedGarment>& garments, Eigen::MatrixX3d DressedGarment::*at) {
  if (garments.size() < 2) return 0;
  TriangleMesh all = empty_mesh();
  int own = 0;
  for (const DressedGarment& g : garments) {
    TriangleMesh m;
    m.V = g.*at;
    m.F = g.mesh.F;
    if (at == &DressedGarment::dressed && g.dressed_outer.rows() > 0) {  // a padded garment: both shells
      TriangleMesh outer = m;
      outer.V = g.dressed_outer;
      append_mesh(m, outer, "");
    }
    own += count_intersections(m.V, m.F);
    append_mesh(all, m, "");
  }
  return std::max(0, count_intersections(all.V, all.F) - own);
}

std::vector<Grading> grade_layers(std::vector<DressedGarment>& garments, const std::shared_ptr<const MeshDistance>& body,
                                  double separation) {
  // Moves spread this many rings of neighbours: a smooth bulge a few edges wide around a region
  // moved out.
  constexpr int kSpread = 8;
  // Over a layer beneath that is not smooth at the scale of the garment's triangles (collars,
  // pockets, wrinkles), a vertex just over it can have edges that dip under it: the vertices of
  // such crossings move kStep farther out, up to kRounds times.
  constexpr int kRounds = 30;
  constexpr double kStep = 0.002;  // [m]
  std::vector<Grading> graded(garments.size());
  if (garments.size() < 2) return graded;
  const std::vector<Collider> colliders = {Collider::mesh(body)};
  // The garments stacked in one numbering: positions, faces and each vertex's garment.
  std::vector<int> first = {0}, garment_of;
  std::vector<Eigen::Index> faces_end;
  for (const DressedGarment& g : garments) first.push_back(first.back() + static_cast<int>(g.placed.rows()));
  Eigen::MatrixX3d x(first.back(), 3);
  Eigen::MatrixX3i faces(0, 3);
  for (std::size_t k = 0; k < garments.size(); ++k) {
    const DressedGarment& g = garments[k];
    x.middleRows(first[k], g.placed.rows()) = g.placed;
    garment_of.insert(garment_of.end(), static_cast<std::size_t>(g.placed.rows()), static_cast<int>(k));
    faces.conservativeResize(faces.rows() + g.mesh.F.rows(), 3);
    faces.bottomRows(g.mesh.F.rows()) = g.mesh.F.array() + first[k];
    faces_end.push_back(faces.rows());
  }
  for (std::size_t k = 1; k < garments.size(); ++k) {  // inner garments first: their moves carry outwards
    const int n = first[k + 1] - first[k];
    const Eigen::MatrixX3i& F = garments[k].mesh.F;
    // Two layers for match_layers: every garment beneath this one, and this one.
    ClothModel worn;
    worn.faces = faces.topRows(faces_end[k]);
    worn.layer = Eigen::VectorXi::Zero(first[k + 1]);
    worn.layer.tail(n).setOnes();
    const std::vector<std::vector<int>> neighbours = vertex_neighbours(F, n);
    const Eigen::MatrixX3d start = x.middleRows(first[k], n);
    Eigen::MatrixX3d projected(n, 3);
    double reach = 0.0;  // the garment's mean edge [m]
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int e = 0; e < 3; ++e) reach += (start.row(F(f, e)) - start.row(F(f, (e + 1) % 3))).norm();
    reach /= std::max<double>(1.0, 3.0 * static_cast<double>(F.rows()));
    Eigen::VectorXd extra = Eigen::VectorXd::Zero(n), push = Eigen::VectorXd::Zero(n);
    // Where the body's normal does not lead out of the garments beneath (an armpit, the crotch), a
    // crossing's vertices move along the normal of the nearest face beneath instead, turned away
    // from the body.
    Eigen::MatrixXd away = Eigen::MatrixXd::Zero(n, 3);
    // Moves (one per row) spread over the mesh: kSpread times, each vertex takes its neighbours'
    // mean move where that is longer than its own.
    auto spread = [&](auto& moves) {
      for (int round = 0; round < kSpread; ++round) {
        Eigen::MatrixXd next = moves;
        for (int v = 0; v < n; ++v) {
          const std::vector<int>& around = neighbours[static_cast<std::size_t>(v)];
          if (around.empty()) continue;
          Eigen::RowVectorXd mean = Eigen::RowVectorXd::Zero(moves.cols());
          for (int u : around) mean += moves.row(u);
          mean /= static_cast<double>(around.size());
          if (mean.squaredNorm() > moves.row(v).squaredNorm()) next.row(v) = mean;
        }
        moves = next;
      }
    };
    const TriangleBvh beneath(x.topRows(first[k]), faces.topRows(faces_end[k - 1]));
    for (int round = 0; round < kRounds; ++round) {
      x.middleRows(first[k], n) = start;
      const LayerContacts c = match_layers(worn, x.topRows(first[k + 1]), colliders, true);
      for (int v = 0; v < n; ++v) {
        const int p = first[k] + v;
        // Beside the garments beneath (past their hems), only the crossings' extra moves it.
        const double needed = c.below_face[p] < 0 ? c.distance[p] : c.height_below(p, worn, x, colliders) + separation;
        push(v) = std::max(0.0, needed + extra(v) - c.distance[p]);
      }
      spread(push);
      Eigen::MatrixXd moved_away = away;
      spread(moved_away);
      // Every sheet of this garment over one place of the body moves out as far as the lowest:
      // the largest push within one mean edge of a vertex's projection onto the body, so that a
      // lapel over a front or a pocket over a side keeps its side of it.
      if (reach > 0.0) {
        std::unordered_map<std::int64_t, std::vector<int>> grid;
        auto cell = [&](int v, int dx, int dy, int dz) {
          const Eigen::Vector3i q = (projected.row(v).transpose() / reach).array().floor().cast<int>();
          return grid_cell_key(Eigen::Vector3i(q + Eigen::Vector3i(dx, dy, dz)));
        };
        for (int v = 0; v < n; ++v) {
          projected.row(v) = x.row(first[k] + v) - c.distance[first[k] + v] * c.normal.row(first[k] + v);
          if (push(v) > 0.0) grid[cell(v, 0, 0, 0)].push_back(v);
        }
        Eigen::VectorXd widest = push;
        for (int v = 0; v < n; ++v)
          for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dz = -1; dz <= 1; ++dz) {
                const auto it = grid.find(cell(v, dx, dy, dz));
                if (it == grid.end()) continue;
                for (int u : it->second)
                  if ((projected.row(u) - projected.row(v)).squaredNorm() < reach * reach)
                    widest(v) = std::max(widest(v), push(u));
              }
        push = widest;
      }
      for (int v = 0; v < n; ++v) x.row(first[k] + v) += push(v) * c.normal.row(first[k] + v) + moved_away.row(v);
      // Vertices of this garment in crossings with those beneath.
      int crossing = 0;
      for (int p : crossing_vertices(x.topRows(first[k + 1]), worn.faces, garment_of)) {
        if (p < first[k]) continue;
        const int v = p - first[k];
        ++crossing;
        Eigen::Vector3d q;
        double d2 = 0.0;
        const int t = beneath.closest(x.row(p).transpose(), &q, &d2);
        if (t < 0) continue;
        const Eigen::Vector3i f = faces.row(t).transpose();
        Eigen::Vector3d out = (x.row(f[1]) - x.row(f[0])).cross(x.row(f[2]) - x.row(f[0])).transpose().normalized();
        Eigen::Vector3d body_normal;
        body->distance(q, &body_normal);
        if (out.dot(body_normal) < 0.0) out = -out;
        if (out.dot(c.normal.row(p)) > 0.7) extra(v) += kStep;
        else away.row(v) += kStep * out.transpose();
      }
      if (crossing == 0) break;
    }
    Grading& g = graded[k];
    for (int v = 0; v < n; ++v) {
      const double moved = (x.row(first[k] + v) - start.row(v)).norm();
      if (moved > 0.0) ++g.vertices, g.largest = std::max(g.largest, moved);
    }
    garments[k].placed = x.middleRows(first[k], n);
  }
  return graded;
}

/// Where placement made a garment cross itself (bending parts apart and together by their own
/// transforms), the crossing regions are rebuilt from the garment's rest shape, which keeps their
/// edges' lengths: the vertices of each crossing and their neighbours `rings` deep are left free
/// in fit_outside (with and without pushing), the rest held. Wider regions in turn until the
/// garment crosses itself no more than as authored or two widths in a row do not help; a fit is
/// kept only where it lowers the crossings, adds none with the other garments and takes no vertex
/// deep into the body.
void untangle(std::vector<DressedGarment>& garments, std::size_t k, const MeshDistance& body, double clearance) {
  DressedGarment& g = garments[k];
  const Eigen::MatrixX3d rest = rest_shape(g).V;
  const int between = crossings_between(garments, &DressedGarment::placed);
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(g.mesh.F, g.mesh.num_vertices());
  int fruitless = 0;
  for (int rings : {2, 4, 8, 12}) {
    Eigen::VectorXd weight = Eigen::VectorXd::Constant(g.mesh.num_vertices(), kHeld);
    std::vector<int> free = crossing_vertices(g.placed, g.mesh.F);
    for (int v : free) weight(v) = 0.0;
    for (int r = 0; r < rings; ++r) {
      std::vector<int> next;
      for (int v : free)
        for (int u : neighbours[static_cast<std::size_t>(v)])
          if (weight(u) > 0.0) {
            weight(u) = 0.0;
            next.push_back(u);
          }
      free = std::move(next);
    }
    const int before = g.crossings_placed;
    for (bool push : {true, false}) {
      std::pair<Eigen::MatrixX3d, int> fit;
      try {
        fit = fit_outside(g, rest, weight, body, clearance, push);
      } catch (const InputError&) {  // the fitting system could not be factored: no fit
        continue;
      }
      if (fit.second > 0 || !fit.first.allFinite()) continue;
      const int crossings = count_intersections(fit.first, g.mesh.F);
      if (crossings >= g.crossings_placed) continue;
      const Eigen::MatrixX3d placed = g.placed;
      g.placed = fit.first;
      if (crossings_between(garments, &DressedGarment::placed) > between) {
        g.placed = placed;
        continue;
      }
      g.crossings_placed = crossings;
    }
    if (g.crossings_placed <= g.crossings_authored) return;
    fruitless = g.crossings_placed < before ? 0 : fruitless + 1;
    if (fruitless == 2) return;
  }
}

/// Where rebuilding leaves a garment crossing itself more often than as authored, it is moved
/// instead from its rest shape under the placement's global similarity transform (which crosses
/// itself exactly as authored) towards its placed positions, in kSteps equal steps of each vertex's
/// straight path, with the simulator's cloth–cloth collisions (cloth/self_collision.h) keeping its
/// parts their default thickness apart on the way: a vertex stopped by another part tries again at
/// the next step. The garment ends at its placed positions except where its pieces would pass
/// through each other, there stopped where they meet, as settling would have them (a few may be
/// left inside the body, for settling to push out: it can do that, not undo a crossing). Kept
/// unless it adds crossings with the other garments.
void untangle_along_path(std::vector<DressedGarment>& garments, std::size_t k) {
  constexpr int kSteps = 24, kCatchUp = 8;
  DressedGarment& g = garments[k];
  if (g.crossings_placed <= g.crossings_authored) return;
  const int between = crossings_between(garments, &DressedGarment::placed);
  const Eigen::Matrix4d& T = g.placement.global;
  const Eigen::MatrixX3d start =
      ((g.mesh.V * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose()).eval();
  SelfCollision collisions(g.mesh.F, g.mesh.num_vertices(), {});
  const Eigen::VectorXd inverse_mass = Eigen::VectorXd::Ones(g.mesh.num_vertices());
  Eigen::MatrixX3d x = start;
  for (int step = 1; step <= kSteps + kCatchUp; ++step) {
    const double t = std::min(1.0, static_cast<double>(step) / kSteps);
    Eigen::MatrixX3d next = (1.0 - t) * start + t * g.placed;
    if (collisions.resolve(x, next, inverse_mass).held) continue;
    x = std::move(next);
  }
  const int crossings = count_intersections(x, g.mesh.F);
  if (crossings >= g.crossings_placed) return;
  const Eigen::MatrixX3d placed = g.placed;
  g.placed = x;
  if (crossings_between(garments, &DressedGarment::placed) > between) {
    g.placed = placed;
    return;
  }
  g.crossings_placed = crossings;
}

/// Part names, as segmentation or a label file gives them, of a garment's legs (trouser legs, skirt
/// parts) and of its sleeves.
bool names_legs(const std::string& part) { return part.rfind("leg", 0) == 0 || part.rfind("skirt", 0) == 0; }
bool names_sleeves(const std::string& part) { return part.rfind("sleeve", 0) == 0 || part.rfind("arm", 0) == 0; }

/// A garment with sleeves, or with no legs or skirt (a top, a dress, a jumpsuit); otherwise a bottom
/// (trousers, a skirt). A sewn pattern says it by its panels: one of a bodice (GarmentCode's
/// "…torso…") or a sleeve makes a top, whatever the segmentation of its sewn mesh (a hoody's sleeves,
/// hanging in A-pose, are cut as legs).
namespace {

/// The names of the parts that have vertices (a label file may name parts a garment lacks).
std::vector<std::string> parts_present(const TriangleMesh& m) {
  std::vector<bool> used(m.label_names.size(), false);
  for (Eigen::Index i = 0; i < m.labels.size(); ++i)
    if (m.labels(i) >= 0 && static_cast<std::size_t>(m.labels(i)) < used.size()) used[m.labels(i)] = true;
  std::vector<std::string> names;
  for (std::size_t k = 0; k < used.size(); ++k)
    if (used[k]) names.push_back(m.label_names[k]);
  return names;
}

}  // namespace

bool is_top(const DressedGarment& g) {
  if (g.from_pattern)
    return std::any_of(g.pattern.panels.begin(), g.pattern.panels.end(), [](const std::string& panel) {
      return panel.find("torso") != std::string::npos || panel.find("sleeve") != std::string::npos;
    });
  const std::vector<std::string> names = parts_present(g.mesh);
  return std::any_of(names.begin(), names.end(), names_sleeves) || std::none_of(names.begin(), names.end(), names_legs);
}

bool covers_legs(const DressedGarment& g) {
  if (g.from_pattern)
    return std::any_of(g.pattern.panels.begin(), g.pattern.panels.end(), [](const std::string& panel) {
      return panel.find("skirt") != std::string::npos || panel.find("pant") != std::string::npos ||
             panel.find("leg") != std::string::npos;
    });
  const std::vector<std::string> names = parts_present(g.mesh);
  return std::any_of(names.begin(), names.end(), names_legs);
}

/// The waistband of each bottom among a garment's pieces: a piece with leg or skirt parts, no
/// sleeves and its top below `shoulders` (the height of the body's shoulders [m]: trousers, a skirt;
/// not a dress or a jumpsuit, which hang from the shoulders, sleeved or not); its vertices within
/// `band` of its top, where they lie outside the body and their edges are stretched by at most
/// `max_strain` against `rest`. A waist placed tighter than that holds by itself, and held it would
/// keep the strain limit from ever being met. Returns garment rows.
std::vector<int> waistband(const DressedGarment& g, const Eigen::MatrixX3d& rest, double band, double max_strain,
                           const InsideTest& inside, double shoulders) {
  if (!(band > 0.0) || (g.from_pattern && is_top(g))) return {};  // a sewn top hangs from its shoulders
  std::vector<char> loose(static_cast<std::size_t>(g.mesh.num_vertices()), 1);
  for (int f = 0; f < g.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = g.mesh.F(f, k), b = g.mesh.F(f, (k + 1) % 3);
      const double L0 = (rest.row(a) - rest.row(b)).norm();
      if (L0 > 0.0 && (g.placed.row(a) - g.placed.row(b)).norm() > (1.0 + max_strain) * L0)
        loose[static_cast<std::size_t>(a)] = loose[static_cast<std::size_t>(b)] = 0;
    }
  int pieces = 0;
  const std::vector<int> piece = face_components(g.mesh.F, g.mesh.num_vertices(), &pieces);
  std::vector<int> piece_of(static_cast<std::size_t>(g.mesh.num_vertices()), -1);
  for (int f = 0; f < g.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) piece_of[static_cast<std::size_t>(g.mesh.F(f, k))] = piece[static_cast<std::size_t>(f)];
  std::vector<char> legs(static_cast<std::size_t>(pieces), 0), sleeves(static_cast<std::size_t>(pieces), 0);
  std::vector<double> top(static_cast<std::size_t>(pieces), -HUGE_VAL);
  for (int v = 0; v < g.mesh.num_vertices(); ++v) {
    const int c = piece_of[static_cast<std::size_t>(v)];
    if (c < 0) continue;
    top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], g.placed(v, 1));
    const int l = g.mesh.labels.size() ? g.mesh.labels(v) : -1;
    if (l < 0) continue;
    const std::string& name = g.mesh.label_names[static_cast<std::size_t>(l)];
    legs[static_cast<std::size_t>(c)] |= names_legs(name);
    sleeves[static_cast<std::size_t>(c)] |= names_sleeves(name);
  }
  std::vector<int> belt;
  for (int v = 0; v < g.mesh.num_vertices(); ++v) {
    const int c = piece_of[static_cast<std::size_t>(v)];
    if (c < 0 || !legs[static_cast<std::size_t>(c)] || sleeves[static_cast<std::size_t>(c)] ||
        top[static_cast<std::size_t>(c)] > shoulders)
      continue;
    if (g.placed(v, 1) >= top[static_cast<std::size_t>(c)] - band && loose[static_cast<std::size_t>(v)] &&
        inside.signed_distance(g.placed.row(v).transpose()) > 0.0)
      belt.push_back(v);
  }
  return belt;
}

}  // namespace dresskit::dressing::detail
