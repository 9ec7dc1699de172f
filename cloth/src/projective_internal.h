#pragma once
// Projective dynamics' internals shared by its step (projective.cpp) and its L-BFGS solve
// (projective_lbfgs.cpp): the springs packed for the local step, the local step's kernels, and the
// integrator's state kept between steps.
#include <algorithm>
#include <array>
#include <cmath>
#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define DRESSKIT_SSE2 1
#endif

#include "dresskit/cloth/seams.h"
#include "dresskit/cloth/simulator.h"
#include "integrator.h"
#include "dresskit/cloth/stiffness_law.h"
#include "dresskit/mesh/errors.h"
#include "interleaved_cholesky.h"
#include "simulator_internal.h"

namespace dresskit::cloth {

namespace pd {
/// The spring's weight: the law's tangent stiffness just below the knee, k_knee + (5/3)(k_knee −
/// k0) (the last ramp segment's slope × knee strain, plus k_knee).
inline double projective_weight(double k_rest, double k_knee) {
  const double knee = std::max(k_rest, k_knee);
  return knee + 5.0 / 3.0 * (knee - k_rest);
}

using RowX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A spring's constants for the local step, packed (one read per spring): the ends, rest length and
/// its inverse, the law (fitted_k: k0, the rise to the knee, the slope beyond it) and the weight.
struct LocalSpring {
  int i, j;
  double L0, inv_L0, k0, rise, slope, w;
  /// w for bending springs, else 0. Only their diagonal terms are in the matrix: their couplings
  /// are moved to the right-hand side at the current iterate (a splitting; the fixed point is the
  /// same). They join vertices two apart, so in the matrix they more than double the factor (81×81
  /// cloth: 465 k entries with them, 195 k without) and the solve's time with it; their weights are
  /// a small fraction of the stretch springs', so the lag costs no iterations (docs/results.md).
  double lagged_w;
};

/// The law's secant stiffness k(ε) without branches (fitted_k): ramp knots at thirds of the knee
/// strain, then the straight continuation beyond it.
inline double law_k(const LocalSpring& q, double strain) {
  const double u = std::min(std::max(strain * (3.0 / kKneeStrain), 0.0), 3.0);
  const double seg = static_cast<int>(u);
  return q.k0 + q.rise * (1.0 / 9.0) * (seg * seg + (u - seg) * (2.0 * seg + 1.0)) +
         q.slope * std::max(strain - kKneeStrain, 0.0);
}

/// The law's tangent stiffness dt/dL = k(ε) + k′(ε) ε (k0 in compression).
inline double law_tangent(const LocalSpring& q, double strain) {
  if (strain <= 0.0) return q.k0;
  const double u = strain * (3.0 / kKneeStrain);
  const double dk =
      u >= 3.0 ? q.slope : q.rise * (1.0 / 9.0) * (2.0 * std::floor(u) + 1.0) * (3.0 / kKneeStrain);
  return law_k(q, strain) + dk * strain;
}

/// The local step for a list of springs: adds each spring's w d (and, for lagged springs, its
/// couplings at the current iterate) to the right-hand side R. Lagged (bending) springs are linear
/// (k0 = k_knee), so their law is k0; the stretch springs' loop has no lagged terms. Check: also
/// returns the largest ratio of a spring's tangent stiffness to its weight. Residual: adds the
/// spring's part of the residual b − A x instead, w (d − e) = (w d − w e): the matrix's spring
/// terms are w on the diagonal and −w off it (lagged springs: their couplings were at the
/// current iterate on the right-hand side, so the same), so the residual needs no product with A.
template <bool Lagged, bool Check = false, bool Residual = false>
double local_step(const std::vector<LocalSpring>& springs, const double* x, const double* rest,
                  int n, double beyond, double* R) {
  double worst = 0.0;
  auto one = [&](const LocalSpring& q) {
    const int i = q.i, j = q.j;
    double e[3] = {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]};
    double L = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    if (L < 1e-12) {  // no direction: take the rest direction
      for (int a = 0; a < 3; ++a) e[a] = rest[j + a * n] - rest[i + a * n];
      L = 0.0;
    }
    // 1 / |e| first: the division then runs alongside the law below instead of after it.
    const double inv_norm =
        1.0 / (L > 0.0 ? L : std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]));
    const double strain = L * q.inv_L0 - 1.0;
    const double k = Lagged ? q.k0 : law_k(q, strain);
    if (Check) worst = std::max(worst, law_tangent(q, strain) / q.w);
    const double stretch = L > beyond * q.L0 ? L * q.inv_L0 : 1.0;  // dynamic stiffness
    const double t = k * strain * q.L0 * stretch;
    // w d: the quadratic's pull w (L − ℓ) along e with ℓ = max(L − t/w, 0).
    double scale = std::max(q.w * L - t, 0.0) * inv_norm;
    if (Residual) scale -= q.w;  // minus the matrix's row: w (d − e), couplings included
    for (int a = 0; a < 3; ++a) {
      if (Lagged && !Residual) {
        R[3 * j + a] += scale * e[a] + q.lagged_w * x[3 * i + a];
        R[3 * i + a] += q.lagged_w * x[3 * j + a] - scale * e[a];
      } else {
        R[3 * j + a] += scale * e[a];
        R[3 * i + a] -= scale * e[a];
      }
    }
  };
  std::size_t k = 0;
#if defined(DRESSKIT_SSE2)
  // The iterations' form (residual, no check): two springs at a time in SSE2 registers, as the
  // explicit force loop (simulator.cpp) — the square roots, divisions and law_k for both in one
  // instruction each, then the adds one spring at a time; the arithmetic is one()'s (law_k's
  // branchless form, not fitted_k's: the two are kept apart as the scalar ones are).
  if (Residual && !Check) {
    const __m128d one_v = _mm_set1_pd(1.0), zero = _mm_setzero_pd(), tiny = _mm_set1_pd(1e-12),
                  u_scale = _mm_set1_pd(3.0 / kKneeStrain), three = _mm_set1_pd(3.0),
                  knee = _mm_set1_pd(kKneeStrain), ninth = _mm_set1_pd(1.0 / 9.0),
                  two = _mm_set1_pd(2.0), beyond_v = _mm_set1_pd(beyond);
    for (; k + 1 < springs.size(); k += 2) {
      const LocalSpring &p = springs[k], &q = springs[k + 1];
      const double *xi0 = x + 3 * p.i, *xj0 = x + 3 * p.j, *xi1 = x + 3 * q.i, *xj1 = x + 3 * q.j;
      const __m128d ex = _mm_sub_pd(_mm_set_pd(xj1[0], xj0[0]), _mm_set_pd(xi1[0], xi0[0]));
      const __m128d ey = _mm_sub_pd(_mm_set_pd(xj1[1], xj0[1]), _mm_set_pd(xi1[1], xi0[1]));
      const __m128d ez = _mm_sub_pd(_mm_set_pd(xj1[2], xj0[2]), _mm_set_pd(xi1[2], xi0[2]));
      const __m128d L = _mm_sqrt_pd(
          _mm_add_pd(_mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey)), _mm_mul_pd(ez, ez)));
      if (_mm_movemask_pd(_mm_cmplt_pd(L, tiny))) {  // a spring without direction: one at a time
        one(p);
        one(q);
        continue;
      }
      const __m128d inv_norm = _mm_div_pd(one_v, L);
      const __m128d L0 = _mm_set_pd(q.L0, p.L0), inv_L0 = _mm_set_pd(q.inv_L0, p.inv_L0);
      const __m128d w = _mm_set_pd(q.w, p.w), k0 = _mm_set_pd(q.k0, p.k0);
      const __m128d strain = _mm_sub_pd(_mm_mul_pd(L, inv_L0), one_v);
      __m128d k_law = k0;
      if (!Lagged) {  // law_k: ramp knots at thirds of the knee strain, then the straight line
        const __m128d u = _mm_min_pd(_mm_max_pd(_mm_mul_pd(strain, u_scale), zero), three);
        const __m128d seg = _mm_cvtepi32_pd(_mm_cvttpd_epi32(u));
        const __m128d ramp = _mm_mul_pd(
            _mm_mul_pd(_mm_set_pd(q.rise, p.rise), ninth),
            _mm_add_pd(_mm_mul_pd(seg, seg),
                       _mm_mul_pd(_mm_sub_pd(u, seg), _mm_add_pd(_mm_mul_pd(two, seg), one_v))));
        k_law = _mm_add_pd(_mm_add_pd(k0, ramp),
                           _mm_mul_pd(_mm_set_pd(q.slope, p.slope),
                                      _mm_max_pd(_mm_sub_pd(strain, knee), zero)));
      }
      const __m128d over = _mm_cmpgt_pd(L, _mm_mul_pd(beyond_v, L0));
      const __m128d stretch =
          _mm_or_pd(_mm_and_pd(over, _mm_mul_pd(L, inv_L0)), _mm_andnot_pd(over, one_v));
      const __m128d t = _mm_mul_pd(_mm_mul_pd(_mm_mul_pd(k_law, strain), L0), stretch);
      alignas(16) double scale[2], dx[2], dy[2], dz[2];
      _mm_store_pd(scale, _mm_sub_pd(
                              _mm_mul_pd(_mm_max_pd(_mm_sub_pd(_mm_mul_pd(w, L), t), zero), inv_norm),
                              w));
      _mm_store_pd(dx, ex);
      _mm_store_pd(dy, ey);
      _mm_store_pd(dz, ez);
      const int ends[2][2] = {{p.i, p.j}, {q.i, q.j}};
      for (int l = 0; l < 2; ++l) {
        double* Ri = R + 3 * ends[l][0];
        double* Rj = R + 3 * ends[l][1];
        Rj[0] += scale[l] * dx[l], Rj[1] += scale[l] * dy[l], Rj[2] += scale[l] * dz[l];
        Ri[0] -= scale[l] * dx[l], Ri[1] -= scale[l] * dy[l], Ri[2] -= scale[l] * dz[l];
      }
    }
  }
#endif
  for (; k < springs.size(); ++k) one(springs[k]);
  return worst;
}

/// The law's energy L0² ∫₀^ε k(s) s ds, exact per segment: k0 ε²/2, plus the ramp rise/9 q(u)
/// (q the piecewise-linear interpolant of u² at the knots u = 0…3, u = 3s/ε_knee) giving
/// rise/9 (ε_knee/3)² ∫₀^U q(u) u du, plus beyond the knee the ramp's full rise, rise ∫ s ds, and
/// slope ∫ (s − ε_knee) s ds. Equal to StiffnessLaw::energy (the L-BFGS chain test past the knee
/// fails without the held rise).
inline double law_energy(const LocalSpring& q, double strain) {
  double e = 0.5 * q.k0 * strain * strain;
  if (strain > 0.0) {
    const double U = std::min(strain * (3.0 / kKneeStrain), 3.0);
    const int j = std::min(static_cast<int>(U), 2);
    static const double F[3] = {0.0, 1.0 / 3.0, 13.0 / 3.0};  // ∫₀^j q(u) u du
    const double jj = j, u2 = U * U, j2 = jj * jj;
    const double ramp = F[j] + j2 * (u2 - j2) / 2.0 +
                        (2.0 * jj + 1.0) * ((u2 * U - j2 * jj) / 3.0 - jj * (u2 - j2) / 2.0);
    e += q.rise * (1.0 / 9.0) * (kKneeStrain * kKneeStrain / 9.0) * ramp;
    if (strain > kKneeStrain) {
      const double a = kKneeStrain;
      e += 0.5 * q.rise * (strain * strain - a * a) +  // the ramp's full rise, held
           q.slope * (strain * strain * strain / 3.0 - a * strain * strain / 2.0 + a * a * a / 6.0);
    }
  }
  return e * q.L0 * q.L0;
}
/// The largest squared move of a particle between two iterates (n particles, x y z interleaved) [m²].
inline double largest_move2(const double* x, const double* previous, int n) {
  double moved2 = 0.0;
  for (int v = 0; v < n; ++v) {
    const double* a = x + 3 * v;
    const double* b = previous + 3 * v;
    moved2 = std::max(moved2, (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                  (a[2] - b[2]) * (a[2] - b[2]));
  }
  return moved2;
}

/// Spring k's constants with the weight w.
inline LocalSpring local_spring(const SpringSet& s, int k, double w) {
  const double rise = std::max(s.k_knee[k] - s.k_rest[k], 0.0);
  return {s.i[k],
          s.j[k],
          s.rest_length[k],
          1.0 / s.rest_length[k],
          s.k_rest[k],
          rise,
          std::max(2.0 * rise, s.k_rest[k] + rise) / kKneeStrain,
          w,
          s.type[k] == SpringType::bending ? w : 0.0};
}

}  // namespace pd

/// The factorised global matrix for one step size and set of pins, with the step's work arrays.
struct ProjectiveFactor {
  double h = 0.0;  ///< the step in the matrix: dt, or 2 dt / 3 for BDF2
  bool single_precision = true;
  bool adaptive = false;  ///< weights from the springs' strains (projective_adaptive_weights)
  std::vector<bool> pinned;
  Eigen::VectorXd inertia;                         ///< m/h² + c m/h per particle
  Eigen::SparseMatrix<double, Eigen::RowMajor> A;  ///< the global matrix (pinned rows: identity)
  Eigen::SparseMatrix<double> to_pinned;  ///< free-row × pinned-column couplings, moved to the rhs
  std::vector<pd::LocalSpring> springs;
  std::vector<pd::LocalSpring> stretch, bend;  ///< the same, split for the local step's two loops
  /// Work arrays of a step, kept between steps: each is 6,561 × 3 doubles on the error bench's
  /// cloth, above malloc's mmap threshold, so allocating them anew every step cost page faults
  /// (5.6 % of a run's time in perf).
  mutable pd::RowX3 fixed, rhs, previous, X;
  /// Adaptive weights: the largest tangent stiffness / weight of a stretch spring at the start of
  /// an iteration since the weights were set.
  mutable double worst = 0.0;
  /// Adaptive weights: A column-major (factorised; its arrays are those of the symmetric A when
  /// same_layout) and each spring's entries ii, jj, ij, ji in it and in to_pinned (−1: none).
  Eigen::SparseMatrix<double> Acol;
  bool same_layout = false;
  std::vector<std::array<int, 4>> a_offset, b_offset;
  mutable Eigen::MatrixX3d x0, v0, base, vbase, target, y;
  std::vector<int> pinned_list;
  detail::InterleavedCholesky<float> single;
  detail::InterleavedCholesky<double> full;
  bool ok = false;
};

/// Projective dynamics as a time integrator (projective.cpp; the L-BFGS solve in projective_lbfgs.cpp).
class ProjectiveDynamics final : public TimeIntegrator {
 public:
  void step(ClothSimulator& sim, StepResult& r) override;
  void restart() override { history_ = History{}; }

 private:
  /// The factorisation for step h (current_), from the cache or new.
  void prepare(const ClothSimulator& sim, double h, const std::vector<double>* weights = nullptr);
  int solve(ClothSimulator& sim, const Eigen::MatrixX3d& target, const Eigen::MatrixX3d& air_base,
            const Eigen::Vector3d& wind, const Eigen::MatrixX3d& x0, pd::RowX3& X,
            ClothSimulator::Contacts& contacts);
  int lbfgs(const ClothSimulator& sim, const Eigen::MatrixX3d& target, const Eigen::MatrixX3d& air_base,
            const Eigen::Vector3d& wind, const Eigen::MatrixX3d& x0, pd::RowX3& X);
  /// Built at the first step and again when the step size or the pins change.
  std::shared_ptr<ProjectiveFactor> current_;
  /// The last solve's unbalanced force at the start of its last iteration [N] (−1: not measured,
  /// the double-precision solve).
  double force_end_ = -1.0;
  /// The factorisations of up to four other step sizes, most recent first (adaptive steps, BDF2's
  /// start-up); dropped when adaptive weights change the matrix.
  std::vector<std::shared_ptr<ProjectiveFactor>> cache_;
  /// BDF2's history: the state at the start of the step before (x_{n−1}, v_{n−1}) and at the start of
  /// the last step tried, with their times; cleared by restart().
  struct History {
    Eigen::MatrixX3d x_prev, v_prev, x_start, v_start;
    double t_prev = -1.0, t_start = -1.0;
  } history_;
};

}  // namespace dresskit::cloth
