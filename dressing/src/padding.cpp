#include "padding.h"

#include <algorithm>
#include <cmath>

#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "dresskit/mesh/topology.h"
#include "garments.h"

using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace dresskit::dressing::detail {
namespace {

/// Rounds of halving the outer shell's start where it crosses something; a start below kStartFloor
/// becomes zero (the shells touch there: nothing lies between them and what is over them).
constexpr int kStartRounds = 32;
constexpr double kStartFloor = 1e-4;  // [m]
/// Neighbouring starts differ by at most this × their distance, so that the outer shell starts
/// without steps in it [unitless].
constexpr double kStartSlope = 0.3;

/// Turns the faces of every connected piece of the model whose normals at x point into the body
/// (by the body's distance a little way along them, summed over the piece) so that they point out.
void face_outwards(ClothModel& m, const Eigen::MatrixX3d& x, const MeshDistance& body) {
  int pieces = 0;
  const std::vector<int> piece = face_components(m.faces, static_cast<int>(x.rows()), &pieces);
  const Eigen::MatrixX3d n = vertex_normals(x, m.faces);
  std::vector<double> outward(static_cast<std::size_t>(pieces), 0.0);
  const double step = 0.002;
  Eigen::Vector3d unused;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d p = x.row(m.faces(f, c)).transpose(), d = step * n.row(m.faces(f, c)).transpose();
      outward[static_cast<std::size_t>(piece[static_cast<std::size_t>(f)])] +=
          body.distance(p + d, &unused) - body.distance(p - d, &unused);
    }
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f)
    if (outward[static_cast<std::size_t>(piece[static_cast<std::size_t>(f)])] < 0.0) std::swap(m.faces(f, 1), m.faces(f, 2));
}

/// How far each particle first + v can move along direction[v] before it meets a triangle of F at x
/// that does not have it as a corner, at most cap[v] [m]; hit[v]: that triangle, −1 none.
Eigen::VectorXd clearance(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& F, int first,
                          const Eigen::MatrixX3d& direction, const Eigen::VectorXd& cap, std::vector<int>* hit = nullptr) {
  const TriangleBvh tree(x, F);
  Eigen::VectorXd free = cap;
  if (hit) hit->assign(static_cast<std::size_t>(direction.rows()), -1);
  for (Eigen::Index v = 0; v < direction.rows(); ++v) {
    const int p = first + static_cast<int>(v);
    const Eigen::Vector3d o = x.row(p).transpose(), d = direction.row(v).transpose();
    if (d.squaredNorm() == 0.0) continue;
    Eigen::AlignedBox3d box(o);
    box.extend(o + cap(v) * d);
    tree.query(box, [&](int t) {
      if (F(t, 0) == p || F(t, 1) == p || F(t, 2) == p) return;
      const Eigen::Vector3d a = x.row(F(t, 0)).transpose(), b = x.row(F(t, 1)).transpose(), c = x.row(F(t, 2)).transpose();
      const Eigen::Vector3d fn = (b - a).cross(c - a);
      const double along = fn.dot(d);
      if (along == 0.0) return;
      const double s = fn.dot(a - o) / along;
      if (!(s >= 0.0 && s < free(v))) return;
      const Eigen::Vector3d q = o + s * d;
      if ((b - a).cross(q - a).dot(fn) >= 0.0 && (c - b).cross(q - b).dot(fn) >= 0.0 &&
          (a - c).cross(q - c).dot(fn) >= 0.0) {
        free(v) = s;
        if (hit) (*hit)[static_cast<std::size_t>(v)] = t;
      }
    });
  }
  return free;
}

/// The double layer of a padded garment settled as the sheet x (outward unit normals `normal`),
/// its outer shell starting `start` [m] out: padding springs of rest length `asked.thickness`, held
/// inside [min(start, asked.min), asked.max]. The outer shell's rest lengths are the sheet's,
/// scaled as the settled sheet's edges lengthen when moved out by the thickness along its normals
/// (a shell around a limb or over a fold is longer than the one beneath it; by at most twice, at
/// least half), and never shorter than its start over 1 + strain_limit (where the sheet is held
/// stretched by the body, the limits of both shells and of the padding could not all hold).
ClothModel padded_model(const ClothModel& single, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& normal,
                        const LayerThickness& asked, const Eigen::VectorXd& start, double strain_limit) {
  ClothModel d = make_double_layer(single, asked);
  d.layer_offset[1] = 0.0;  // held off the body by the padding, not by the collider's margin
  const int nv = static_cast<int>(single.rest_positions.rows());
  const Eigen::MatrixX3d full = x + asked.thickness * normal, begin = x + start.asDiagonal() * normal;
  SpringSet& s = d.springs;
  for (int k = 0; k < s.size(); ++k) {
    const int i = s.i[k], j = s.j[k];
    double& length = s.rest_length[static_cast<std::size_t>(k)];
    if (s.type[k] == SpringType::layer_shear) {
      const int a = i < nv ? i : j, b = (i < nv ? j : i) - nv;
      const double edge = (single.rest_positions.row(a) - single.rest_positions.row(b)).norm();
      length = std::hypot(edge, asked.thickness);
    } else if (s.type[k] != SpringType::layer_structural && i >= nv && j >= nv) {
      const double sheet = (x.row(i - nv) - x.row(j - nv)).norm();
      if (sheet > 0.0)
        length = std::max(length * std::clamp((full.row(i - nv) - full.row(j - nv)).norm() / sheet, 0.5, 2.0),
                          (begin.row(i - nv) - begin.row(j - nv)).norm() / (1.0 + strain_limit));
    }
  }
  for (std::size_t k = 0; k < s.limited.size(); ++k)
    s.limit_min[k] = std::min(asked.min, start(s.i[static_cast<std::size_t>(s.limited[k])]));
  return d;
}

/// The faces of a stacked model with corners in [lo, hi).
Eigen::MatrixX3i faces_within(const Eigen::MatrixX3i& F, int lo, int hi) {
  Eigen::MatrixX3i out(F.rows(), 3);
  int kept = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (F(f, 0) >= lo && F(f, 0) < hi) out.row(kept++) = F.row(f);
  out.conservativeResize(kept, 3);
  return out;
}

}  // namespace

PaddingRun pad_garments(std::vector<DressedGarment>& garments, const std::vector<Fabric>& fabrics, const MeshDistance& body,
                        const SimulationOptions& options, double separation, double seconds, int max_steps,
                        const std::vector<std::vector<int>>& belt, const std::function<void(double, double)>& on_settle) {
  const std::size_t n = garments.size();
  std::vector<ClothModel> sheets(n);
  std::vector<Eigen::MatrixX3d> normal(n);
  for (std::size_t k = 0; k < n; ++k) {
    DressedGarment& g = garments[k];
    sheets[k] = garment_cloth(g, fabrics[k]);
    if (!g.padded) continue;
    face_outwards(sheets[k], g.dressed, body);
    normal[k] = vertex_normals(g.dressed, sheets[k].faces);
  }

  // The outfit as sheets: where each outer shell can start, and what lies over padding.
  std::vector<int> first(1, 0);
  std::vector<int> face_garment;
  for (std::size_t k = 0; k < n; ++k) {
    first.push_back(first.back() + static_cast<int>(garments[k].dressed.rows()));
    face_garment.insert(face_garment.end(), static_cast<std::size_t>(sheets[k].faces.rows()), static_cast<int>(k));
  }
  Eigen::MatrixX3d sheet_x(first.back(), 3);
  Eigen::MatrixX3i sheet_f(face_garment.size(), 3);
  for (std::size_t k = 0, f = 0; k < n; ++k) {
    sheet_x.middleRows(first[k], first[k + 1] - first[k]) = garments[k].dressed;
    sheet_f.middleRows(static_cast<Eigen::Index>(f), sheets[k].faces.rows()) = sheets[k].faces.array() + first[k];
    f += static_cast<std::size_t>(sheets[k].faces.rows());
  }
  std::vector<Eigen::VectorXd> start(n);
  std::vector<std::vector<char>> free(n);  // the padded garments' particles not held where they settled
  for (std::size_t k = 0; k < n; ++k) {
    const DressedGarment& g = garments[k];
    if (!g.padded) continue;
    const Eigen::Index nv = g.dressed.rows();
    start[k] = 0.5 * clearance(sheet_x, sheet_f, first[k], normal[k], Eigen::VectorXd::Constant(nv, 2.0 * g.padding.thickness));
    // A vertex lies over padding when, looking into the body, it meets a padded sheet first: that
    // padding pushes it out as it grows. The rest of a padded garment's inner shell stays where
    // it settled: the padding grows over it.
    Eigen::VectorXd depth(nv);
    Eigen::Vector3d unused;
    for (Eigen::Index v = 0; v < nv; ++v) depth(v) = std::clamp(body.distance(g.dressed.row(v).transpose(), &unused), 0.0, 0.1);
    std::vector<int> hit;
    clearance(sheet_x, sheet_f, first[k], -normal[k], depth, &hit);
    free[k].assign(static_cast<std::size_t>(nv), 0);
    for (std::size_t v = 0; v < hit.size(); ++v)
      free[k][v] = hit[v] >= 0 && garments[static_cast<std::size_t>(face_garment[static_cast<std::size_t>(hit[v])])].padded;
  }

  auto outfit = [&](std::vector<int>& offsets) {
    std::vector<ClothModel> models;
    for (std::size_t k = 0; k < n; ++k) {
      const DressedGarment& g = garments[k];
      models.push_back(g.padded ? padded_model(sheets[k], g.dressed, normal[k], {g.padding.thickness, g.padding.min, g.padding.max},
                                               start[k], options.strain_limit)
                                : sheets[k]);
    }
    offsets = garment_offsets(models);
    return models.size() == 1 ? models[0] : stack_layers(models, separation);
  };
  auto positions = [&](const std::vector<int>& offsets) {
    Eigen::MatrixX3d x(offsets.back(), 3);
    for (std::size_t k = 0; k < n; ++k) {
      const DressedGarment& g = garments[k];
      const Eigen::Index nv = g.dressed.rows();
      x.middleRows(offsets[k], nv) = g.dressed;
      if (g.padded) x.middleRows(offsets[k] + nv, nv) = g.dressed + start[k].asDiagonal() * normal[k];
    }
    return x;
  };

  // Starts are smoothed; where one still crosses something (an edge of the outer shell passing
  // another sheet beside the ray), it is halved and the starts smoothed again, round by round.
  std::vector<std::vector<std::vector<int>>> near(n);
  for (std::size_t k = 0; k < n; ++k)
    if (garments[k].padded) near[k] = vertex_neighbours(sheets[k].faces, static_cast<int>(garments[k].dressed.rows()));
  auto smooth = [&] {
    for (std::size_t k = 0; k < n; ++k) {
      if (!garments[k].padded) continue;
      const Eigen::MatrixX3d& x = garments[k].dressed;
      for (bool changed = true; changed;) {
        changed = false;
        for (Eigen::Index v = 0; v < x.rows(); ++v)
          for (int u : near[k][static_cast<std::size_t>(v)]) {
            const double bound = start[k](u) + kStartSlope * (x.row(u) - x.row(v)).norm();
            if (bound < start[k](v)) start[k](v) = bound, changed = true;
          }
      }
    }
  };
  smooth();
  std::vector<int> offsets;
  ClothModel model = outfit(offsets);
  for (int round = 0; round < kStartRounds; ++round) {
    const std::vector<int> crossing = crossing_vertices(positions(offsets), model.faces);
    bool moved = false;
    for (std::size_t k = 0; k < n; ++k) {
      if (!garments[k].padded) continue;
      const int nv = static_cast<int>(garments[k].dressed.rows()), outer = offsets[k] + nv;
      for (auto it = std::lower_bound(crossing.begin(), crossing.end(), outer); it != crossing.end() && *it < outer + nv; ++it) {
        double& s = start[k](*it - outer);
        moved = moved || s > 0.0;
        s = s < kStartFloor ? 0.0 : 0.5 * s;
      }
    }
    if (!moved) break;
    smooth();
  }
  model = outfit(offsets);
  const Eigen::MatrixX3d x0 = positions(offsets);
  for (std::size_t k = 0; k < n; ++k) {
    DressedGarment& g = garments[k];
    if (!g.padded) continue;
    const int nv = static_cast<int>(g.dressed.rows());
    g.padding.crossings_start = count_intersections(x0, faces_within(model.faces, offsets[k], offsets[k] + 2 * nv));
    g.padding.start_at_full = static_cast<int>((start[k].array() >= g.padding.thickness).count());
  }

  // The padding grows to its thickness and the outfit settles, until rest.
  std::vector<int> held;
  for (std::size_t k = 0; k < n; ++k) {
    for (int v : belt[k]) held.push_back(offsets[k] + v);
    if (garments[k].padded)
      for (std::size_t v = 0; v < free[k].size(); ++v)
        if (!free[k][v]) held.push_back(offsets[k] + static_cast<int>(v));
  }
  std::sort(held.begin(), held.end());
  held.erase(std::unique(held.begin(), held.end()), held.end());
  RunOptions r;
  r.duration = seconds;
  r.max_steps = max_steps;
  // Steps held below 1/256 of the full one (the length limits, the body and what lies over the
  // padding not all holding) count as stalled: the padding is kept where it got to, rather than
  // settled for hours of such steps.
  r.stall.factor = std::max(r.stall.factor, options.dt / 256.0 / options.dt_min);
  PaddingRun out;
  ClothSimulator sim(model, options);
  sim.set_state(x0, Eigen::MatrixX3d::Zero(x0.rows(), 3));
  if (!held.empty()) sim.set_pinned(held);
  out.run = run(sim, r, {}, [&](const StepResult&) {
    if (on_settle) on_settle(sim.time(), seconds);
  });
  out.simulated = sim.time();
  const Eigen::MatrixX3d& x = sim.positions();

  for (std::size_t k = 0; k < n; ++k) {
    DressedGarment& g = garments[k];
    const Eigen::Index nv = g.dressed.rows();
    g.dressed = x.middleRows(offsets[k], nv);
    if (!g.padded) continue;
    g.dressed_outer = x.middleRows(offsets[k] + nv, nv);
    std::vector<double> gap;
    for (Eigen::Index v = 0; v < nv; ++v)
      if (normal[k].row(v).squaredNorm() > 0.0) gap.push_back((g.dressed_outer.row(v) - g.dressed.row(v)).norm());
    std::sort(gap.begin(), gap.end());
    PaddingFigures& p = g.padding;
    if (!gap.empty()) {
      p.gap_min = gap.front(), p.gap_p5 = gap[gap.size() / 20], p.gap_median = gap[gap.size() / 2], p.gap_max = gap.back();
      p.below_min = static_cast<int>(std::lower_bound(gap.begin(), gap.end(), p.min) - gap.begin());
    }
    p.crossings = count_intersections(x, faces_within(model.faces, offsets[k], offsets[k] + 2 * static_cast<int>(nv)));
  }
  return out;
}

}  // namespace dresskit::dressing::detail
