// ClothSimulator and its colliders: penalty forces, contacts, collision response.
#include "dresskit/cloth/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dresskit/cloth/geometry.h"
#include "simulator_internal.h"

namespace dresskit::cloth {
using detail::row;

namespace {
/// exp(depth/δ) − 1 with the exponent capped at 4 (deeper particles are projected out anyway).
double penalty_profile(double depth, double delta) { return std::exp(std::min(depth / delta, 4.0)) - 1.0; }
}  // namespace

void ClothSimulator::add_penalty_forces(Eigen::MatrixX3d& f) const {
  for (std::size_t k = 0; k < contacts_.particle.size(); ++k) {
    const int p = contacts_.particle[k];
    const double a = options_.colliders[contacts_.collider[k]].penalty;
    f.row(p) += model_.mass(p) * a * penalty_profile(contacts_.depth[k], options_.penalty_thickness) *
                contacts_.normal[k].transpose();
  }
}

double ClothSimulator::distance_lower_bound(int i, int c, const Eigen::Vector3d& p) const {
  if (static_cast<int>(lookup_x_.size()) <= c) return -HUGE_VAL;
  return lookup_d_(i, c) - 1.75 * (p - row(lookup_x_[c], i)).norm();
}

void ClothSimulator::find_inside() {
  start_distance_ = Eigen::VectorXd::Constant(x_.rows(), HUGE_VAL);
  for (int i = 0; i < x_.rows(); ++i) {
    const double margin = options_.collision_margin + model_.layer_offset[model_.layer[i]];
    for (const Collider& c : options_.colliders) {
      Eigen::Vector3d n;
      const double d = c.distance(row(x_, i), &n);
      if (d < margin) start_distance_[i] = std::min(start_distance_[i], d);
    }
  }
}

double ClothSimulator::exit_margin(int i, double margin) const {
  return std::min(margin, start_distance_[i] + deep_push_speed_ * dt_);
}

void ClothSimulator::find_contacts() {
  contacts_.clear();
  for (int c = 0; c < static_cast<int>(options_.colliders.size()); ++c) {
    const Collider& collider = options_.colliders[c];
    if (collider.penalty <= 0.0) continue;
    for (int i = 0; i < x_.rows(); ++i) {
      const double zone = options_.collision_margin + model_.layer_offset[model_.layer[i]] + options_.penalty_thickness;
      Eigen::Vector3d n;
      const double d = collider.distance(row(x_, i), &n);
      if (d < zone) contacts_.add(i, c, n, zone - d);
    }
  }
}

// Collision response with analytic colliders: a particle closer than the margin is pushed out along
// the outward normal where it entered (found by bisection on its path during the step; the nearest
// surface point is wrong for a particle that went deeper than its distance to another face of a box),
// or along the nearest normal if it was already inside. Its inward normal velocity is removed and its
// tangential velocity stopped when it is under μ_static × the removed normal speed (static friction),
// else reduced by μ × that speed (kinetic). The pass also records the particles in a penalty zone.
// Moves particle i out to the margin along the collider's normal, again from where that lands (up to
// four times: one push along a sharp feature's normal can fall short).
double ClothSimulator::push_out(const Collider& c, double margin, int i) {
  Eigen::Vector3d n;
  for (int it = 0; it < 4; ++it) {
    const double d = c.distance(row(x_, i), &n);
    if (d >= margin) return d;
    x_.row(i) += (margin - d) * n.transpose();
  }
  return c.distance(row(x_, i), &n);
}

void ClothSimulator::collide(const Eigen::MatrixX3d& x_start, StepResult& r) {
  contacts_.clear();
  // Particles still inside a collider after this pass (a particle there is always looked up: its
  // distance is below the margin); the next step starts from these.
  end_distance_.setConstant(x_.rows(), HUGE_VAL);
  const double delta = options_.penalty_thickness;
  const int colliders = static_cast<int>(options_.colliders.size());
  // A particle's distance changes by at most √3 × its travel (the body grid's trilinear value has
  // partial derivatives ≤ 1; analytic distances are 1-Lipschitz), so one that was far enough at its
  // last lookup needs none now. On the 10k-particle cape draped on gc_mean_all a lookup costs ~0.1 µs
  // (cache misses in the 34 MB grid) and a step made ~10,750 of them for ~200 contacts.
  if (lookup_x_.size() != static_cast<std::size_t>(colliders)) {
    lookup_x_.assign(static_cast<std::size_t>(colliders), x_);
    lookup_d_ = Eigen::MatrixXd::Constant(x_.rows(), colliders, -1e300);
  }
  for (int i = 0; i < x_.rows(); ++i) {
    // Outer layers keep clear of the layers beneath them too.
    const double margin = options_.collision_margin + model_.layer_offset[model_.layer[i]];
    for (int ci = 0; ci < colliders; ++ci) {
      const Collider& c = options_.colliders[ci];
      Eigen::Vector3d n;
      const Eigen::Vector3d x = row(x_, i), x0 = row(x_start, i);
      // Every point of the path x0 → x is within the farther of its two ends from the last lookup.
      const double travel = std::max((x - row(lookup_x_[ci], i)).norm(), (x0 - row(lookup_x_[ci], i)).norm());
      if (lookup_d_(i, ci) - 1.75 * travel > margin + delta + 1e-4) continue;
      const double d = c.distance(x, &n, lookup_cell(i, ci));
      lookup_d_(i, ci) = d;
      lookup_x_[ci].row(i) = x.transpose();
      if (c.penalty > 0.0 && d < margin + delta) contacts_.add(i, ci, n, margin + delta - std::max(d, margin));
      if (pinned_[i]) continue;
      Eigen::Vector3d unused;
      // Where the path first comes within the margin: t_in (1: at its end), f_in the distance − margin there.
      double t_in = 1.0, f_in = d - margin, d0 = 0.0;
      bool through_from_margin = false;  // passed through, having started within the margin
      if (d >= margin) {
        // Ends outside, but a fast particle may have passed through a thin part (a finger, an arm
        // seen edge-on) within the step: continuous collision detection by conservative advancement
        // along the path (sphere tracing: the distance is a lower bound on how far the path can go
        // before it meets the surface, with the grid's Lipschitz bound 1.75), looking for a point
        // inside the collider. Only a path long enough to pass through from both ends' distances
        // is traced, so particles resting or sliding on the surface are not. Steps are at least a
        // quarter of the margin (a part thinner than that is not resolved), and a trace takes at
        // most 256 lookups.
        const double path = (x - x0).norm();
        if (d > 1.75 * path) continue;
        d0 = c.distance(x0, &unused);
        if (d0 < 0.0 || d0 + d > 1.75 * path) continue;
        t_in = -1.0;
        const double least = std::max(0.25 * margin / path, 1.0 / 256.0);
        for (double t = 0.0, f = d0; t < 1.0;) {
          t += std::max(f / (1.75 * path), least);
          if (t >= 1.0) break;
          f = c.distance(x0 + t * (x - x0), &unused);
          if (f < 0.0) {
            t_in = t, f_in = f - margin;
            break;
          }
        }
        if (t_in < 0.0) continue;
        ++r.tunnelling;
        through_from_margin = d0 < margin;
      } else {
        d0 = c.distance(x0, &unused);
      }
      ++r.collisions;
      if (through_from_margin) {  // back to where it started, then out to the margin there
        x_.row(i) = x0.transpose();
        push_out(c, margin, i);
        c.distance(row(x_, i), &n);
      } else if (d0 >= margin) {
        // The entry point: the root of f(t) = distance(x0 + t (x − x0)) − margin on [0, 1] by the
        // Illinois variant of regula falsi (f is nearly linear along a short path: 2–4 lookups where
        // bisection took 10–20); lo stays outside (f ≥ 0), hi inside.
        double lo = 0.0, hi = t_in, f_lo = d0 - margin, f_hi = f_in, outside = f_lo;
        const double path = (x - x0).norm();
        for (int it = 0, kept = 0; it < 40 && (hi - lo) * path > 1e-7 && outside > 1e-7; ++it) {
          const double t = std::clamp((lo * f_hi - hi * f_lo) / (f_hi - f_lo), lo, hi);
          const double f = c.distance(x0 + t * (x - x0), &unused) - margin;
          if (f >= 0.0) {
            lo = t, f_lo = outside = f;
            if (kept == -1) f_hi *= 0.5;  // the same end kept twice: halve the other's weight
            kept = -1;
          } else {
            hi = t, f_hi = f;
            if (kept == 1) f_lo *= 0.5;
            kept = 1;
          }
        }
        const Eigen::Vector3d entry = x0 + lo * (x - x0);
        c.distance(entry, &n);
        x_.row(i) -= std::min(0.0, (x - entry).dot(n)) * n.transpose();  // back to the entry plane
        // Curved or concave surfaces: still inside the margin after that, out along the local normal;
        // the entry point itself only if that leaves it inside the collider (in a crease narrower than
        // the margin) — the entry point stops the particle sliding, so it is the last resort.
        if (push_out(c, margin, i) < 0.0) x_.row(i) = entry.transpose();
      } else if (d0 >= 0.0) {  // started within the margin: back to it along the nearest normal
        push_out(c, margin, i);
      } else {
        // Started inside the collider (cloth that began inside a body, or was pushed in): out at a
        // bounded speed (deep_push_speed_), so that a deep particle does not tear its springs, and
        // never deeper than it started, whatever the integrator did (the projective iterations
        // hold it there too: exit_margin); it is reported.
        const double target = std::min(margin, std::min(start_distance_[i], d0) + deep_push_speed_ * dt_);
        if (target < margin) ++r.deep_pushes;
        if (d < target) x_.row(i) += (target - d) * n.transpose();
        end_distance_[i] = std::min(end_distance_[i], std::max(d, target));
      }
      Eigen::Vector3d v = row(v_, i);
      const double vn = v.dot(n);
      if (vn < 0.0) {
        v -= vn * n;
        const Eigen::Vector3d vt = v - v.dot(n) * n;
        const double t = vt.norm(), mu_static = c.static_friction < 0.0 ? c.friction : c.static_friction;
        if (t <= mu_static * -vn) v -= vt;        // static: sticks
        else v -= (c.friction * -vn / t) * vt;   // kinetic: slides, slowed
      }
      v_.row(i) = v.transpose();
      contact_normal_.row(i) = n.transpose();
    }
  }
}

}  // namespace dresskit::cloth
