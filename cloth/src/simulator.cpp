#include "dresskit/cloth/simulator.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <Eigen/Geometry>
#include <cmath>
#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define DRESSKIT_SSE2 1
#endif
#include <cstdio>
#include <limits>
#include <utility>

#include "dresskit/cloth/geometry.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/spring_kernels.h"
#include "dresskit/mesh/errors.h"
#include "cpu_clock.h"
#include "integrator.h"
#include "simulator_internal.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {
using detail::add_spring_blocks;
using detail::row;

namespace {
/// A state strained beyond this many times blow_up_strain has exploded (see try_step).
constexpr double kExplodedFactor = 5.0;

std::unique_ptr<TimeIntegrator> make_integrator(Integrator kind) {
  switch (kind) {
    case Integrator::symplectic_euler: return make_symplectic_euler();
    case Integrator::implicit_euler: return make_implicit_euler();
    case Integrator::newton: return make_newton();
    case Integrator::projective: return make_projective();
  }
  return make_projective();
}
}  // namespace

ClothSimulator::~ClothSimulator() = default;
ClothSimulator::ClothSimulator(ClothSimulator&&) noexcept = default;
ClothSimulator& ClothSimulator::operator=(ClothSimulator&&) noexcept = default;

ClothSimulator::ClothSimulator(ClothModel model, SimulationOptions options)
    : model_(std::move(model)), options_(options) {
  check_options(options_);
  integrator_ = make_integrator(options_.integrator);
  x_ = model_.rest_positions;
  v_ = Eigen::MatrixX3d::Zero(x_.rows(), 3);
  if (model_.layer.size() != x_.rows()) model_.layer = Eigen::VectorXi::Zero(x_.rows());
  if (model_.layer_offset.empty()) model_.layer_offset = {0.0};
  model_.layer_min_gap.resize(model_.layer_offset.size(), 0.0);
  // A layer-guard push is at most a tenth of the mean spring length per step: larger jumps strain the
  // springs beyond what the next solve can absorb (measured: full pushes blew the stacked scene up).
  double rest_sum = 0.0;
  for (double L : model_.springs.rest_length) rest_sum += L;
  layer_push_cap_ = 0.1 * rest_sum / std::max(1, model_.springs.size());
  blow_up_length_ = 2.5 * layer_push_cap_;
  // A particle that started inside a collider leaves it at most at this speed [m/s]: 6 mean spring
  // lengths a second, a quarter of the adaptive step's strain jump (0.05) per 1/240 s step, so
  // that halving the step halves the push and a retried step can succeed (a push per step does
  // not shrink with the step: a cloth that started inside a body failed at the smallest step).
  deep_push_speed_ = 60.0 * layer_push_cap_;
  inv_rest_.resize(model_.springs.rest_length.size());
  for (std::size_t k = 0; k < inv_rest_.size(); ++k) inv_rest_[k] = 1.0 / model_.springs.rest_length[k];
  // Each particle's mean structural rest length (the mean over the cloth for one without any): the
  // length scale of the contact step bound.
  {
    const SpringSet& s = model_.springs;
    const int n = static_cast<int>(x_.rows());
    std::vector<int> count(static_cast<std::size_t>(n), 0);
    contact_length_ = Eigen::VectorXd::Zero(n);
    double sum = 0.0;
    int structural = 0;
    for (int k = 0; k < s.size(); ++k) {
      if (s.type[k] != SpringType::structural) continue;
      for (int p : {s.i[k], s.j[k]}) {
        contact_length_[p] += s.rest_length[k];
        ++count[p];
      }
      sum += s.rest_length[k];
      ++structural;
    }
    // A particle of a small detail (sub-millimetre springs of a button or a seam allowance) takes
    // at least a quarter of the cloth's mean: the bound is to keep steps from tearing springs and
    // skipping thin features, which at that length no step does, and the detail's own length would
    // shrink every step near the body to a fraction of the cloth's.
    const double mean = structural ? sum / structural : 0.0;
    for (int p = 0; p < n; ++p)
      contact_length_[p] = std::max(count[p] ? contact_length_[p] / count[p] : mean, 0.25 * mean);
  }
  assert(model_.layer.maxCoeff() < static_cast<int>(model_.layer_offset.size()));
  set_pinned({});
  const int n = static_cast<int>(x_.rows());
  for (int k = 0; k < model_.seams.size(); ++k) {
    for (int p : {model_.seams.a[k], model_.seams.b0[k], model_.seams.b1[k]})
      if (p < 0 || p >= n) throw InputError("seams: particle " + std::to_string(p) + " is out of range");
  }
  sewn_.assign(static_cast<std::size_t>(model_.seams.size()), 0);
  joined_ = seam_representatives(model_.seams, n);
  if (options_.self_collision && model_.faces.rows() > 0)
    self_ = std::make_shared<SelfCollision>(model_.faces, n, joined_, options_.self_collision_options);
  find_contacts();
  find_inside();
}

void ClothSimulator::set_pinned(const std::vector<int>& vertices) {
  pinned_.assign(static_cast<size_t>(x_.rows()), false);
  for (int p : vertices) {
    if (p < 0 || p >= x_.rows()) {
      throw InputError("pins: vertex " + std::to_string(p) + " is out of range (the cloth has " +
                       std::to_string(x_.rows()) + " vertices)");
    }
    pinned_[p] = true;
    v_.row(p).setZero();
  }
  for (int p = 0; p < x_.rows(); ++p)
    if (!(model_.mass(p) > 0.0)) {
      pinned_[p] = true;
      v_.row(p).setZero();
    }
  inverse_mass_ = model_.mass.cwiseInverse();
  for (int p = 0; p < x_.rows(); ++p)
    if (pinned_[p]) inverse_mass_(p) = 0.0;
}

void ClothSimulator::set_pin_motion(const PinMotion& motion) {
  std::vector<int> pins;
  for (int p = 0; p < x_.rows(); ++p)
    if (pinned_[p]) pins.push_back(p);
  pins.insert(pins.end(), motion.particles.begin(), motion.particles.end());
  set_pinned(pins);
  if (!motion.axis.allFinite() || motion.axis.norm() < 1e-12 || !motion.centre.allFinite() ||
      !motion.velocity.allFinite() || !std::isfinite(motion.turns_per_second) || !(motion.until >= 0.0)) {
    throw InputError("pin_motion: axis must be a direction; centre, velocity, rate finite; until ≥ 0");
  }
  pin_motion_ = motion;
  pin_motion_.axis.normalize();
  pin_start_.resize(static_cast<Eigen::Index>(motion.particles.size()), 3);
  for (std::size_t k = 0; k < motion.particles.size(); ++k) pin_start_.row(static_cast<Eigen::Index>(k)) = x_.row(motion.particles[k]);
}

// Driven pins at time t; their velocity is the move over the step.
void ClothSimulator::move_pins(double t) {
  if (pin_motion_.particles.empty()) return;
  const PinMotion& m = pin_motion_;
  const double s = std::min(t, m.until);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.0 * M_PI * m.turns_per_second * s, m.axis).toRotationMatrix();
  for (std::size_t k = 0; k < m.particles.size(); ++k) {
    const int p = m.particles[k];
    const Eigen::Vector3d next = m.centre + R * (pin_start_.row(static_cast<Eigen::Index>(k)).transpose() - m.centre) + s * m.velocity;
    v_.row(p) = (next.transpose() - x_.row(p)) / dt_;
    x_.row(p) = next.transpose();
  }
}

int ClothSimulator::intersections() const { return count_intersections(x_, model_.faces, joined_); }

void ClothSimulator::set_state(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& v) {
  assert(x.rows() == x_.rows() && v.rows() == v_.rows());
  x_ = x;
  v_ = v;
  integrator_->restart();  // BDF2 must not reach back past a state set from outside
  contact_forces_ = ContactForces{};
  find_contacts();
  find_inside();
}

double ClothSimulator::allowed_length(int s) const {
  return options_.dynamic_stiffness ? (1.0 + options_.strain_limit) * model_.springs.rest_length[s] : 0.0;
}

// The hot loop of explicit stepping: raw column arrays, 1 / L0 precomputed and the law inlined
// (fitted_k) instead of spring_force() and a StiffnessLaw per spring. Measured with
// bench_cloth_throughput (docs/results.md); sorting the springs by particle measured slower than the
// model's order. The kernels stay the reference: a test checks this loop against them.
namespace {
/// The loop body for one combination of the switches, so that neither is tested per spring. Two
/// springs at a time in SSE2 registers (x86-64's baseline; elsewhere one at a time): the square
/// roots, divisions and the law's three branches (compressed, on the ramp, beyond the knee,
/// selected by masks) for both in one instruction each, then the six adds per spring as before
/// (1.15 times the scalar loop's throughput, docs/results.md; the arithmetic is the scalar loop's,
/// operation by operation, unless the compiler is allowed to fuse multiplies and adds).
template <bool kDamping, bool kDynamic>
void spring_loop(const SpringSet& s, const std::vector<double>& inv_rest, const Eigen::MatrixX3d& x,
                 const Eigen::MatrixX3d& v, double beyond, double damping, Eigen::MatrixX3d& f) {
  const Eigen::Index n = x.rows();
  const double* X = x.data();
  const double* V = v.data();
  double* F = f.data();
  auto add = [&](int i, int j, double scale, double dx, double dy, double dz) {
    F[i] += scale * dx;
    F[i + n] += scale * dy;
    F[i + 2 * n] += scale * dz;
    F[j] -= scale * dx;
    F[j + n] -= scale * dy;
    F[j + 2 * n] -= scale * dz;
  };
  auto one = [&](int k) {
    const int i = s.i[k], j = s.j[k];
    const double dx = X[j] - X[i], dy = X[j + n] - X[i + n], dz = X[j + 2 * n] - X[i + 2 * n];
    const double L = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (L < 1e-12) return;  // no direction: no force (as spring_force)
    const double L0 = s.rest_length[k], inv_L = 1.0 / L;
    const double e = L * inv_rest[k] - 1.0;
    double t = fitted_k(s.k_rest[k], s.k_knee[k], kKneeStrain, e) * e * L0;
    if (kDynamic && L > beyond * L0) t *= L * inv_rest[k];
    double scale = t * inv_L;
    if (kDamping) {  // −kd ((vi − vj)·u) u along the spring
      const double dv = (V[i] - V[j]) * dx + (V[i + n] - V[j + n]) * dy + (V[i + 2 * n] - V[j + 2 * n]) * dz;
      scale -= damping * s.k_rest[k] * dv * inv_L * inv_L;
    }
    add(i, j, scale, dx, dy, dz);
  };
  int k = 0;
#if defined(DRESSKIT_SSE2)
  const __m128d one_v = _mm_set1_pd(1.0), zero = _mm_setzero_pd(), tiny = _mm_set1_pd(1e-12);
  const double per_strain = 1.0 / kKneeStrain;
  const __m128d per_v = _mm_set1_pd(per_strain), u_scale = _mm_set1_pd(3.0 * per_strain),
                knee_v = _mm_set1_pd(kKneeStrain), three = _mm_set1_pd(3.0),
                ninth = _mm_set1_pd(1.0 / 9.0), two = _mm_set1_pd(2.0), beyond_v = _mm_set1_pd(beyond);
  for (; k + 1 < s.size(); k += 2) {
    const int i0 = s.i[k], j0 = s.j[k], i1 = s.i[k + 1], j1 = s.j[k + 1];
    const __m128d dx = _mm_sub_pd(_mm_set_pd(X[j1], X[j0]), _mm_set_pd(X[i1], X[i0]));
    const __m128d dy = _mm_sub_pd(_mm_set_pd(X[j1 + n], X[j0 + n]), _mm_set_pd(X[i1 + n], X[i0 + n]));
    const __m128d dz =
        _mm_sub_pd(_mm_set_pd(X[j1 + 2 * n], X[j0 + 2 * n]), _mm_set_pd(X[i1 + 2 * n], X[i0 + 2 * n]));
    const __m128d L = _mm_sqrt_pd(
        _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz)));
    if (_mm_movemask_pd(_mm_cmplt_pd(L, tiny))) {  // a spring without direction: one at a time
      one(k);
      one(k + 1);
      continue;
    }
    const __m128d L0 = _mm_loadu_pd(&s.rest_length[k]), inv_r = _mm_loadu_pd(&inv_rest[k]);
    const __m128d k0 = _mm_loadu_pd(&s.k_rest[k]), kk = _mm_loadu_pd(&s.k_knee[k]);
    const __m128d inv_L = _mm_div_pd(one_v, L);
    const __m128d e = _mm_sub_pd(_mm_mul_pd(L, inv_r), one_v);
    // fitted_k's three branches for both lanes, then the one each lane takes.
    const __m128d rise = _mm_max_pd(_mm_sub_pd(kk, k0), zero);
    const __m128d u = _mm_mul_pd(u_scale, e);
    const __m128d k_beyond = _mm_add_pd(
        _mm_add_pd(k0, rise),
        _mm_mul_pd(_mm_mul_pd(_mm_max_pd(_mm_mul_pd(two, rise), _mm_add_pd(k0, rise)), per_v),
                   _mm_sub_pd(e, knee_v)));
    const __m128d seg = _mm_cvtepi32_pd(_mm_cvttpd_epi32(_mm_min_pd(_mm_max_pd(u, zero), three)));
    const __m128d k_ramp = _mm_add_pd(
        k0, _mm_mul_pd(_mm_mul_pd(rise, ninth),
                       _mm_add_pd(_mm_mul_pd(seg, seg),
                                  _mm_mul_pd(_mm_sub_pd(u, seg),
                                             _mm_add_pd(_mm_mul_pd(two, seg), one_v)))));
    const __m128d past = _mm_cmpge_pd(u, three), compressed = _mm_cmple_pd(e, zero);
    __m128d k_law = _mm_or_pd(_mm_and_pd(past, k_beyond), _mm_andnot_pd(past, k_ramp));
    k_law = _mm_or_pd(_mm_and_pd(compressed, k0), _mm_andnot_pd(compressed, k_law));
    __m128d t = _mm_mul_pd(_mm_mul_pd(k_law, e), L0);
    if (kDynamic) {
      const __m128d over = _mm_cmpgt_pd(L, _mm_mul_pd(beyond_v, L0));
      t = _mm_or_pd(_mm_and_pd(over, _mm_mul_pd(t, _mm_mul_pd(L, inv_r))), _mm_andnot_pd(over, t));
    }
    alignas(16) double scale[2], ex[2], ey[2], ez[2], il[2];
    _mm_store_pd(scale, _mm_mul_pd(t, inv_L));
    _mm_store_pd(ex, dx);
    _mm_store_pd(ey, dy);
    _mm_store_pd(ez, dz);
    _mm_store_pd(il, inv_L);
    const int ends[2][2] = {{i0, j0}, {i1, j1}};
    for (int l = 0; l < 2; ++l) {
      const int i = ends[l][0], j = ends[l][1];
      if (kDamping) {
        const double dv = (V[i] - V[j]) * ex[l] + (V[i + n] - V[j + n]) * ey[l] +
                          (V[i + 2 * n] - V[j + 2 * n]) * ez[l];
        scale[l] -= damping * s.k_rest[k + l] * dv * il[l] * il[l];
      }
      add(i, j, scale[l], ex[l], ey[l], ez[l]);
    }
  }
#endif
  for (; k < s.size(); ++k) one(k);
}
}  // namespace

void ClothSimulator::add_spring_forces(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& v,
                                       Eigen::MatrixX3d& f) const {
  const SpringSet& s = model_.springs;
  const double beyond = 1.0 + options_.strain_limit, c = options_.spring_damping;
  const bool damping = c > 0.0, dynamic = options_.dynamic_stiffness;
  if (damping && dynamic) spring_loop<true, true>(s, inv_rest_, x, v, beyond, c, f);
  else if (damping) spring_loop<true, false>(s, inv_rest_, x, v, beyond, c, f);
  else if (dynamic) spring_loop<false, true>(s, inv_rest_, x, v, beyond, c, f);
  else spring_loop<false, false>(s, inv_rest_, x, v, beyond, c, f);
  add_seam_forces(model_.seams, x, f);
}

Eigen::MatrixX3d ClothSimulator::forces() const {
  Eigen::MatrixX3d f;
  forces(f);
  return f;
}

void ClothSimulator::forces(Eigen::MatrixX3d& f) const {
  f.resize(x_.rows(), 3);  // no allocation when f already has the size
  // Gravity and air first, column by column, f = m (g − c (v − wind)) (one pass instead of zeroing
  // and adding), then the springs.
  const Eigen::Vector3d wind = wind_at(time_);
  for (int c = 0; c < 3; ++c) {
    f.col(c).array() = model_.mass.array() *
                       (options_.gravity[c] - options_.air_damping * (v_.col(c).array() - wind[c]));
  }
  add_spring_forces(x_, v_, f);
  add_penalty_forces(f);
  for (int i = 0; i < x_.rows(); ++i)
    if (pinned_[i]) f.row(i).setZero();
}

Eigen::SparseMatrix<double> ClothSimulator::stiffness_matrix(bool clamp_geometric) const {
  const SpringSet& s = model_.springs;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(s.size()) * 36);
  for (int k = 0; k < s.size(); ++k) {
    const Eigen::Matrix3d J = spring_jacobian(s.law(k), s.rest_length[k], row(x_, s.i[k]),
                                              row(x_, s.j[k]), allowed_length(k), clamp_geometric);
    add_spring_blocks(t, s.i[k], s.j[k], -J);
  }
  int idx[3];
  double w[3];
  for (int k = 0; k < model_.seams.size(); ++k) {  // w wᵀ ⊗ (−∂F/∂c)
    seam_weights(model_.seams, k, idx, w);
    Eigen::Matrix3d S;
    stitch_force(model_.seams, k, seam_gap(model_.seams, k, x_), &S);
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) detail::add_block(t, idx[p], idx[q], w[p] * w[q] * S);
  }
  Eigen::SparseMatrix<double> K(3 * x_.rows(), 3 * x_.rows());
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

Eigen::Vector3d ClothSimulator::wind_at(double t) const {
  return options_.wind * (1.0 + options_.gust_amplitude * std::sin(2.0 * M_PI * options_.gust_frequency * t));
}

ClothSimulator::Snapshot ClothSimulator::snapshot() const {
  return {x_, v_, contact_forces_, contacts_, sewn_};
}

void ClothSimulator::restore(const Snapshot& s) {
  x_ = s.x;
  v_ = s.v;
  contact_forces_ = s.contact_forces;
  contacts_ = s.contacts;
  sewn_ = s.sewn;
}

double ClothSimulator::free_strain() const {
  const SpringSet& s = model_.springs;
  double worst = 0.0;
  for (int k = 0; k < s.size(); ++k) {
    if (s.type[k] != SpringType::structural || std::isfinite(start_distance_[s.i[k]]) ||
        std::isfinite(start_distance_[s.j[k]]) || (!held_at_limit_.empty() && held_at_limit_[k]))
      continue;
    // Judged as blow-up judges it (blow_up_stretch): a detail's sub-millimetre spring, stretched
    // by a fraction of a millimetre, would make no step calm.
    worst = std::max(worst, ((x_.row(s.j[k]) - x_.row(s.i[k])).norm() - s.rest_length[k]) /
                                std::max(s.rest_length[k], blow_up_length_));
  }
  return worst;
}

void ClothSimulator::mark_held_springs() {
  held_at_limit_.clear();
  if (!options_.rise_skips_held_springs || !options_.strain_limiting) return;
  // From 0.001 below the limit up: the length limit leaves a spring it corrected at the limit
  // (within strain_limit_tolerance) and the springs around it a little below; the contact passes
  // after it can leave one a little beyond, which the next step's limit takes back as well.
  const double held = options_.strain_limit - 1e-3;
  const SpringSet& s = model_.springs;
  held_at_limit_.assign(static_cast<std::size_t>(s.size()), 0);
  for (int k = 0; k < s.size(); ++k)
    held_at_limit_[k] = s.type[k] == SpringType::structural &&
                        (x_.row(s.j[k]) - x_.row(s.i[k])).norm() * inv_rest_[k] - 1.0 >= held;
}

StepResult ClothSimulator::try_step(double dt) {
  StepResult r;
  r.dt = dt;
  dt_ = dt;
  const Snapshot start = snapshot();
  const Eigen::MatrixX3d& x0 = start.x;
  contact_normal_.setZero(x_.rows(), 3);
  move_pins(time_ + dt);
  using Clock = ThreadCpuClock;
  auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto t = Clock::now();
  integrator_->step(*this, r);
  // Constraints, then collisions: the layer guard and the length limits move particles, the
  // collision projection last keeps every particle outside the colliders.
  r.integrate_seconds = since(t);
  const Eigen::MatrixX3d x_integrated = x_;
  r.integrator_strain = free_strain();
  t = Clock::now();
  // The guard is for runs without cloth–cloth collisions: with them no layer can pass through
  // another, and its pushes made hems wrap around the next garment's (docs/cloth.md, Layers).
  if (r.ok && options_.layer_order_guard && !self_ && model_.layer_offset.size() > 1 &&
      !options_.colliders.empty())
    keep_layer_order(r);
  if (r.ok && (options_.strain_limiting || !model_.springs.limited.empty())) {
    const Eigen::MatrixX3d x_stepped = x_;
    limit_strain(x_stepped, r, true);
  }
  r.constraint_seconds = since(t);
  t = Clock::now();
  if (r.ok && model_.seams.size() > 0) sew(r, true);
  r.seam_seconds = since(t);
  t = Clock::now();
  if (r.ok && !options_.colliders.empty()) {
    const Eigen::MatrixX3d before = x_;
    collide(x0, r);
    // The collider pass stops particles on the body while their neighbours move on, stretching
    // springs past the limit. The limits run once more with the pushed particles sliding along the
    // body (their moves lose the part into it), so the two passes do not undo each other and a
    // spring on a curved part shortens the only way it can, by sliding; then the collider pass for
    // the few neighbours that followed into the margin, so a step ends outside the margin.
    if (options_.strain_limiting && before != x_) {
      const Eigen::MatrixX3d pushed = x_;
      limit_strain(pushed, r, false, true);
      collide(x0, r);
    }
  }
  r.collision_seconds = since(t);
  // Cloth–cloth last: whatever moved the particles before, the paths from x0 gain no intersection.
  // Its corrections can move a particle resting on a collider into the margin, squeeze a double
  // layer below its thickness limit or open a sewn stitch: then the length limits, the sewing and
  // the collider pass run again, and the cloth–cloth pass after them (up to five more rounds; later
  // rounds rarely have anything to do).
  // A step that has exploded (strained beyond kExplodedFactor × blow_up_strain) already fails
  // before the cloth–cloth collisions, which on such a state find millions of candidate pairs
  // (minutes and gigabytes before the check below). Over blow_up_strain alone it is checked after
  // them, which can bring it back: a suit fitted onto another body, 180 % before them at its first
  // step, 15 % after (refused there, its settle would start at 1/30 the step and take 3.2× the
  // steps).
  if (r.ok && self_ && x_.allFinite() && blow_up_stretch(x_) > kExplodedFactor * options_.blow_up_strain) {
    r.ok = false;
    r.failure = blow_up_report(x_integrated, time_ + dt);
  }
  t = Clock::now();
  for (int round = 0; round < 6 && r.ok && self_ && x_.allFinite(); ++round) {
    if (round > 0) {
      const Eigen::MatrixX3d start = x_;
      if (!model_.springs.limited.empty() || options_.strain_limiting) limit_strain(start, r, false);
      const double opened = model_.seams.size() > 0 ? sew(r, false) : 0.0;
      if (!options_.colliders.empty()) collide(x0, r);
      // A round that moved nothing ends them. (Stopping already when it moved nothing by more than
      // 1 % of the thickness saved no time on the sphere or cape scenes and left the 100² cape's
      // strain above the limit more often: 15.0 against 10.7 % at the end.)
      if ((x_ - start).cwiseAbs().maxCoeff() == 0.0 && opened <= 0.1 * options_.seam_tolerance) break;
    }
    const Eigen::MatrixX3d before = x_;
    const SelfCollisionResult s = self_->resolve(x0, x_, inverse_mass_);
    r.self.proximity_pairs += s.proximity_pairs;
    r.self.repulsions += s.repulsions;
    r.self.ccd_collisions += s.ccd_collisions;
    r.self.ccd_passes += s.ccd_passes;
    r.self.zones += s.zones;
    r.self.zone_particles += s.zone_particles;
    r.self.held = r.self.held || s.held;
    r.self.tangled_particles = std::max(r.self.tangled_particles, s.tangled_particles);
    v_ += (x_ - before) / dt_;
    if ((x_ - before).cwiseAbs().maxCoeff() == 0.0) break;
  }
  r.self_collision_seconds = since(t);
  if (r.ok && (!x_.allFinite() || !v_.allFinite())) {
    r.ok = false;
    r.failure = "non-finite state (NaN or infinity)";
  }
  if (r.ok) {
    r.strain = max_strain();
    if (blow_up_stretch(x_) > options_.blow_up_strain) {
      r.ok = false;
      r.failure = blow_up_report(x_integrated, time_ + dt);
    }
  }
  if (!r.ok) restore(start);  // keep the last good state
  else if (!options_.colliders.empty()) start_distance_ = end_distance_;
  return r;
}

// The largest step that keeps contact and explicit stepping under control [s] (adaptive stepping):
//  - contact: a particle within one spring length of a collider moves at most
//    contact_travel × its springs' mean rest length in a step (farther out it may close all but
//    that length of its gap), so a particle stopped by the body leaves its neighbours at most that
//    far behind: one step cannot tear a spring, and a thin feature cannot be skipped;
//  - symplectic Euler: h ω_max ≤ 2 × 0.9 for the stiffest mode, ω_max² bounded (Gershgorin) by
//    max over particles of Σ k (1/m_i + 1/√(m_i m_j)) over its springs at their tangent stiffness
//    a little beyond their strain, plus the colliders' penalty stiffness.
double ClothSimulator::step_bound() {
  double bound = std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(x_.rows());
  if (!options_.colliders.empty() && options_.contact_travel > 0.0) {
    for (int i = 0; i < n; ++i) {
      const double speed = v_.row(i).norm();
      if (pinned_[i] || !(speed > 0.0)) continue;
      const double reach = contact_length_[i];
      double gap = std::numeric_limits<double>::infinity();
      for (int c = 0; c < static_cast<int>(options_.colliders.size()); ++c)
        gap = std::min(gap, distance_lower_bound(i, c, row(x_, i)));
      const double margin = options_.collision_margin + model_.layer_offset[model_.layer[i]];
      const double travel = std::max(options_.contact_travel * reach, gap - margin - reach);
      bound = std::min(bound, travel / speed);
    }
  }
  if (options_.integrator == Integrator::symplectic_euler) {
    const SpringSet& s = model_.springs;
    std::vector<double> omega2(static_cast<std::size_t>(n), 0.0);
    for (int k = 0; k < s.size(); ++k) {
      const int i = s.i[k], j = s.j[k];
      const double e = (x_.row(j) - x_.row(i)).norm() * inv_rest_[k] - 1.0;
      const double stiffness = fitted_tangent(s.k_rest[k], s.k_knee[k], kKneeStrain, std::max(e, 0.0) + 0.05);
      const double mi = model_.mass(i), mj = model_.mass(j);
      if (!(mi > 0.0) || !(mj > 0.0)) continue;
      const double cross = stiffness / std::sqrt(mi * mj);
      omega2[i] += stiffness / mi + cross;
      omega2[j] += stiffness / mj + cross;
    }
    double worst = 0.0;
    for (int i = 0; i < n; ++i) worst = std::max(worst, pinned_[i] ? 0.0 : omega2[i]);
    double penalty = 0.0;
    for (const Collider& c : options_.colliders) penalty = std::max(penalty, c.penalty);
    worst += penalty * std::exp(4.0) / options_.penalty_thickness;
    if (worst > 0.0) {
      const double omega = std::sqrt(worst);
      // Spring damping β k: damping ratio ζ = β ω / 2 shrinks the bound to 2 (√(ζ² + 1) − ζ) / ω.
      const double zeta = 0.5 * options_.spring_damping * omega;
      bound = std::min(bound, 0.9 * 2.0 * (std::sqrt(zeta * zeta + 1.0) - zeta) / omega);
    }
  }
  return bound;
}

StepResult ClothSimulator::step() {
  if (dt_next_ <= 0.0) dt_next_ = options_.dt;
  if (!options_.adaptive) {
    StepResult r = try_step(options_.dt);
    if (r.ok) time_ += r.dt;
    return r;
  }
  // dt_next_ is the controller's step (halved on failure, doubled after calm steps); a step takes
  // it or the contact and stability bound, whichever is smaller, rounded down to dt / 2^k (never
  // below dt_min): projective dynamics factorises its matrix once per step size and keeps the
  // factorisations of recent sizes, which a step chosen freely from the bound would change at
  // every step.
  double dt = dt_next_;
  int retries = 0;
  double last_rise = 0.0;
  const double bound = step_bound();
  mark_held_springs();
  auto on_ladder = [&](double wanted) {
    double h = options_.dt;
    while (h > wanted && 0.5 * h >= options_.dt_min) h *= 0.5;
    return h;
  };
  for (;;) {
    const double h = on_ladder(std::min(dt, bound));
    const double strain_before = free_strain();
    const Snapshot start = snapshot();
    StepResult r = try_step(h);
    // The integrator's own rise counts: the contact and constraint passes after it move particles
    // by distances that do not shrink with the step (a cloth that started within a collider's
    // margin is pushed out to it), so a smaller step would not change what they do; and the
    // length limits bringing a strain back down is no reason to retry.
    const double rise = r.integrator_strain - strain_before;
    // A rise that two halvings did not bring down by a fifth does not come from the step's length
    // (a contact pass moved particles, not the dynamics): the step is kept, as it is at dt_min.
    const bool step_driven = retries < 2 || rise < 0.8 * last_rise;
    const bool jump = r.ok && rise > options_.max_strain_change && step_driven && h * 0.5 >= options_.dt_min;
    last_rise = rise;
    if (r.ok && !jump) {
      r.retries = retries;
      time_ += h;
      calm_steps_ = std::abs(r.integrator_strain - strain_before) < 0.25 * options_.max_strain_change ? calm_steps_ + 1 : 0;
      dt_next_ = std::max(dt, h);
      if (calm_steps_ >= 10) {
        dt_next_ = std::min(options_.dt, 2.0 * dt_next_);
        calm_steps_ = 0;
      }
      return r;
    }
    if (jump) restore(start);
    if (h * 0.5 < options_.dt_min) {  // a failed step at the smallest step
      r.failure += " (adaptive step at its minimum " + std::to_string(options_.dt_min) + " s)";
      r.retries = retries;
      dt_next_ = h;
      return r;
    }
    dt = h * 0.5;
    ++retries;
    calm_steps_ = 0;
  }
}

}  // namespace dresskit::cloth
