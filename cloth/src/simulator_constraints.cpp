// ClothSimulator's position passes after the integrator: strain limiting, seams, layer order.
#include "dresskit/cloth/simulator.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

#include "dresskit/cloth/geometry.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/seams.h"
#include "simulator_internal.h"

namespace dresskit::cloth {
using detail::row;

namespace {
/// limit_strain queues the springs of the active particles, rather than scanning all springs, when
/// fewer than one particle in this many is active (a full scan is cheaper beyond).
constexpr double kQueueShare = 8.0;
}  // namespace

void ClothSimulator::limit_strain(const Eigen::MatrixX3d& x_before, StepResult& r, bool all, bool after_contact) {
  const SpringSet& s = model_.springs;
  const double limit = 1.0 + options_.strain_limit;
  const double done = limit + options_.strain_limit_tolerance;
  const int n = static_cast<int>(x_.rows());
  // Active set: a spring is looked at only when one of its ends has moved since it was last found
  // within its bounds. The first sweep's set: every particle (all), or those that moved since the
  // last call ended with every spring within its bounds (a later round of a step: the cloth–cloth
  // pass and the collider pass moved a few particles).
  std::vector<char>& active = limit_active_;
  std::vector<char>& next = limit_next_;
  all = all || !limit_converged_ || limit_end_.rows() != n;
  active.assign(static_cast<std::size_t>(n), 1);
  if (!all)
    for (int p = 0; p < n; ++p) active[p] = x_.row(p) != limit_end_.row(p);
  next.assign(static_cast<std::size_t>(n), 0);
  // In a later round of a step the particles that moved since the last call were moved by the
  // contact passes (cloth–cloth, colliders, sewing): a length-limited spring with one such end and
  // one free end moves only the free end (shock propagation, Guendelman et al. 2003). Split
  // half-way, a double layer whose inner layer the cloth–cloth pass had just stopped on the layer
  // beneath was pushed back into it by half of each correction, the next pass stopped it again, and
  // the rounds ended with the double layer up to 0.6 mm below its lower limit at landing.
  std::vector<char>& held = limit_held_;
  held.assign(static_cast<std::size_t>(n), 0);
  if (!all) held = active;
  // Moves i and j so that their distance becomes `target`; false when it was within `slack` of it.
  // A move of particle p that a collider pass of this step pushed out loses its part into the
  // collider: the particle slides along the surface instead of being pulled back in.
  auto slide = [&](int p, Eigen::Vector3d move) {
    const Eigen::Vector3d n = row(contact_normal_, p);
    const double into = move.dot(n);
    if (into < 0.0) move -= into * n;
    return move;
  };
  auto correct = [&](int i, int j, double target, double slack_low, double slack_high,
                     bool hold = false, bool sliding = false) {
    if (pinned_[i] && pinned_[j]) return false;
    const Eigen::Vector3d d = row(x_, j) - row(x_, i);
    const double L = d.norm();
    if ((L <= target + slack_high && L >= target - slack_low) || L == 0.0) return false;
    const Eigen::Vector3d c = (L - target) / L * d;  // moves i towards j by this much in total
    if (pinned_[i] || (hold && held[i] && !held[j])) {
      x_.row(j) += (sliding ? slide(j, -c) : Eigen::Vector3d(-c)).transpose();
    } else if (pinned_[j] || (hold && held[j] && !held[i])) {
      x_.row(i) += (sliding ? slide(i, c) : c).transpose();
    } else if (sliding) {
      x_.row(i) += slide(i, 0.5 * c).transpose();
      x_.row(j) += slide(j, -0.5 * c).transpose();
    } else {
      x_.row(i) += 0.5 * c.transpose();
      x_.row(j) -= 0.5 * c.transpose();
    }
    active[i] = active[j] = next[i] = next[j] = 1;  // later springs this sweep, earlier ones next
    return true;
  };
  const double inf = std::numeric_limits<double>::infinity();
  const auto length_limited = [&](int k) {
    return s.type[k] != SpringType::bending && s.type[k] != SpringType::layer_structural &&
           s.type[k] != SpringType::layer_shear;
  };
  if (options_.strain_limiting && (limit_first_.size() != static_cast<std::size_t>(n) + 1 ||
                                   limit_mark_.size() != static_cast<std::size_t>(s.size()))) {
    limit_first_.assign(static_cast<std::size_t>(n) + 1, 0);
    for (int k = 0; k < s.size(); ++k)
      if (length_limited(k)) ++limit_first_[s.i[k] + 1], ++limit_first_[s.j[k] + 1];
    for (int p = 0; p < n; ++p) limit_first_[p + 1] += limit_first_[p];
    limit_springs_.resize(static_cast<std::size_t>(limit_first_[n]));
    std::vector<int> fill(limit_first_.begin(), limit_first_.end() - 1);
    for (int k = 0; k < s.size(); ++k)  // ascending spring order within each particle's list
      if (length_limited(k)) limit_springs_[fill[s.i[k]]++] = k, limit_springs_[fill[s.j[k]]++] = k;
    limit_mark_.assign(static_cast<std::size_t>(s.size()), -1);
  }
  // A sweep looks at the springs in index order, each when one of its ends is active at that
  // moment. With few particles active (the later rounds of a step, a cloth held stretched in a few
  // places) the springs of active particles are queued instead of scanning them all: the same
  // springs in the same order, so the same result, for the work of the active ones.
  std::priority_queue<int, std::vector<int>, std::greater<int>> queue;
  int& stamp = limit_stamp_;
  const auto enqueue_after = [&](int p, int after) {
    for (int m = limit_first_[p]; m < limit_first_[p + 1]; ++m) {
      const int k = limit_springs_[m];
      if (k > after && limit_mark_[k] != stamp) limit_mark_[k] = stamp, queue.push(k);
    }
  };
  limit_converged_ = false;
  for (int sweep = 0; sweep < options_.strain_limit_iterations; ++sweep) {
    int violated = 0;
    if (options_.strain_limiting) {
      const auto spring = [&](int k) {
        const double L0 = s.rest_length[k];
        return correct(s.i[k], s.j[k], limit * L0, inf, (done - limit) * L0, false, after_contact);
      };
      const long active_count = std::count(active.begin(), active.end(), 1);
      if (kQueueShare * static_cast<double>(active_count) > n) {
        for (int k = 0; k < s.size(); ++k)
          if (length_limited(k) && (active[s.i[k]] || active[s.j[k]])) violated += spring(k);
      } else {
        ++stamp;
        for (int p = 0; p < n; ++p)
          if (active[p]) enqueue_after(p, -1);
        while (!queue.empty()) {
          const int k = queue.top();
          queue.pop();
          if (!spring(k)) continue;
          ++violated;
          enqueue_after(s.i[k], k);  // its ends are active now: their later springs this sweep
          enqueue_after(s.j[k], k);
        }
      }
    }
    for (std::size_t m = 0; m < s.limited.size(); ++m) {
      const int k = s.limited[m];
      if (!(active[s.i[k]] || active[s.j[k]])) continue;
      const Eigen::Vector3d d = row(x_, s.j[k]) - row(x_, s.i[k]);
      const double L = d.norm(), lo = s.limit_min[m], hi = s.limit_max[m];
      const double slack = options_.strain_limit_tolerance * s.rest_length[k];
      if (L > hi) violated += correct(s.i[k], s.j[k], hi, inf, slack, true);
      else if (L < lo) violated += correct(s.i[k], s.j[k], lo, slack, inf, true);
    }
    r.strain_limit_sweeps = sweep + 1;
    r.springs_limited += violated;
    if (violated == 0) {
      limit_converged_ = true;
      break;
    }
    active.swap(next);
    std::fill(next.begin(), next.end(), 0);
  }
  limit_end_ = x_;
  v_ += (x_ - x_before) / dt_;
}

// Sewing: a stitch whose two points have come within the seam tolerance is sewn, and from then on
// its points are moved together (by inverse mass, as the collision corrections), so a closed seam
// stays closed; velocities follow the moves. With a closing speed (and `draw`: once per step) a
// stitch not yet sewn is drawn closer by up to speed × dt, and sewn once that closes it.
double ClothSimulator::sew(StepResult& r, bool draw) {
  const double reach = draw ? options_.seam_closing_speed * dt_ : 0.0;
  const SeamSet& s = model_.seams;
  const Eigen::MatrixX3d before = x_;
  int idx[4] = {0, 0, 0, 0};
  double w[4] = {0, 0, 0, 0}, widest = 0.0;
  std::vector<int> drawn;
  for (int k = 0; k < s.size(); ++k) {
    const Eigen::Vector3d c = seam_gap(s, k, x_);
    if (!sewn_[k]) {
      if (c.norm() > std::max(options_.seam_tolerance, reach)) {
        if (reach > 0.0) drawn.push_back(k);
        continue;
      }
      sewn_[k] = 1;
      ++r.stitches_sewn;
    }
    widest = std::max(widest, c.norm());
    seam_weights(s, k, idx, w);
    shift_weighted_difference(x_, inverse_mass_, idx, w, -c);
  }
  for (const int k : drawn) draw_stitch(k, reach);
  v_ += (x_ - before) / dt_;
  return widest;
}

// Where a stitch's two sides a and b are to meet: their midpoint, or where that lies within a
// collider's margin, the nearest point outside it on a ray from the midpoint square to a–b (eight
// directions, sphere-traced): the way around the body part between them.
Eigen::Vector3d ClothSimulator::meeting_point(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  const Eigen::Vector3d mid = 0.5 * (a + b);
  const double margin = options_.collision_margin;
  auto clearance = [&](const Eigen::Vector3d& p) {
    double d = std::numeric_limits<double>::infinity();
    Eigen::Vector3d n;
    for (const Collider& c : options_.colliders) d = std::min(d, c.distance(p, &n) - margin);
    return d;
  };
  if (clearance(mid) >= 0.0) return mid;
  const Eigen::Vector3d u = (b - a).normalized();
  const Eigen::Vector3d e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  const double farthest = 0.5, step = 0.002;  // [m]: searched up to, and the smallest stride
  double best = farthest;
  Eigen::Vector3d meet = mid;
  for (int k = 0; k < 8; ++k) {
    const double angle = k * M_PI / 4.0;
    const Eigen::Vector3d dir = std::cos(angle) * e1 + std::sin(angle) * e2;
    for (double t = 0.0; t < best;) {
      const double d = clearance(mid + t * dir);
      if (d >= 0.0) {
        best = t;
        meet = mid + t * dir;
        break;
      }
      t += std::max(-d, step);
    }
  }
  return meet;
}

// A stitch not yet sewn is drawn closer: each side moves by up to half the reach towards the point
// where they are to meet (meeting_point). So a seam whose two sides lie on either side of a
// shoulder closes over the shoulder instead of pulling both sides into it.
void ClothSimulator::draw_stitch(int k, double reach) {
  const SeamSet& s = model_.seams;
  const Eigen::Vector3d a = row(x_, s.a[k]);
  const Eigen::Vector3d b = (1.0 - s.t[k]) * row(x_, s.b0[k]) + s.t[k] * row(x_, s.b1[k]);
  const Eigen::Vector3d meet = meeting_point(a, b);
  auto towards = [&](const Eigen::Vector3d& from) -> Eigen::Vector3d {
    const Eigen::Vector3d to = meet - from;
    const double len = to.norm();
    return len > 0.5 * reach ? Eigen::Vector3d(0.5 * reach / len * to) : to;
  };
  auto move = [&](int p, const Eigen::Vector3d& d) {
    if (!pinned_[p]) x_.row(p) += d.transpose();
  };
  const Eigen::Vector3d db = towards(b);
  move(s.a[k], towards(a));
  move(s.b0[k], db);  // an edge's point moves with both its ends
  if (s.b1[k] != s.b0[k]) move(s.b1[k], db);
}

void ClothSimulator::keep_layer_order(StepResult& r) {
  const LayerContacts c = match_layers(model_, x_, options_.colliders);
  const int layers = static_cast<int>(model_.layer_offset.size());
  for (int l = 1; l < layers; ++l) {  // inner layers first: their pushes carry outwards
    for (int p = 0; p < x_.rows(); ++p) {
      if (model_.layer[p] != l || c.below_face[p] < 0 || pinned_[p]) continue;
      Eigen::Vector3d n;
      const double dp = options_.colliders[c.collider[p]].distance(row(x_, p), &n);
      const double needed = c.height_below(p, model_, x_, options_.colliders) + model_.layer_min_gap[l];
      if (dp >= needed) continue;
      x_.row(p) += std::min(needed - dp, layer_push_cap_) * n.transpose();
      const double vn = v_.row(p).dot(n.transpose());
      if (vn < 0.0) v_.row(p) -= vn * n.transpose();
      ++r.layer_pushes;
    }
  }
}

}  // namespace dresskit::cloth
