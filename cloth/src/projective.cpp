// Projective dynamics (Bouaziz et al. 2014, "Projective Dynamics: Fusing Constraint Projections for
// Fast Simulation"; for mass-spring systems Liu et al. 2013, "Fast Simulation of Mass-Spring
// Systems"): backward Euler's incremental potential with every spring as the quadratic
// w/2 |xj − xi − d|². Global step: one constant, prefactored linear system for the three coordinate
// columns. Local step: d along the spring with the length ℓ = L − t(L)/w, so that the quadratic's
// force w (L − ℓ) equals the spring law's tension t(L) at the current length (the nonlinear law,
// with dynamic stiffness, enters through the targets while the matrix stays constant). A converged
// step is therefore backward Euler with the full law. w is the law's tangent stiffness just below
// the knee: the fixed-point iteration contracts while the local stiffness stays within about twice
// w (with w = k_knee the error bench's error grew with the iteration count). Spring damping is not
// modelled (as in the Newton integrator).
//
// BDF2 (options.projective.time_scheme): x_{n+1} = x̂ + h' v_{n+1} and v_{n+1} = v̂ + h' M⁻¹ f(x_{n+1}) with
// h' = 2h/3, x̂ = (4 x_n − x_{n−1})/3, v̂ = (4 v_n − v_{n−1})/3 — the same minimisation as backward
// Euler with the inertia target x̂ + h' v̂ and the step h' (air damping acts on (x − x̂)/h'). The
// first step (and the first after a change of step size or set_state) is backward Euler: BDF2
// started from x_{n−1} = x_n − h v_n, v_{n−1} = v_n stays first order for the whole run (the
// start's O(h) velocity error; order 1.2–1.3 on the oscillator test), and a Taylor start with the
// current acceleration, second order, is an explicit step in disguise that blows up on very stiff
// springs.
//
// Speed (docs/results.md, bench_cloth_error): the global step's three triangular solves dominate;
// they run on an interleaved copy of the factor (interleaved_cholesky.h), by default in single
// precision for the change of the iterate against a double-precision residual. The local step reads
// flat arrays. Collisions (options.projective.collisions): after every global step particles inside
// a collider's margin are pushed out to it along the normal, so the springs settle around the
// contacts within the step; the contacts of the last pass then lose their inward speed and get
// friction (as collide()).
#include <algorithm>
#include <array>
#include <cmath>
#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define DRESSKIT_SSE2 1
#endif

#include "dresskit/mesh/names.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/simulator.h"
#include "dresskit/cloth/stiffness_law.h"
#include "dresskit/mesh/errors.h"
#include "interleaved_cholesky.h"
#include "projective_internal.h"
#include "simulator_internal.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {
using namespace pd;

const NameTable<TimeScheme> kTimeSchemes = {{"backward_euler", TimeScheme::backward_euler}, {"bdf2", TimeScheme::bdf2},
    {"midpoint", TimeScheme::midpoint}, {"tr_bdf2", TimeScheme::tr_bdf2}};
TimeScheme parse_time_scheme(const std::string& text) { return parse_name(text, kTimeSchemes, "time_scheme"); }
std::string to_string(TimeScheme scheme) { return name_of(scheme, kTimeSchemes); }

// The factorisation for the step h in the matrix: the current one, one kept from a recent step
// size (BDF2's backward Euler start-up, adaptive steps dt / 2^k), or a new one.
void ProjectiveDynamics::prepare(const ClothSimulator& sim, double h, const std::vector<double>* weights) {
  const int n = static_cast<int>(sim.x_.rows());
  const SpringSet& s = sim.model_.springs;
  const double c = sim.options_.air_damping;
  if (current_ && current_->h != h) {
    for (auto it = cache_.begin(); it != cache_.end(); ++it) {
      if ((*it)->h != h || (*it)->pinned != sim.pinned_) continue;
      std::shared_ptr<ProjectiveFactor> found = *it;
      cache_.erase(it);
      cache_.insert(cache_.begin(), current_);
      current_ = found;
      break;
    }
  }
  if (!weights && current_ && current_->h == h && current_->pinned == sim.pinned_ &&
      current_->single_precision == sim.options_.projective.single_precision)
    return;
  // New adaptive weights for the same step and pins: the matrices' values change in place through
  // each spring's entries, and the factor keeps its ordering and symbolic analysis (building the
  // matrices anew from triplets took as long as the numeric factorisation, ~4.5 ms on the error
  // bench's cloth).
  if (weights && current_ && current_->adaptive && current_->ok && current_->h == h &&
      current_->pinned == sim.pinned_ &&
      current_->single_precision == sim.options_.projective.single_precision &&
      current_->same_layout) {
    ProjectiveFactor& P = *current_;
    double* a = P.Acol.valuePtr();
    double* b = P.to_pinned.valuePtr();
    for (int k = 0; k < s.size(); ++k) {
      LocalSpring& q = P.springs[static_cast<std::size_t>(k)];
      const double dw = (*weights)[static_cast<std::size_t>(k)] - q.w;
      if (dw == 0.0) continue;
      const std::array<int, 4>& ao = P.a_offset[static_cast<std::size_t>(k)];
      const std::array<int, 4>& bo = P.b_offset[static_cast<std::size_t>(k)];
      for (int e = 0; e < 4; ++e) {
        const double sign = e < 2 ? 1.0 : -1.0;
        if (ao[e] >= 0) a[ao[e]] += sign * dw;
        if (bo[e] >= 0) b[bo[e]] += sign * dw;
      }
      q.w += dw;
      if (q.lagged_w > 0.0) q.lagged_w = q.w;
    }
    std::copy(a, a + P.Acol.nonZeros(), P.A.valuePtr());  // symmetric: the same arrays
    P.stretch.clear(), P.bend.clear();
    for (const LocalSpring& q : P.springs) (q.lagged_w > 0.0 ? P.bend : P.stretch).push_back(q);
    P.worst = 0.0;
    P.ok = P.single_precision ? P.single.refactor(P.Acol) : P.full.refactor(P.Acol);
    return;
  }
  // Adaptive weights carry over to a new factorisation (a new step size or pin set).
  std::vector<double> kept;
  if (!weights && current_ && current_->adaptive) {
    for (const LocalSpring& q : current_->springs) kept.push_back(q.w);
    weights = &kept;
  }
  auto p = std::make_shared<ProjectiveFactor>();
  p->h = h;
  p->pinned = sim.pinned_;
  p->single_precision = sim.options_.projective.single_precision;
  p->adaptive = weights != nullptr;
  p->inertia = sim.model_.mass * (1.0 / (h * h) + c / h);
  std::vector<Eigen::Triplet<double>> a, b;
  a.reserve(static_cast<std::size_t>(4 * s.size() + n));
  for (int v = 0; v < n; ++v) a.emplace_back(v, v, sim.pinned_[v] ? 1.0 : p->inertia[v]);
  auto couple = [&](int row, int col, double value) {
    if (sim.pinned_[row]) return;
    (sim.pinned_[col] ? b : a).emplace_back(row, col, value);
  };
  p->springs.resize(static_cast<std::size_t>(s.size()));
  for (int k = 0; k < s.size(); ++k) {
    const int i = s.i[k], j = s.j[k];
    const double w = weights ? (*weights)[k] : projective_weight(s.k_rest[k], s.k_knee[k]);
    const bool lagged =
        s.type[k] == SpringType::bending;  // off the matrix: see LocalSpring::lagged_w
    p->springs[k] = local_spring(s, k, w);
    couple(i, i, w);
    couple(j, j, w);
    if (lagged) continue;
    couple(i, j, -w);
    couple(j, i, -w);
  }
  // A stitch is the quadratic ½ k |Σ w x − d|² with d its soft-threshold target (seams.h).
  int idx[3];
  double sw[3];
  for (int k = 0; k < sim.model_.seams.size(); ++k) {
    seam_weights(sim.model_.seams, k, idx, sw);
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) couple(idx[p], idx[q], sim.model_.seams.stiffness[k] * sw[p] * sw[q]);
  }
  for (const LocalSpring& q : p->springs) (q.lagged_w > 0.0 ? p->bend : p->stretch).push_back(q);
  for (int v = 0; v < n; ++v)
    if (sim.pinned_[v]) p->pinned_list.push_back(v);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(a.begin(), a.end());
  p->A = A;
  p->to_pinned.resize(n, n);
  p->to_pinned.setFromTriplets(b.begin(), b.end());
  if (p->adaptive) {  // where each spring's weight enters the matrices (for new weights)
    p->Acol = A;
    p->same_layout =
        std::equal(A.outerIndexPtr(), A.outerIndexPtr() + n + 1, p->A.outerIndexPtr()) &&
        std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), p->A.innerIndexPtr());
    auto offset = [](const Eigen::SparseMatrix<double>& M, int row, int col) {
      const int* inner = M.innerIndexPtr();
      const int *first = inner + M.outerIndexPtr()[col], *last = inner + M.outerIndexPtr()[col + 1];
      const int* at = std::lower_bound(first, last, row);
      return at != last && *at == row ? static_cast<int>(at - inner) : -1;
    };
    p->a_offset.resize(static_cast<std::size_t>(s.size()));
    p->b_offset.resize(static_cast<std::size_t>(s.size()));
    for (int k = 0; k < s.size(); ++k) {
      const int i = s.i[k], j = s.j[k];
      const bool lagged = s.type[k] == SpringType::bending;
      const int rows[4] = {i, j, i, j}, cols[4] = {i, j, j, i};
      for (int e = 0; e < 4; ++e) {
        const bool in = !sim.pinned_[rows[e]] && !(lagged && e >= 2);
        const bool to_pin = in && sim.pinned_[cols[e]];
        p->a_offset[static_cast<std::size_t>(k)][e] =
            in && !to_pin ? offset(A, rows[e], cols[e]) : -1;
        p->b_offset[static_cast<std::size_t>(k)][e] =
            to_pin ? offset(p->to_pinned, rows[e], cols[e]) : -1;
      }
    }
  }
  // Adaptive weights keep no other step sizes' factorisations: a refactorisation for new weights (or a new step) keeps the
  // old factor's ordering and symbolic analysis (same sparsity while the pins are the same).
  const bool reuse = p->adaptive && current_ && current_->ok &&
                     current_->pinned == sim.pinned_ &&
                     current_->single_precision == p->single_precision;
  if (reuse) {
    p->single = std::move(current_->single);
    p->full = std::move(current_->full);
  }
  p->ok = p->single_precision ? (reuse ? p->single.refactor(A) : p->single.compute(A))
                              : (reuse ? p->full.refactor(A) : p->full.compute(A));
  if (p->adaptive) {
    cache_.clear();
  } else if (current_ && current_->h != h) {
    cache_.insert(cache_.begin(), current_);
    if (cache_.size() > 4) cache_.pop_back();
  }
  current_ = p;
}

// One minimisation of the incremental potential
//   Σ m/(2h²)|x − target|² + Σ c m/(2h)|x − air_base − h wind|² + E(x) − Σ m g·x
// (pinned particles at x0) by local/global iterations from X; h is the current factorisation's.
// Fills the contacts of the last collision pass (projective_collisions) and returns the
// iterations taken.
int ProjectiveDynamics::solve(ClothSimulator& sim, const Eigen::MatrixX3d& target,
                              const Eigen::MatrixX3d& air_base, const Eigen::Vector3d& wind,
                              const Eigen::MatrixX3d& x0, RowX3& X, ClothSimulator::Contacts& contacts) {
  const ProjectiveFactor& P = *current_;
  const double h = P.h, c = sim.options_.air_damping;
  const int n = static_cast<int>(sim.x_.rows());
  // Single precision solves for the change δ of the iterate from the residual b − A X; without
  // stitches the residual is formed in the local step itself (the springs' w (d − e)), so the
  // product with A is not needed (it was 0.07 of the ~0.9 ms an iteration took).
  const bool fused = P.single_precision && sim.model_.seams.size() == 0;
  RowX3& fixed = P.fixed;
  fixed.resize(n, 3);
  {
    double* F = fixed.data();
    const double* T = target.data();
    const double* B = air_base.data();
    for (int d = 0; d < 3; ++d) {
      const double air = h * wind[d], g = sim.options_.gravity[d];
      for (int v = 0; v < n; ++v) {
        const double m = sim.model_.mass(v);
        F[3 * v + d] = (m / (h * h)) * T[v + d * n] + (c * m / h) * (B[v + d * n] + air) + m * g;
      }
    }
    // Pinned particles stay where they are: their couplings move to the right-hand side (in the
    // fused residual below they come with the springs' terms).
    if (!fused)
      for (int col = 0; col < P.to_pinned.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(P.to_pinned, col); it; ++it)
          for (int d = 0; d < 3; ++d) F[3 * it.row() + d] -= it.value() * x0(col, d);
  }
  for (int v : P.pinned_list) fixed.row(v) = x0.row(v), X.row(v) = x0.row(v);

  if (sim.options_.projective.lbfgs_history > 0) return lbfgs(sim, target, air_base, wind, x0, X);
  RowX3 &rhs = P.rhs, &previous = P.previous;
  // Contacts inside the iterations (projective_collisions). A particle in contact carries a normal
  // force f n in the global step's right-hand side. After each global step its penetration p below
  // the margin raises f by κ p and its gap g above the margin lowers f by κ g (never below 0), and
  // the particle is pushed out to the margin. κ is the particle's inertia term m/h² (+ air): the
  // force that moves it by one metre when its neighbours move with it, as a whole patch resting on
  // a collider does. (Its row's diagonal in the global matrix, springs included, moves a lone
  // particle but overshoots a patch: the sphere scene's cloth was thrown 9 m up.) The forces are
  // kept from step to step: a cloth at rest on a collider starts every step with the force that
  // holds it, so the global step no longer pulls the supported particles into the collider for the
  // pass after the step to push them back out (on the cloth-onto-sphere scene at 1/60 s that had
  // sunk the top of the cloth 1.8 cm each step, and the push back stretched the strain-limited
  // springs around the sphere's top by 6 %).
  const bool in_contact = sim.options_.projective.collisions && !sim.options_.colliders.empty();
  ClothSimulator::ContactForces& cf = sim.contact_forces_;
  if (in_contact && cf.force.size() != static_cast<std::size_t>(n)) {
    cf.force.assign(static_cast<std::size_t>(n), 0.0);
    cf.collider.assign(static_cast<std::size_t>(n), -1);
    cf.normal.assign(static_cast<std::size_t>(n), Eigen::Vector3d::Zero());
  }
  auto add_contact_forces = [&](double* R) {
    for (int v = 0; v < n; ++v) {
      const double f = cf.force[v];
      if (f == 0.0) continue;
      const Eigen::Vector3d& nv = cf.normal[v];
      R[3 * v] += f * nv[0], R[3 * v + 1] += f * nv[1], R[3 * v + 2] += f * nv[2];
    }
  };
  auto contact_pass = [&](RowX3& Xc, ClothSimulator::Contacts& found) {
    found.clear();
    const int colliders = static_cast<int>(sim.options_.colliders.size());
    for (int v = 0; v < n; ++v) {
      if (sim.pinned_[v]) continue;
      // A particle that started the step inside a collider leaves it at a bounded speed.
      const double margin = sim.exit_margin(v, sim.options_.collision_margin + sim.model_.layer_offset[sim.model_.layer[v]]);
      const Eigen::Vector3d p = Xc.row(v).transpose();
      double& f = cf.force[v];
      // Far from every collider by the last collider pass's lookups, and carrying no force: no
      // contact, no lookup (the lookups were a quarter of the head-drop scene's time).
      if (f == 0.0) {
        bool far = true;
        for (int ci = 0; ci < colliders && far; ++ci) far = sim.distance_lower_bound(v, ci, p) > margin;
        if (far) {
          cf.collider[v] = -1;
          continue;
        }
      }
      int nearest = -1;
      double gap = HUGE_VAL;
      Eigen::Vector3d normal;
      for (int ci = 0; ci < colliders; ++ci) {
        Eigen::Vector3d nc;
        const double g = sim.options_.colliders[ci].distance(p, &nc, sim.lookup_cell(v, ci)) - margin;
        if (g < gap) gap = g, nearest = ci, normal = nc;
      }
      if (nearest != cf.collider[v]) f = 0.0;
      if (gap < 0.0) {
        f += P.inertia[v] * -gap;
        Xc.row(v) -= gap * normal.transpose();
      } else if (f > 0.0) {
        f = std::max(0.0, f - P.inertia[v] * gap);
      }
      cf.collider[v] = f > 0.0 ? nearest : -1;
      cf.normal[v] = normal;
      if (f > 0.0 || gap < 0.0) found.add(v, nearest, normal, std::max(0.0, -gap));
    }
  };
  const double beyond = sim.options_.dynamic_stiffness ? 1.0 + sim.options_.strain_limit : HUGE_VAL;
  const double* rest = sim.model_.rest_positions.data();
  int iterations = 0;
  // The force left unbalanced at the start of the last iteration: the largest row of
  // b − A X over free particles [N] (the potential's gradient; free in the residual forms below).
  auto unbalanced = [&](const double* R) {
    double worst = 0.0;
    for (int v = 0; v < n; ++v)
      if (!sim.pinned_[v]) worst = std::max(worst, R[3 * v] * R[3 * v] + R[3 * v + 1] * R[3 * v + 1] + R[3 * v + 2] * R[3 * v + 2]);
    return std::sqrt(worst);
  };
  force_end_ = -1.0;
  for (int it = 0; it < sim.options_.projective.iterations && fused; ++it) {
    double* R = rhs.data();
    const double* x = X.data();
    const double* F = fixed.data();
    rhs.resize(n, 3);
    R = rhs.data();
    for (int v = 0; v < n; ++v) {
      const double a = P.inertia[v];
      R[3 * v] = F[3 * v] - a * x[3 * v];
      R[3 * v + 1] = F[3 * v + 1] - a * x[3 * v + 1];
      R[3 * v + 2] = F[3 * v + 2] - a * x[3 * v + 2];
    }
    if (it == 0 && P.adaptive)
      P.worst = std::max(P.worst, local_step<false, true, true>(P.stretch, x, rest, n, beyond, R));
    else
      local_step<false, false, true>(P.stretch, x, rest, n, beyond, R);
    local_step<true, false, true>(P.bend, x, rest, n, beyond, R);
    if (in_contact) add_contact_forces(R);
    for (int v : P.pinned_list) R[3 * v] = R[3 * v + 1] = R[3 * v + 2] = 0.0;
    force_end_ = unbalanced(R);
    previous = X;
    P.single.solve_in_place(R);
    X += rhs;
    if (in_contact) contact_pass(X, contacts);
    const double moved2 = largest_move2(X.data(), previous.data(), n);
    iterations = it + 1;
    if (std::sqrt(moved2) < sim.options_.iteration_tolerance) break;
  }
  for (int it = 0; it < sim.options_.projective.iterations && !fused; ++it) {
    rhs = fixed;
    double* R = rhs.data();
    const double* x = X.data();
    if (it == 0 && P.adaptive)  // how far the start of the iterations has outgrown the weights
      P.worst = std::max(P.worst, local_step<false, true>(P.stretch, x, rest, n, beyond, R));
    else
      local_step<false>(P.stretch, x, rest, n, beyond, R);  // each spring's target
    local_step<true>(P.bend, x, rest, n, beyond, R);
    // Stitches: k d spread by their weights (d: the soft-threshold target of the current gap).
    int idx[3];
    double sw[3];
    for (int k = 0; k < sim.model_.seams.size(); ++k) {
      seam_weights(sim.model_.seams, k, idx, sw);
      const Eigen::Vector3d gap =
          (sw[0] * X.row(idx[0]) + sw[1] * X.row(idx[1]) + sw[2] * X.row(idx[2])).transpose();
      const Eigen::RowVector3d d =
          sim.model_.seams.stiffness[k] * stitch_target(sim.model_.seams, k, gap).transpose();
      for (int p = 0; p < 3; ++p) rhs.row(idx[p]) += sw[p] * d;
    }
    if (in_contact) add_contact_forces(R);
    for (int v : P.pinned_list)
      R[3 * v] = x[3 * v], R[3 * v + 1] = x[3 * v + 1], R[3 * v + 2] = x[3 * v + 2];
    previous = X;
    if (P.single_precision) {  // global step as a correction: A δ = rhs − A X
      const int* outer = P.A.outerIndexPtr();
      const int* inner = P.A.innerIndexPtr();
      const double* value = P.A.valuePtr();
      for (int row = 0; row < n; ++row) {
        double r0 = R[3 * row], r1 = R[3 * row + 1], r2 = R[3 * row + 2];
        for (int q = outer[row]; q < outer[row + 1]; ++q) {
          const double* xc = x + 3 * inner[q];
          r0 -= value[q] * xc[0];
          r1 -= value[q] * xc[1];
          r2 -= value[q] * xc[2];
        }
        R[3 * row] = r0, R[3 * row + 1] = r1, R[3 * row + 2] = r2;
      }
      force_end_ = unbalanced(R);
      P.single.solve_in_place(R);
      X += rhs;
    } else {
      P.full.solve_in_place(R);
      X = rhs;
    }
    if (in_contact) contact_pass(X, contacts);
    const double moved2 = largest_move2(X.data(), previous.data(), n);
    const double moved = std::sqrt(moved2);
    iterations = it + 1;
    if (moved < sim.options_.iteration_tolerance) break;
  }
  return iterations;
}

void ProjectiveDynamics::step(ClothSimulator& sim, StepResult& r) {
  const double dt = sim.dt_;
  const int n = static_cast<int>(sim.x_.rows());
  const TimeScheme scheme = sim.options_.projective.time_scheme;
  // BDF2's history: a completed step since the last try makes its start the previous state.
  if (history_.t_start != sim.time_) {
    if (history_.t_start >= 0.0) {
      history_.x_prev = history_.x_start;
      history_.v_prev = history_.v_start;
      history_.t_prev = history_.t_start;
    }
    history_.x_start = sim.x_;
    history_.v_start = sim.v_;
    history_.t_start = sim.time_;
  }
  // Without a previous state a step apart (the first step, after a change of step or set_state) the
  // step is backward Euler: its O(h²) error enters once, so the run stays second order.
  const bool bdf2 = scheme == TimeScheme::bdf2 && history_.t_prev >= 0.0 &&
                    std::abs(sim.time_ - history_.t_prev - dt) <= 1e-9 * dt;
  // The step in the matrix: BDF2 2h/3; the midpoint rule's half step h/2 (its midpoint y is a
  // backward Euler step of h/2 from x_n: x_{n+1} = 2y − x_n); TR-BDF2's two stages share one,
  // γh/2 = (1 − γ) h/(2 − γ) = (1 − 1/√2) h.
  const double tr_h = (1.0 - 1.0 / std::sqrt(2.0)) * dt;
  const double h = bdf2                             ? 2.0 * dt / 3.0
                   : scheme == TimeScheme::midpoint ? 0.5 * dt
                   : scheme == TimeScheme::tr_bdf2  ? tr_h
                                                    : dt;
  if (sim.options_.projective.adaptive_weights) {
    // Each stretch spring's weight is the law's tangent stiffness a little beyond its strain (the
    // iterations contract while the spring's stiffness stays below twice its weight): far below
    // the one weight for all (the tangent just below the knee), which is 10–100 times the
    // stiffness of a lightly stretched cloth and makes its iterations crawl. A spring whose
    // stiffness passes 1.5 × its weight raises all weights to their springs' current strains
    // (never lowering one) and the matrix is factorised again. Measured on the error bench:
    // headroom 0.05 and trigger 1.5 (5 refactorisations in 1 s); weights at the tangent itself
    // (headroom 0) or below it (0.7 × tangent) blew up with few iterations.
    const double headroom = 0.05, trigger = 1.5;
    const SpringSet& s = sim.model_.springs;
    const double* x = sim.x_.data();
    auto strain_of = [&](const LocalSpring& q) {
      const double dx = x[q.j] - x[q.i], dy = x[q.j + n] - x[q.i + n],
                   dz = x[q.j + 2 * n] - x[q.i + 2 * n];
      return std::sqrt(dx * dx + dy * dy + dz * dz) * q.inv_L0 - 1.0;
    };
    const bool have = current_ && current_->adaptive;
    // Has a stretch spring stiffened past its weight (checked by the first local step of every
    // minimisation, at the point the iterations start from)?
    const bool raise = !have || current_->worst > trigger;
    std::vector<double> weights;
    if (raise) {
      weights.resize(static_cast<std::size_t>(s.size()));
      for (int k = 0; k < s.size(); ++k) {
        const LocalSpring q = have ? current_->springs[k] : local_spring(s, k, 0.0);
        if (s.type[k] == SpringType::bending) {  // linear: its weight is its stiffness
          weights[k] = s.k_rest[k];
          continue;
        }
        const double wanted = law_tangent(q, strain_of(q) + headroom);
        weights[k] = have ? std::max(q.w, wanted) : wanted;
      }
    }
    prepare(sim, h, raise ? &weights : nullptr);
  } else {
    prepare(sim, h);
  }
  if (!current_->ok) {
    r.ok = false;
    r.failure = "projective dynamics: the global matrix could not be factorised";
    return;
  }
  const ProjectiveFactor& P = *current_;
  P.x0 = sim.x_, P.v0 = sim.v_;
  const Eigen::MatrixX3d &x0 = P.x0, &v0 = P.v0;
  RowX3& X = P.X;
  ClothSimulator::Contacts contacts;
  // x̂ and v̂ of the last stage: x_{n+1} = x̂ + h v_{n+1}
  Eigen::MatrixX3d &base = P.base, &vbase = P.vbase, &target = P.target, &y = P.y;
  base = x0, vbase = v0;
  if (scheme == TimeScheme::midpoint || scheme == TimeScheme::tr_bdf2) {
    // Implicit midpoint over the first stage (the whole step, or γ h of TR-BDF2): y minimises
    // backward Euler's potential of step h from (x_n, v_n); the stage ends at 2y − x_n with the
    // velocity 2 (y − x_n)/h − v_n.
    const double stage = scheme == TimeScheme::midpoint ? dt : 2.0 * h;
    target = x0 + h * v0;
    X = target;
    r.newton_iterations +=
        solve(sim, target, x0, sim.wind_at(sim.time_ + 0.5 * stage), x0, X, contacts);
    y = X;
    base = 2.0 * y - x0;              // x at the stage's end
    vbase = 2.0 / h * (y - x0) - v0;  // v there
    if (scheme == TimeScheme::midpoint) {
      sim.x_ = base;
      sim.v_ = vbase;
    } else {
      // BDF2 over the rest of the step from (x_n, x_γ): x̂ = a x_γ − b x_n, a = 1/(γ(2 − γ)),
      // b = (1 − γ)²/(γ(2 − γ)), the same for v.
      const double gamma = 2.0 - std::sqrt(2.0);
      const double a = 1.0 / (gamma * (2.0 - gamma)), b = (1.0 - gamma) * (1.0 - gamma) * a;
      base = a * base - b * x0;
      vbase = a * vbase - b * v0;
    }
  } else if (bdf2) {
    base = (4.0 * x0 - history_.x_prev) / 3.0;
    vbase = (4.0 * v0 - history_.v_prev) / 3.0;
  }
  if (scheme != TimeScheme::midpoint) {
    target = base + h * vbase;  // the inertia target
    X = target;                 // start from it
    const int iterations = solve(sim, target, base, sim.wind_at(sim.time_ + dt), x0, X, contacts);
    r.newton_iterations += iterations;
    const double weight = sim.model_.mass.maxCoeff() * sim.options_.gravity.norm();
    if (force_end_ >= 0.0 && weight > 0.0) {
      r.unbalanced_end = force_end_ / weight;
      r.iterations_ran_out = iterations >= sim.options_.projective.iterations;
    }
    sim.x_ = X;
    sim.v_ = (sim.x_ - base) / h;
  }
  for (int v = 0; v < n; ++v)
    if (sim.pinned_[v]) sim.x_.row(v) = x0.row(v), sim.v_.row(v).setZero();
  // Contacts: no inward speed; static or kinetic friction on the sliding part (as ClothSimulator::collide()). The
  // normal speed the contact removed is the contact force's impulse per mass (h g_n for a particle
  // resting under gravity), the last pass's push over h and any inward speed left.
  for (std::size_t k = 0; k < contacts.particle.size(); ++k) {
    const Collider& col = sim.options_.colliders[contacts.collider[k]];
    const Eigen::Vector3d& nk = contacts.normal[k];
    Eigen::Vector3d vel = sim.v_.row(contacts.particle[k]).transpose();
    const double vn = vel.dot(nk), removed = std::max(-vn, 0.0) + contacts.depth[k] / h +
                              sim.contact_forces_.force[contacts.particle[k]] * h / sim.model_.mass(contacts.particle[k]);
    if (vn < 0.0) vel -= vn * nk;
    const Eigen::Vector3d vt = vel - vel.dot(nk) * nk;
    const double speed = vt.norm(),
                 mu_static = col.static_friction < 0.0 ? col.friction : col.static_friction;
    if (speed <= mu_static * removed)
      vel -= vt;
    else
      vel -= (col.friction * removed / speed) * vt;
    sim.v_.row(contacts.particle[k]) = vel.transpose();
  }
}

std::unique_ptr<TimeIntegrator> make_projective() { return std::make_unique<ProjectiveDynamics>(); }

}  // namespace dresskit::cloth
