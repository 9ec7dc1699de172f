#include "dresskit/segmentation/cleanup.h"

#include <algorithm>
#include <map>

namespace dresskit {

int merge_orphan_patches(const MeshGraph& graph, const Adjacency& adj,
                         const Eigen::VectorXd& vertex_area, Eigen::VectorXi& labels) {
  const int n = graph.num_vertices;
  int relabelled = 0;
  // Each round finds the patches (connected runs of one label), keeps the largest of each label and
  // hands every other patch to its strongest neighbour label. Rounds repeat because a patch may be
  // enclosed by another orphan; a patch with no labelled neighbour stays as it is.
  for (int round = 0; round < 32; ++round) {
    std::vector<int> patch(n, -1);
    std::vector<int> patch_label;
    std::vector<double> patch_area;
    std::vector<int> stack;
    for (int s = 0; s < n; ++s) {
      if (patch[s] >= 0 || labels(s) < 0) continue;
      const int id = static_cast<int>(patch_label.size());
      patch_label.push_back(labels(s));
      patch_area.push_back(0.0);
      patch[s] = id;
      stack.assign(1, s);
      while (!stack.empty()) {
        const int v = stack.back();
        stack.pop_back();
        patch_area[id] += vertex_area(v);
        for (int k = adj.start[v]; k < adj.start[v + 1]; ++k) {
          const int w = adj.adj[k];
          if (patch[w] < 0 && labels(w) == labels(v)) {
            patch[w] = id;
            stack.push_back(w);
          }
        }
      }
    }
    std::map<int, int> largest;  // label → its largest patch
    for (int p = 0; p < static_cast<int>(patch_label.size()); ++p) {
      auto it = largest.find(patch_label[p]);
      if (it == largest.end() || patch_area[p] > patch_area[it->second]) largest[patch_label[p]] = p;
    }
    // Affinity from each orphan patch to each neighbouring label.
    std::vector<std::map<int, double>> toward(patch_label.size());
    for (int e = 0; e < graph.num_edges(); ++e) {
      const int a = patch[graph.from(e)], b = patch[graph.to(e)];
      if (a < 0 || b < 0 || a == b) continue;
      toward[a][patch_label[b]] += graph.affinity(e);
      toward[b][patch_label[a]] += graph.affinity(e);
    }
    std::vector<int> target(patch_label.size(), -1);
    bool any = false;
    for (int p = 0; p < static_cast<int>(patch_label.size()); ++p) {
      if (largest[patch_label[p]] == p || toward[p].empty()) continue;
      target[p] = std::max_element(toward[p].begin(), toward[p].end(), [](const auto& x, const auto& y) {
                    return x.second < y.second;
                  })->first;
      any = true;
    }
    if (!any) break;
    for (int v = 0; v < n; ++v)
      if (patch[v] >= 0 && target[patch[v]] >= 0) {
        labels(v) = target[patch[v]];
        ++relabelled;
      }
  }
  return relabelled;
}

int smooth_label_boundaries(const MeshGraph& graph, const Adjacency& adj, int iterations,
                            Eigen::VectorXi& labels) {
  const int n = graph.num_vertices;
  int changes = 0;
  std::map<int, double> vote;
  for (int it = 0; it < iterations; ++it) {
    Eigen::VectorXi next = labels;
    int changed = 0;
    for (int v = 0; v < n; ++v) {
      if (labels(v) < 0 || adj.start[v] == adj.start[v + 1]) continue;
      bool boundary = false;
      for (int k = adj.start[v]; k < adj.start[v + 1] && !boundary; ++k)
        boundary = labels(adj.adj[k]) != labels(v);
      if (!boundary) continue;
      vote.clear();
      double self = 0.0;
      for (int k = adj.start[v]; k < adj.start[v + 1]; ++k) {
        const double w = graph.affinity(adj.edge[k]);
        self += w;
        if (labels(adj.adj[k]) >= 0) vote[labels(adj.adj[k])] += w;
      }
      vote[labels(v)] += self / (adj.start[v + 1] - adj.start[v]);
      const int best = std::max_element(vote.begin(), vote.end(), [](const auto& x, const auto& y) {
                         return x.second < y.second;
                       })->first;
      if (best != labels(v)) {
        next(v) = best;
        ++changed;
      }
    }
    labels = next;
    changes += changed;
    if (!changed) break;
  }
  return changes;
}

Eigen::VectorXi face_labels_from_vertices(const Eigen::MatrixX3i& F, const Eigen::VectorXi& labels) {
  Eigen::VectorXi out(F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    const int a = labels(F(f, 0)), b = labels(F(f, 1)), c = labels(F(f, 2));
    out(f) = (b == c && b != a) ? b : a;
  }
  return out;
}

}  // namespace dresskit
