#include "dresskit/alignment/wearer.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <numeric>
#include <queue>

#include "dresskit/alignment/icp.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"

namespace dresskit::alignment {

using mesh::TriangleMesh;

namespace {

/// Where a straight limb is split, as a fraction of its length from the torso along its surface
/// (shoulder to elbow over shoulder to fingertips, about 0.19 and 0.44 of a person's height; hip
/// crease to knee over hip crease to the tip of the toes, about 0.2 and 0.55).
constexpr double kElbowFraction = 0.40, kKneeFraction = 0.38;
constexpr int kLimbBins = 20;
/// Directions a limb is tried in before the articulated fit (search_limbs).
constexpr int kLimbDirections = 32;
/// The share of the garment's points, those fitting best, by which starts are ranked.
constexpr double kStartKept = 0.7;
/// The share by which a limb's turn must lower the garment's cost to be taken (search_limbs).
constexpr double kLimbGain = 0.02;
/// Garment points the limb search looks at, at most (every k-th).
constexpr int kLimbSamples = 800;

Eigen::Matrix3d rotation(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

/// Geodesic distance along edges from `sources` over the vertices with `inside` true (∞ elsewhere).
std::vector<double> edge_distance(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& neighbours,
                                  const std::vector<int>& sources, const std::vector<bool>& inside) {
  std::vector<double> d(static_cast<std::size_t>(V.rows()), HUGE_VAL);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int s : sources) {
    d[s] = 0.0;
    queue.push({0.0, s});
  }
  while (!queue.empty()) {
    const auto [du, u] = queue.top();
    queue.pop();
    if (du > d[u]) continue;
    for (int w : neighbours[u]) {
      if (!inside[w]) continue;
      const double dw = du + (V.row(u) - V.row(w)).norm();
      if (dw < d[w]) {
        d[w] = dw;
        queue.push({dw, w});
      }
    }
  }
  return d;
}

/// `sweeps` times, each row of W (one per vertex) moves halfway to the mean of its neighbours' rows.
void smooth_rows(Eigen::MatrixXd& W, const std::vector<std::vector<int>>& neighbours, int sweeps) {
  Eigen::MatrixXd next(W.rows(), W.cols());
  for (int s = 0; s < sweeps; ++s) {
    for (Eigen::Index v = 0; v < W.rows(); ++v) {
      const std::vector<int>& around = neighbours[static_cast<std::size_t>(v)];
      if (around.empty()) {
        next.row(v) = W.row(v);
        continue;
      }
      Eigen::RowVectorXd mean = Eigen::RowVectorXd::Zero(W.cols());
      for (int w : around) mean += W.row(w);
      next.row(v) = 0.5 * W.row(v) + 0.5 * mean / static_cast<double>(around.size());
    }
    W.swap(next);
  }
}

Eigen::Vector3d centroid(const Eigen::MatrixX3d& V, const std::vector<int>& rows) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int v : rows) sum += V.row(v).transpose();
  return rows.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(rows.size()));
}

/// A limb's bones: the distance along its surface from the torso where it is split, and the split's
/// centre (the cross-section's centroid there).
struct LimbSplit {
  double at = 0.0;
  Eigen::Vector3d joint = Eigen::Vector3d::Zero();
};
LimbSplit split_limb(const Eigen::MatrixX3d& V, const std::vector<int>& members, const std::vector<double>& d,
                     double straight_fraction, double min_bend_deg) {
  double length = 0.0;
  for (int v : members)
    if (std::isfinite(d[v])) length = std::max(length, d[v]);
  std::vector<Eigen::Vector3d> centre(kLimbBins, Eigen::Vector3d::Zero());
  std::vector<int> count(kLimbBins, 0);
  const double bin = std::max(length, 1e-9) / kLimbBins;
  for (int v : members) {
    if (!std::isfinite(d[v])) continue;
    const int k = std::min(kLimbBins - 1, static_cast<int>(d[v] / bin));
    centre[k] += V.row(v).transpose();
    ++count[k];
  }
  for (int k = 0; k < kLimbBins; ++k)
    if (count[k] > 0) centre[k] /= count[k];
  // The bend along the limb's centre line: the turn between the three bins before and after.
  LimbSplit split{straight_fraction * length, Eigen::Vector3d::Zero()};
  double sharpest = 0.0;
  constexpr int w = 3;
  for (int k = w; k + w < kLimbBins; ++k) {
    const double at = (k + 0.5) * bin;
    if (at < 0.25 * length || at > 0.7 * length || !count[k - w] || !count[k] || !count[k + w]) continue;
    const Eigen::Vector3d a = centre[k] - centre[k - w], b = centre[k + w] - centre[k];
    if (a.norm() < 1e-9 || b.norm() < 1e-9) continue;
    const double turn = std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
    if (turn > sharpest) {
      sharpest = turn;
      if (turn >= min_bend_deg) split.at = at;
    }
  }
  std::vector<int> ring;
  for (int v : members)
    if (std::abs(d[v] - split.at) < bin) ring.push_back(v);
  split.joint = centroid(V, ring);
  return split;
}

}  // namespace

BodyPartKind body_part_kind(const std::string& name) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool left = n.find("left") != std::string::npos, right = n.find("right") != std::string::npos;
  if (n.find("head") != std::string::npos || n.find("neck") != std::string::npos) return BodyPartKind::head;
  if (left != right) {
    if (n.find("arm") != std::string::npos || n.find("hand") != std::string::npos)
      return left ? BodyPartKind::arm_left : BodyPartKind::arm_right;
    if (n.find("leg") != std::string::npos || n.find("foot") != std::string::npos)
      return left ? BodyPartKind::leg_left : BodyPartKind::leg_right;
  }
  return BodyPartKind::torso;
}

std::string to_string(BodyPartKind kind) {
  static const char* names[] = {"torso", "head", "arm_left", "arm_right", "leg_left", "leg_right"};
  return names[static_cast<int>(kind)];
}

BodyRig rig_body(const TriangleMesh& body, const RigOptions& options) {
  if (!body.has_labels()) throw InputError("body: no part labels to rig it by");
  const int n = body.num_vertices();
  std::vector<BodyPartKind> kind(static_cast<std::size_t>(n), BodyPartKind::torso);
  bool limbs = false;
  for (int v = 0; v < n; ++v) {
    const int l = body.labels(v);
    if (l >= 0) kind[v] = body_part_kind(body.label_names[static_cast<std::size_t>(l)]);
    limbs = limbs || kind[v] >= BodyPartKind::arm_left;
  }
  if (!limbs) throw InputError("body: no arm or leg among its parts");
  BodyRig rig;
  rig.normals = mesh::vertex_normals(body.V, body.F);
  rig.height = body.V.col(1).maxCoeff() - body.V.col(1).minCoeff();
  const std::vector<std::vector<int>> neighbours = mesh::vertex_neighbours(body.F, n);
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  rig.bones = {"torso"};
  rig.part = {BodyPartKind::torso};
  rig.parent = {-1};
  std::vector<int> torso;
  for (int v = 0; v < n; ++v)
    if (kind[v] == BodyPartKind::torso) torso.push_back(v);
  rig.joint = {centroid(body.V, torso.empty() ? all : torso)};  // a limb held out does not move it
  std::vector<int> bone(static_cast<std::size_t>(n), 0);
  for (const BodyPartKind k : {BodyPartKind::head, BodyPartKind::arm_left, BodyPartKind::arm_right,
                               BodyPartKind::leg_left, BodyPartKind::leg_right}) {
    std::vector<int> members, junction;
    std::vector<bool> inside(static_cast<std::size_t>(n), false);
    for (int v = 0; v < n; ++v)
      if (kind[v] == k) members.push_back(v), inside[v] = true;
    if (members.empty()) continue;
    for (int v : members)
      if (std::any_of(neighbours[v].begin(), neighbours[v].end(), [&](int w) { return kind[w] == BodyPartKind::torso; }))
        junction.push_back(v);
    if (junction.empty()) {  // not joined to the torso by an edge: its vertex nearest the torso's centre
      const auto nearest = std::min_element(members.begin(), members.end(), [&](int a, int b) {
        return (body.V.row(a).transpose() - rig.joint[0]).squaredNorm() < (body.V.row(b).transpose() - rig.joint[0]).squaredNorm();
      });
      junction.push_back(*nearest);
    }
    const int first = static_cast<int>(rig.bones.size());
    rig.joint.push_back(centroid(body.V, junction));
    rig.parent.push_back(0);
    rig.part.push_back(k);
    if (k == BodyPartKind::head) {
      rig.bones.push_back("head");
      for (int v : members) bone[v] = first;
      continue;
    }
    const std::string name = to_string(k);
    rig.bones.push_back(name + "_upper");
    const std::vector<double> d = edge_distance(body.V, neighbours, junction, inside);
    const bool arm = k == BodyPartKind::arm_left || k == BodyPartKind::arm_right;
    const LimbSplit split = split_limb(body.V, members, d, arm ? kElbowFraction : kKneeFraction, options.min_bend_deg);
    rig.bones.push_back(name + "_lower");
    rig.joint.push_back(split.joint);
    rig.parent.push_back(first);
    rig.part.push_back(k);
    for (int v : members) bone[v] = std::isfinite(d[v]) && d[v] > split.at ? first + 1 : first;
  }
  // Weights: each bone's indicator diffused along the edges (lazy Jacobi sweeps), spreading about
  // blend_width across each joint; the kMaxInfluences largest kept.
  const int bones = static_cast<int>(rig.bones.size());
  double edge_sum = 0.0;
  long edges = 0;
  for (int v = 0; v < n; ++v)
    for (int w : neighbours[v]) edge_sum += (body.V.row(v) - body.V.row(w)).norm(), ++edges;
  const double mean_edge = edges ? edge_sum / static_cast<double>(edges) : 1.0;
  const int sweeps = std::clamp(static_cast<int>(std::lround(std::pow(options.blend_width / mean_edge, 2.0))), 0, 400);
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, bones);
  for (int v = 0; v < n; ++v) W(v, bone[v]) = 1.0;
  smooth_rows(W, neighbours, sweeps);
  rig.influence_bone.setConstant(n, BodyRig::kMaxInfluences, -1);
  rig.influence_weight.setZero(n, BodyRig::kMaxInfluences);
  rig.bone_of_vertex.resize(n);
  std::vector<int> order(static_cast<std::size_t>(bones));
  for (int v = 0; v < n; ++v) {
    std::iota(order.begin(), order.end(), 0);
    std::partial_sort(order.begin(), order.begin() + std::min(bones, BodyRig::kMaxInfluences), order.end(),
                      [&](int a, int b) { return W(v, a) > W(v, b); });
    double total = 0.0;
    for (int k = 0; k < std::min(bones, BodyRig::kMaxInfluences); ++k)
      if (W(v, order[k]) > 1e-3) total += W(v, order[k]);
    for (int k = 0; k < std::min(bones, BodyRig::kMaxInfluences); ++k) {
      if (W(v, order[k]) <= 1e-3) continue;
      rig.influence_bone(v, k) = order[k];
      rig.influence_weight(v, k) = W(v, order[k]) / total;
    }
    rig.bone_of_vertex(v) = order[0];
  }
  return rig;
}

namespace {

/// The fit's unknowns but the eases: the whole body's turn (rotation vector about the torso's centroid),
/// move [m] and log size, then each bone's turn (rotation vector, parent frame) but the root's.
constexpr int kGlobal = 7;

struct Pose {
  std::vector<Eigen::Matrix3d> R;  ///< per bone, body → wearer before the global similarity
  std::vector<Eigen::Vector3d> t;
  Eigen::Matrix3d Rg;
  Eigen::Vector3d tg;  ///< global: y ↦ s Rg (y − c) + c + tg
  double s = 1.0;
};

Pose pose_of(const BodyRig& rig, const Eigen::VectorXd& theta) {
  const int bones = static_cast<int>(rig.bones.size());
  Pose p;
  p.R.resize(bones);
  p.t.resize(bones);
  for (int b = 0; b < bones; ++b) {
    if (rig.parent[b] < 0) {
      p.R[b].setIdentity();
      p.t[b].setZero();
      continue;
    }
    const Eigen::Matrix3d turn = rotation(theta.segment<3>(kGlobal + 3 * (b - 1)));
    const int q = rig.parent[b];  // parents come before their children
    p.R[b] = p.R[q] * turn;
    p.t[b] = p.R[q] * (rig.joint[b] - turn * rig.joint[b]) + p.t[q];
  }
  p.Rg = rotation(theta.segment<3>(0));
  p.tg = theta.segment<3>(3);
  p.s = std::exp(theta(6));
  return p;
}

/// Body vertex v (at x) posed by the bones of p, before the global similarity.
Eigen::Vector3d skinned(const BodyRig& rig, const Pose& p, const Eigen::Vector3d& x, int v) {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  for (int k = 0; k < BodyRig::kMaxInfluences; ++k) {
    const int b = rig.influence_bone(v, k);
    if (b >= 0) y += rig.influence_weight(v, k) * (p.R[b] * x + p.t[b]);
  }
  return y;
}

/// Body vertex v (at x) posed by p: bones, then the global similarity.
Eigen::Vector3d posed_point(const BodyRig& rig, const Pose& p, const Eigen::Vector3d& x, int v) {
  return p.s * p.Rg * (skinned(rig, p, x, v) - rig.joint[0]) + rig.joint[0] + p.tg;
}

Eigen::Vector3d posed_normal(const BodyRig& rig, const Pose& p, int v) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int k = 0; k < BodyRig::kMaxInfluences; ++k) {
    const int b = rig.influence_bone(v, k);
    if (b >= 0) n += rig.influence_weight(v, k) * (p.R[b] * rig.normals.row(v).transpose());
  }
  n = p.Rg * n;
  const double length = n.norm();
  return length > 0 ? Eigen::Vector3d(n / length) : n;
}

/// Huber's loss at residual e with scale sigma.
double huber(double e, double sigma) {
  const double a = std::abs(e);
  return a <= sigma ? 0.5 * e * e : sigma * (a - 0.5 * sigma);
}

/// What a refinement may change: the eases only, the whole body's similarity too, or every bone.
enum class Unknowns { eases, whole, all };

/// One state of the fit and its figures at it.
struct FitState {
  Eigen::VectorXd theta;
  Eigen::VectorXd ease;
  double cost = HUGE_VAL;
};

class Fitter {
 public:
  Fitter(const BodyRig& rig, const TriangleMesh& body, const Eigen::MatrixX3d& points, const WearerFitOptions& o)
      : rig_(rig), g_(points), o_(o), rest_(body.V) {
    sigma_ = o.robust_scale * rig.height;
    reach_ = o.max_distance * rig.height;
  }

  int params() const { return kGlobal + 3 * (static_cast<int>(rig_.bones.size()) - 1); }

  /// Runs Gauss–Newton from `s` for `iterations`, changing `unknowns`.
  FitState refine(FitState s, int iterations, Unknowns unknowns, int* done = nullptr) const {
    const bool articulated = unknowns == Unknowns::all;
    const int bones = static_cast<int>(rig_.bones.size());
    const int np = unknowns == Unknowns::eases ? 0 : articulated ? params() : kGlobal;
    const int total = np + bones;
    const int m = static_cast<int>(g_.rows());
    std::vector<int> nearest(static_cast<std::size_t>(m));
    std::vector<Eigen::Vector3d> z(static_cast<std::size_t>(m)), n(static_cast<std::size_t>(m));
    int it = 0;
    for (; it < iterations; ++it) {
      const Pose p = pose_of(rig_, s.theta);
      correspond(p, articulated, nearest);
      double weight_total = 0.0;
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(total, total);
      Eigen::VectorXd grad = Eigen::VectorXd::Zero(total);
      std::vector<double> r(static_cast<std::size_t>(m)), w(static_cast<std::size_t>(m));
      for (int i = 0; i < m; ++i) {
        const int v = nearest[i];
        z[i] = posed_point(rig_, p, rest_.row(v).transpose(), v);
        n[i] = posed_normal(rig_, p, v);
        const Eigen::Vector3d d = g_.row(i).transpose() - z[i];
        r[i] = d.dot(n[i]) - s.ease(rig_.bone_of_vertex(v));
        w[i] = d.norm() > reach_ ? 0.0 : std::abs(r[i]) <= sigma_ ? 1.0 : sigma_ / std::abs(r[i]);
        weight_total += w[i];
      }
      if (weight_total <= 0.0) break;
      // Jacobian of the posed points by forward differences, one unknown at a time.
      Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, np);
      constexpr double h = 1e-6;
      for (int q = 0; q < np; ++q) {
        Eigen::VectorXd moved = s.theta;
        moved(q) += h;
        const Pose pq = pose_of(rig_, moved);
        for (int i = 0; i < m; ++i) {
          if (w[i] == 0.0) continue;
          const int v = nearest[i];
          J(i, q) = -n[i].dot(posed_point(rig_, pq, rest_.row(v).transpose(), v) - z[i]) / h;
        }
      }
      for (int i = 0; i < m; ++i) {
        if (w[i] == 0.0) continue;
        Eigen::VectorXd row = Eigen::VectorXd::Zero(total);
        row.head(np) = J.row(i).transpose();
        row(np + rig_.bone_of_vertex(nearest[i])) = -1.0;
        H.noalias() += w[i] * row * row.transpose();
        grad.noalias() += w[i] * r[i] * row;
      }
      // Priors: the size near the body's own, bone turns near none; a little damping throughout.
      // (Weighted like residuals of robust_scale: a unit of log size or of turn [rad] costs as
      // much as that residual at every point, times the prior's weight.)
      const double unit = weight_total * sigma_ * sigma_;
      const double ws = o_.scale_prior * unit, wt = o_.turn_prior * unit;
      if (np > 6) {
        H(6, 6) += ws;
        grad(6) += ws * s.theta(6);
      }
      for (int q = kGlobal; q < np; ++q) {
        H(q, q) += wt;
        grad(q) += wt * s.theta(q);
      }
      for (int q = 0; q < total; ++q) H(q, q) += 1e-6 * weight_total + 1e-3 * H(q, q);
      const Eigen::VectorXd step = H.ldlt().solve(-grad);
      if (!step.allFinite()) break;
      s.theta.head(np) += step.head(np);
      s.theta(6) = std::clamp(s.theta(6), std::log(o_.smallest_scale), std::log(o_.largest_scale));
      s.ease += step.tail(bones);
      s.ease = s.ease.cwiseMax(0.0).cwiseMin(o_.max_ease * rig_.height);
      if ((np == 0 || step.head(np).cwiseAbs().maxCoeff() < 1e-5) &&
          step.tail(bones).cwiseAbs().maxCoeff() < 1e-5 * rig_.height) {
        ++it;
        break;
      }
    }
    if (done) *done = it;
    s.cost = cost(s, articulated);
    return s;
  }

  /// Mean Huber loss of the points' residuals (points out of reach count as at the reach); with
  /// `kept` below 1, of that fraction of the points that fit best.
  double cost(const FitState& s, bool articulated, double kept = 1.0) const {
    const Pose p = pose_of(rig_, s.theta);
    std::vector<int> nearest(static_cast<std::size_t>(g_.rows()));
    correspond(p, articulated, nearest);
    std::vector<double> loss(static_cast<std::size_t>(g_.rows()));
    for (Eigen::Index i = 0; i < g_.rows(); ++i) {
      const int v = nearest[i];
      const Eigen::Vector3d z = posed_point(rig_, p, rest_.row(v).transpose(), v);
      const Eigen::Vector3d d = g_.row(i).transpose() - z;
      const double e = d.norm() > reach_ ? reach_ : d.dot(posed_normal(rig_, p, v)) - s.ease(rig_.bone_of_vertex(v));
      loss[i] = huber(e, sigma_);
    }
    const std::size_t count = std::max<std::size_t>(1, static_cast<std::size_t>(kept * static_cast<double>(loss.size())));
    if (count < loss.size()) std::nth_element(loss.begin(), loss.begin() + static_cast<long>(count), loss.end());
    double sum = 0.0;
    for (std::size_t i = 0; i < std::min(count, loss.size()); ++i) sum += loss[i];
    return loss.empty() ? 0.0 : sum / static_cast<double>(std::min(count, loss.size()));
  }

  /// Each limb turned about its joint to the direction, of kLimbDirections spread over the sphere,
  /// in which the garment lies closest around the body (the limb's upper bone and the bones below
  /// it move together): a sleeve hanging at the side and an arm held forward are too far apart for
  /// the Gauss–Newton steps to find each other from the correspondences alone.
  FitState search_limbs(FitState s) const {
    const int bones = static_cast<int>(rig_.bones.size());
    const int stride = std::max(1, static_cast<int>((g_.rows() + kLimbSamples - 1) / kLimbSamples));
    const int m = static_cast<int>((g_.rows() + stride - 1) / stride);
    for (int b = 1; b < bones; ++b) {
      if (rig_.parent[b] != 0 || rig_.part[b] == BodyPartKind::head) continue;
      int lower = -1;
      for (int c = 0; c < bones; ++c)
        if (rig_.parent[c] == b) lower = c;
      if (lower < 0) continue;
      const Pose p = pose_of(rig_, s.theta);
      // The garment brought back into the body's frame by the global similarity.
      Eigen::MatrixX3d back(m, 3);
      const Eigen::Vector3d c = rig_.joint[0];
      for (int i = 0; i < m; ++i)
        back.row(i) = (p.Rg.transpose() * (g_.row(i * stride).transpose() - c - p.tg) / p.s + c).transpose();
      // The distance of each garment point to the rest of the body as posed now.
      std::vector<int> limb, rest;
      for (Eigen::Index v = 0; v < rest_.rows(); ++v) {
        const int k = rig_.bone_of_vertex(v);
        (k == b || k == lower ? limb : rest).push_back(static_cast<int>(v));
      }
      if (limb.size() < 10 || rest.size() < 10) continue;
      Eigen::MatrixX3d others(static_cast<Eigen::Index>(rest.size()), 3);
      for (std::size_t k = 0; k < rest.size(); ++k)
        others.row(static_cast<Eigen::Index>(k)) = skinned(rig_, p, rest_.row(rest[k]).transpose(), rest[k]).transpose();
      const PointLocator rest_tree(others);
      Eigen::MatrixX3d others_normal(others.rows(), 3);
      for (std::size_t k = 0; k < rest.size(); ++k) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        for (int j = 0; j < BodyRig::kMaxInfluences; ++j)
          if (rig_.influence_bone(rest[k], j) >= 0)
            n += rig_.influence_weight(rest[k], j) * (p.R[rig_.influence_bone(rest[k], j)] * rig_.normals.row(rest[k]).transpose());
        others_normal.row(static_cast<Eigen::Index>(k)) = n.normalized().transpose();
      }
      std::vector<double> to_rest(static_cast<std::size_t>(m));
      for (int i = 0; i < m; ++i) {
        double d2 = 0.0;
        rest_tree.nearest(back.row(i).transpose(), &d2);
        to_rest[i] = std::sqrt(d2);
      }
      const double reach = reach_ / p.s, sigma = sigma_ / p.s;
      const auto cost_of = [&](const Eigen::VectorXd& theta) {
        const Pose q = pose_of(rig_, theta);
        Eigen::MatrixX3d moved(static_cast<Eigen::Index>(limb.size()), 3);
        for (std::size_t k = 0; k < limb.size(); ++k)
          moved.row(static_cast<Eigen::Index>(k)) = skinned(rig_, q, rest_.row(limb[k]).transpose(), limb[k]).transpose();
        const PointLocator tree(moved);
        double sum = 0.0;
        for (int i = 0; i < m; ++i) {
          double d2 = 0.0;
          tree.nearest(back.row(i).transpose(), &d2);
          sum += huber(std::min({std::sqrt(d2), to_rest[i], reach}), sigma);
        }
        // A limb turned into the body (a leg folded up into the torso under a shirt) costs as much,
        // for each of its points more than σ inside the rest of the body, as a garment point out
        // of reach: the limb's every fourth point, scaled to the garment's count.
        int inside = 0, looked = 0;
        for (std::size_t k = 0; k < limb.size(); k += 4, ++looked) {
          const Eigen::Vector3d x = moved.row(static_cast<Eigen::Index>(k)).transpose();
          const int r = rest_tree.nearest(x);
          inside += (x - others.row(r).transpose()).dot(others_normal.row(r).transpose()) < -sigma;
        }
        return sum + huber(reach, sigma) * m * inside / std::max(1, looked);
      };
      // The bone's direction at rest (from its joint to the joint below) and its turn now.
      const Eigen::Vector3d along = (rig_.joint[lower] - rig_.joint[b]).normalized();
      const double now = cost_of(s.theta);
      double best = now;
      Eigen::Vector3d best_turn = s.theta.segment<3>(kGlobal + 3 * (b - 1));
      for (int k = 0; k < kLimbDirections; ++k) {
        // Fibonacci sphere.
        const double z = 1.0 - 2.0 * (k + 0.5) / kLimbDirections, r = std::sqrt(1.0 - z * z);
        const double phi = k * M_PI * (3.0 - std::sqrt(5.0));
        const Eigen::Vector3d to(r * std::cos(phi), z, r * std::sin(phi));
        const Eigen::AngleAxisd turn(Eigen::Quaterniond::FromTwoVectors(along, to));
        Eigen::VectorXd theta = s.theta;
        theta.segment<3>(kGlobal + 3 * (b - 1)) = turn.angle() * turn.axis();
        const double cost = cost_of(theta);
        if (cost < best) {
          best = cost;
          best_turn = theta.segment<3>(kGlobal + 3 * (b - 1));
        }
      }
      // Only a turn that brings the garment markedly closer (a sleeve or a trouser leg found
      // around the limb): a little closer is a limb folded into the body under the garment.
      if (best < (1.0 - kLimbGain) * now) s.theta.segment<3>(kGlobal + 3 * (b - 1)) = best_turn;
    }
    return s;
  }

  /// The body posed as the wearer of state s.
  Eigen::MatrixX3d posed(const FitState& s) const {
    const Pose p = pose_of(rig_, s.theta);
    Eigen::MatrixX3d Z(rest_.rows(), 3);
    for (Eigen::Index v = 0; v < rest_.rows(); ++v)
      Z.row(v) = posed_point(rig_, p, rest_.row(v).transpose(), static_cast<int>(v)).transpose();
    return Z;
  }

 private:
  /// The body vertex nearest each garment point: with bones at rest, the point brought back by the
  /// global similarity and found among the body's own vertices; articulated, among the posed ones.
  void correspond(const Pose& p, bool articulated, std::vector<int>& nearest) const {
    if (!articulated) {
      if (!rest_tree_) rest_tree_ = std::make_shared<PointLocator>(rest_);
      const Eigen::Vector3d c = rig_.joint[0];
      for (Eigen::Index i = 0; i < g_.rows(); ++i) {
        const Eigen::Vector3d back = p.Rg.transpose() * (g_.row(i).transpose() - c - p.tg) / p.s + c;
        nearest[i] = rest_tree_->nearest(back);
      }
      return;
    }
    Eigen::MatrixX3d Z(rest_.rows(), 3);
    for (Eigen::Index v = 0; v < rest_.rows(); ++v)
      Z.row(v) = posed_point(rig_, p, rest_.row(v).transpose(), static_cast<int>(v)).transpose();
    const PointLocator tree(Z);
    for (Eigen::Index i = 0; i < g_.rows(); ++i) nearest[i] = tree.nearest(g_.row(i).transpose());
  }

  const BodyRig& rig_;
  const Eigen::MatrixX3d& g_;
  const WearerFitOptions& o_;
  const Eigen::MatrixX3d& rest_;
  mutable std::shared_ptr<PointLocator> rest_tree_;
  double sigma_ = 0.0, reach_ = 0.0;
};

}  // namespace

WearerFit fit_wearer(const BodyRig& rig, const TriangleMesh& body, const Eigen::MatrixX3d& garment_points,
                     const WearerFitOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (garment_points.rows() < 10) throw InputError("garment: too few points to fit a body into");
  const Eigen::Index stride = std::max<Eigen::Index>(1, (garment_points.rows() + options.max_samples - 1) / options.max_samples);
  Eigen::MatrixX3d points((garment_points.rows() + stride - 1) / stride, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) = garment_points.row(i * stride);
  const Fitter fitter(rig, body, points, options);
  const int bones = static_cast<int>(rig.bones.size());

  // Starts: the body where it is, and the body moved under the garment (its top at heights along
  // the body, centred on it across) at three sizes; each refined a little by the whole body alone.
  struct Start {
    FitState state;
    std::string name;
  };
  std::vector<Start> starts;
  const auto make = [&](const Eigen::Vector3d& move, double scale, const std::string& name) {
    FitState s;
    s.theta = Eigen::VectorXd::Zero(fitter.params());
    s.theta.segment<3>(3) = move;
    s.theta(6) = std::log(scale);
    s.ease = Eigen::VectorXd::Zero(bones);
    // Ranked by the best 70 % of the garment's points: a sleeve or a trouser leg far from a limb
    // posed otherwise must not hide the right place of the rest.
    FitState refined = fitter.refine(s, 8, Unknowns::whole);
    refined.cost = fitter.cost(refined, false, kStartKept);
    starts.push_back({refined, name});
  };
  make(Eigen::Vector3d::Zero(), 1.0, "as given");
  const Eigen::Vector3d body_min = body.V.colwise().minCoeff(), body_max = body.V.colwise().maxCoeff();
  const Eigen::Vector3d g_min = points.colwise().minCoeff(), g_max = points.colwise().maxCoeff();
  const Eigen::Vector3d g_mid = 0.5 * (g_min + g_max);
  const double H = rig.height;
  for (const double scale : {0.8, 1.0, 1.25, 1.5}) {
    // The body scaled about its centroid by `scale`: where its top and bottom then lie.
    const double c = rig.joint[0].y();
    const double top = c + scale * (body_max.y() - c), bottom = c + scale * (body_min.y() - c);
    for (double y = top; y - (g_max.y() - g_min.y()) >= bottom - 0.05 * H; y -= 0.03 * H) {
      Eigen::Vector3d move = Eigen::Vector3d::Zero();
      // Body moved so that the garment's top lies at height y of the (scaled) body.
      move.y() = g_max.y() - y;
      move.x() = g_mid.x() - rig.joint[0].x();
      move.z() = g_mid.z() - rig.joint[0].z();
      make(move, scale, "moved");
    }
  }
  std::sort(starts.begin(), starts.end(), [](const Start& a, const Start& b) { return a.state.cost < b.state.cost; });
  // The best starts that differ: apart by more than 2 % of the body's height or 5 % in size.
  std::vector<Start> distinct;
  for (const Start& s : starts) {
    const bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const Start& d) {
      return (s.state.theta.segment<3>(3) - d.state.theta.segment<3>(3)).norm() < 0.02 * rig.height &&
             std::abs(s.state.theta(6) - d.state.theta(6)) < 0.05;
    });
    if (!seen) distinct.push_back(s);
  }
  starts = std::move(distinct);
  // The best starts, articulated.
  WearerFit fit;
  FitState best;
  for (int k = 0; k < std::min<int>(options.starts_refined, static_cast<int>(starts.size())); ++k) {
    int iterations = 0;
    const FitState global = fitter.search_limbs(fitter.refine(starts[k].state, 10, Unknowns::whole));
    const FitState s = fitter.refine(global, options.iterations, Unknowns::all, &iterations);
    if (s.cost < best.cost) {
      best = s;
      fit.start = starts[k].name;
      fit.iterations = iterations;
    }
  }
  const Pose p = pose_of(rig, best.theta);
  fit.scale = p.s;
  const Eigen::Vector3d c = rig.joint[0];
  fit.global.setIdentity();
  fit.global.block<3, 3>(0, 0) = p.s * p.Rg;
  fit.global.block<3, 1>(0, 3) = c + p.tg - p.s * p.Rg * c;
  for (int b = 0; b < bones; ++b) {
    fit.turn.push_back(b == 0 ? Eigen::Matrix3d::Identity() : rotation(best.theta.segment<3>(kGlobal + 3 * (b - 1))));
    Eigen::Matrix4d A = Eigen::Matrix4d::Identity();
    A.block<3, 3>(0, 0) = p.R[b];
    A.block<3, 1>(0, 3) = p.t[b];
    fit.bone_transform.push_back(fit.global * A);
    fit.ease.push_back(best.ease(b));
  }
  fit.cost = best.cost;
  {
    FitState as_is;
    as_is.theta = Eigen::VectorXd::Zero(fitter.params());
    as_is.ease = Eigen::VectorXd::Zero(bones);
    fit.cost_as_is = fitter.refine(as_is, 5, Unknowns::eases).cost;
  }
  fit.posed = fitter.posed(best);
  fit.covered.assign(static_cast<std::size_t>(bones), 0);
  const PointLocator tree(fit.posed);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    double d2 = 0.0;
    const int v = tree.nearest(points.row(i).transpose(), &d2);
    if (std::sqrt(d2) <= options.max_distance * rig.height) ++fit.covered[static_cast<std::size_t>(rig.bone_of_vertex(v))];
  }
  fit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return fit;
}

CarriedGarment carry_garment(const BodyRig& rig, const WearerFit& fit, const TriangleMesh& garment,
                             const CarryOptions& options) {
  const int n = garment.num_vertices(), bones = static_cast<int>(rig.bones.size());
  const PointLocator tree(fit.posed);
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, bones);
  for (int g = 0; g < n; ++g) {
    const int v = tree.nearest(garment.V.row(g).transpose());
    for (int k = 0; k < BodyRig::kMaxInfluences; ++k)
      if (rig.influence_bone(v, k) >= 0) W(g, rig.influence_bone(v, k)) += rig.influence_weight(v, k);
  }
  const std::vector<std::vector<int>> neighbours = mesh::vertex_neighbours(garment.F, n);
  smooth_rows(W, neighbours, options.smoothing_sweeps);
  std::vector<Eigen::Matrix4d> back(static_cast<std::size_t>(bones));
  for (int b = 0; b < bones; ++b) back[b] = fit.bone_transform[b].inverse();
  CarriedGarment out;
  out.V.resize(n, 3);
  // Part names of a garment over each body part, in BodyPartKind's order.
  static const char* part_names[] = {"body", "hood", "sleeve_left", "sleeve_right", "leg_left", "leg_right"};
  std::vector<int> part_of(static_cast<std::size_t>(n));
  std::vector<int> used(6, 0);
  double moved = 0.0;
  for (int g = 0; g < n; ++g) {
    const Eigen::Vector4d x(garment.V(g, 0), garment.V(g, 1), garment.V(g, 2), 1.0);
    Eigen::Vector4d y = Eigen::Vector4d::Zero();
    for (int b = 0; b < bones; ++b)
      if (W(g, b) > 0.0) y += W(g, b) * (back[b] * x);
    out.V.row(g) = (y.head<3>() / W.row(g).sum()).transpose();
    moved += (out.V.row(g) - garment.V.row(g)).norm();
    // The part: a limb (or the head) where it carries at least three quarters of the vertex's
    // weight, the torso's otherwise (a shirt's hem over the hips is the shirt's body, not a leg).
    std::vector<double> per_part(6, 0.0);
    for (int b = 0; b < bones; ++b) per_part[static_cast<int>(rig.part[b])] += W(g, b) / W.row(g).sum();
    const int most = static_cast<int>(std::max_element(per_part.begin(), per_part.end()) - per_part.begin());
    part_of[g] = per_part[most] >= 0.75 ? most : static_cast<int>(BodyPartKind::torso);
    ++used[part_of[g]];
  }
  out.mean_move = n ? moved / n : 0.0;
  std::vector<int> index(6, -1);
  for (int k = 0; k < 6; ++k)
    if (used[k] > 0) {
      index[k] = static_cast<int>(out.label_names.size());
      out.label_names.push_back(part_names[k]);
    }
  out.labels.resize(n);
  for (int g = 0; g < n; ++g) out.labels(g) = index[part_of[g]];
  return out;
}

double largest_turn_degrees(const WearerFit& fit) {
  double turn = 0.0;
  for (std::size_t b = 1; b < fit.turn.size() && b < fit.covered.size(); ++b)
    if (fit.covered[b] > 0) turn = std::max(turn, Eigen::AngleAxisd(fit.turn[b]).angle() * 180.0 / M_PI);
  return turn;
}

double rms_from_ease(const WearerFit& fit) { return std::sqrt(2.0 * fit.cost); }

}  // namespace dresskit::alignment
