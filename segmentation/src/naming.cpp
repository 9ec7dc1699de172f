#include "dresskit/segmentation/naming.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace dresskit::segmentation {

AxesEstimate estimate_axes(const Eigen::MatrixX3d& V, const Eigen::VectorXd& area,
                           const Eigen::Vector3d& up_given, const Eigen::Vector3d& forward_given, bool has_feet) {
  AxesEstimate axes;
  const double total = area.sum();
  const Eigen::Vector3d centre = total > 0 ? Eigen::Vector3d((V.transpose() * area) / total)
                                           : Eigen::Vector3d(V.colwise().mean());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d d = V.row(i).transpose() - centre;
    cov += (total > 0 ? area(i) : 1.0) * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(cov);  // ascending spread

  if (up_given.norm() > 0) {
    axes.up = up_given.normalized();
    axes.up_given = true;
    axes.up_source = "given";
  } else {
    // Largest spread; a body carries more area above the middle of its height (torso, head, arms)
    // than below it (two thin legs), and so does an outfit.
    axes.up = pca.eigenvectors().col(2);
    const Eigen::VectorXd h = V * axes.up;
    if (centre.dot(axes.up) < 0.5 * (h.minCoeff() + h.maxCoeff())) axes.up = -axes.up;
    axes.up_source = "pca";
  }
  if (forward_given.norm() > 0) {
    axes.forward = (forward_given - forward_given.dot(axes.up) * axes.up).normalized();
    axes.forward_given = true;
    axes.forward_source = "given";
  } else {
    // The horizontal direction of least spread is the body's depth.
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - axes.up * axes.up.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> flat(P * cov * P);
    // flat has a zero eigenvalue along up; take the smaller of the two horizontal ones.
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3 && best.norm() == 0; ++k)
      if (std::abs(flat.eigenvectors().col(k).dot(axes.up)) < 0.5)
        best = flat.eigenvectors().col(k);
    axes.forward = (best - best.dot(axes.up) * axes.up).normalized();
    // Feet point forward: the lowest 4 % of the height lies ahead of the 8–20 % band (the shins).
    const Eigen::VectorXd h = V * axes.up;
    const double lo = h.minCoeff(), span = h.maxCoeff() - lo;
    double feet = 0, feet_w = 0, shins = 0, shins_w = 0;
    for (int i = 0; i < V.rows(); ++i) {
      const double t = (h(i) - lo) / (span > 0 ? span : 1.0);
      const double f = V.row(i).dot(axes.forward);
      if (t < 0.04) feet += area(i) * f, feet_w += area(i);
      if (t > 0.08 && t < 0.2) shins += area(i) * f, shins_w += area(i);
    }
    const double offset = feet_w > 0 && shins_w > 0 ? feet / feet_w - shins / shins_w : 0.0;
    if (has_feet && std::abs(offset) > 0.01 * span) {
      if (offset < 0) axes.forward = -axes.forward;
      axes.forward_source = "feet";
    } else {
      if (axes.forward.z() < 0) axes.forward = -axes.forward;
      axes.forward_source = "default +Z";
    }
  }
  axes.left = axes.up.cross(axes.forward).normalized();
  return axes;
}

namespace {

struct PartGeometry {
  double area = 0;
  int vertices = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

// Mean position of the vertices of label a that touch label b.
Eigen::Vector3d attachment(const Eigen::MatrixX3d& V, const MeshGraph& g,
                           const Eigen::VectorXi& labels, int a, int b) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (int e = 0; e < g.num_edges(); ++e) {
    const int i = g.from(e), j = g.to(e);
    if (labels(i) == a && labels(j) == b) sum += V.row(i).transpose(), ++count;
    if (labels(j) == a && labels(i) == b) sum += V.row(j).transpose(), ++count;
  }
  return count ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Zero();
}

double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }

// Orders a pair so that the first lies on the character's left; confidence from the lateral share.
std::pair<int, int> left_first(int a, int b, const std::vector<PartGeometry>& geo,
                               const AxesEstimate& axes, double& confidence) {
  const Eigen::Vector3d d = geo[a].centroid - geo[b].centroid;
  confidence = d.norm() > 0 ? clamp01(std::abs(d.dot(axes.left)) / d.norm()) : 0.0;
  return d.dot(axes.left) >= 0 ? std::make_pair(a, b) : std::make_pair(b, a);
}

}  // namespace

std::vector<NamedPart> name_parts(const Eigen::MatrixX3d& V, const MeshGraph& graph,
                                  const Eigen::VectorXd& area, const Eigen::VectorXi& labels,
                                  const std::vector<int>& label_component,
                                  const AxesEstimate& axes) {
  const int P = static_cast<int>(label_component.size());
  std::vector<PartGeometry> geo(P);
  for (int v = 0; v < labels.size(); ++v) {
    if (labels(v) < 0) continue;
    PartGeometry& g = geo[labels(v)];
    g.area += area(v);
    ++g.vertices;
    g.centroid += area(v) * V.row(v).transpose();
  }
  for (auto& g : geo)
    if (g.area > 0) g.centroid /= g.area;
  Eigen::MatrixXd touch = Eigen::MatrixXd::Zero(P, P);  // shared edge affinity between labels
  for (int e = 0; e < graph.num_edges(); ++e) {
    const int a = labels(graph.from(e)), b = labels(graph.to(e));
    if (a >= 0 && b >= 0 && a != b)
      touch(a, b) += graph.affinity(e), touch(b, a) += graph.affinity(e);
  }

  std::vector<NamedPart> parts(P);
  for (int l = 0; l < P; ++l) {
    parts[l].name = "part_" + std::to_string(l);
    parts[l].component = label_component[l];
    parts[l].vertices = geo[l].vertices;
    parts[l].area = geo[l].area;
  }
  const int components =
      P ? *std::max_element(label_component.begin(), label_component.end()) + 1 : 0;
  for (int c = 0; c < components; ++c) {
    std::vector<int> ls;
    for (int l = 0; l < P; ++l)
      if (label_component[l] == c) ls.push_back(l);
    if (ls.empty()) continue;
    auto neighbours = [&](int l) {
      int count = 0;
      for (int m : ls) count += m != l && touch(l, m) > 0;
      return count;
    };
    // Hub: the part touching the most others, then the one sharing the most affinity with them
    // (two trouser legs that touch at the crotch touch as many parts as the seat, but along a few
    // edges only).
    auto shared = [&](int l) {
      double sum = 0;
      for (int m : ls) sum += touch(l, m);
      return sum;
    };
    const int hub = *std::max_element(ls.begin(), ls.end(), [&](int a, int b) {
      return std::make_pair(neighbours(a), shared(a)) < std::make_pair(neighbours(b), shared(b));
    });
    std::vector<int> limbs;
    for (int l : ls)
      if (l != hub) limbs.push_back(l);
    const bool star =
        std::all_of(limbs.begin(), limbs.end(), [&](int l) { return touch(l, hub) > 0; });

    if (ls.size() == 6 && star) {  // a body
      parts[hub].name = "torso";
      parts[hub].confidence = 1.0;
      std::map<int, Eigen::Vector3d> at;
      for (int l : limbs) at[l] = attachment(V, graph, labels, l, hub);
      std::sort(limbs.begin(), limbs.end(),
                [&](int a, int b) { return at[a].dot(axes.up) < at[b].dot(axes.up); });
      // Legs attach lowest; of the other three the head attaches nearest the hub's vertical axis.
      std::vector<int> upper(limbs.begin() + 2, limbs.end());
      auto off_axis = [&](int l) {
        const Eigen::Vector3d d = at[l] - geo[hub].centroid;
        return (d - d.dot(axes.up) * axes.up).norm();
      };
      std::sort(upper.begin(), upper.end(),
                [&](int a, int b) { return off_axis(a) < off_axis(b); });
      const int head = upper[0];
      parts[head].name = "head";
      parts[head].confidence = clamp01(1.0 - off_axis(head) / std::max(off_axis(upper[1]), 1e-12));
      const double legs_gap = at[limbs[2]].dot(axes.up) - at[limbs[1]].dot(axes.up);
      const double legs_span = at[limbs.back()].dot(axes.up) - at[limbs[0]].dot(axes.up);
      const double leg_conf = legs_span > 0 ? clamp01(legs_gap / legs_span * 2) : 0.0;
      double lr = 0;
      auto [ll, lr_leg] = left_first(limbs[0], limbs[1], geo, axes, lr);
      parts[ll] = {"leg_left", leg_conf * lr, c, geo[ll].vertices, geo[ll].area};
      parts[lr_leg] = {"leg_right", leg_conf * lr, c, geo[lr_leg].vertices, geo[lr_leg].area};
      auto [al, ar] = left_first(upper[1], upper[2], geo, axes, lr);
      parts[al] = {"arm_left", parts[head].confidence * lr, c, geo[al].vertices, geo[al].area};
      parts[ar] = {"arm_right", parts[head].confidence * lr, c, geo[ar].vertices, geo[ar].area};
      continue;
    }
    if (ls.size() == 1) {  // one garment part: a skirt is a tube (waist, hem) or widens downwards
      const int l = ls[0];
      const int loops = count_boundary_loops(graph, [&](int v) { return labels(v) == l; });
      double spread[2] = {0, 0}, weight[2] = {0, 0};
      for (int v = 0; v < labels.size(); ++v) {
        if (labels(v) != l) continue;
        const Eigen::Vector3d d = V.row(v).transpose() - geo[l].centroid;
        const int half = d.dot(axes.up) < 0 ? 0 : 1;
        spread[half] += area(v) * (d - d.dot(axes.up) * axes.up).norm();
        weight[half] += area(v);
      }
      const double lower = weight[0] > 0 ? spread[0] / weight[0] : 0,
                   upper = weight[1] > 0 ? spread[1] / weight[1] : 0;
      const bool skirt = loops == 2 || lower > 1.1 * upper;
      parts[l].name = skirt ? "skirt" : "body";
      parts[l].confidence =
          loops == 2 ? 0.8 : clamp01(std::abs(lower - upper) / std::max(lower + upper, 1e-12) * 4);
      continue;
    }
    // A garment with several parts: the hub is the body, legs hang below it, sleeves stick out.
    parts[hub].name = "body";
    parts[hub].confidence = star ? 1.0 : 0.5;
    std::map<std::string, std::vector<int>> by_kind;
    for (int l : limbs) {
      const Eigen::Vector3d d = geo[l].centroid - geo[hub].centroid;
      const double down = -d.dot(axes.up), side = std::abs(d.dot(axes.left));
      const bool leg = down > side;
      by_kind[leg ? "leg" : "sleeve"].push_back(l);
      parts[l].confidence = d.norm() > 0 ? clamp01(std::abs(down - side) / d.norm()) : 0.0;
    }
    for (auto& [kind, members] : by_kind) {
      std::sort(members.begin(), members.end(), [&](int a, int b) {
        return geo[a].centroid.dot(axes.left) > geo[b].centroid.dot(axes.left);
      });
      if (members.size() == 2) {
        double lr = 0;
        left_first(members[0], members[1], geo, axes, lr);
        parts[members[0]].name = kind + "_left";
        parts[members[1]].name = kind + "_right";
        parts[members[0]].confidence *= lr;
        parts[members[1]].confidence *= lr;
      } else {
        for (size_t k = 0; k < members.size(); ++k) {
          const double side = (geo[members[k]].centroid - geo[hub].centroid).dot(axes.left);
          parts[members[k]].name = kind + (side >= 0 ? "_left" : "_right") +
                                   (members.size() > 2 ? "_" + std::to_string(k) : "");
          parts[members[k]].confidence *= 0.5;
        }
      }
    }
  }
  return parts;
}

}  // namespace dresskit::segmentation
