#include "dresskit/segmentation/label_cleanup.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <unordered_map>

namespace dresskit::segmentation {

int merge_orphan_patches(const MeshGraph& graph, const Adjacency& adj,
                         const Eigen::VectorXd& vertex_area, Eigen::VectorXi& labels) {
  const int n = graph.num_vertices;
  int relabelled = 0;
  // Each round finds the patches (connected runs of one label), keeps the largest of each label and
  // hands every other patch that touches a kept patch to the kept label it shares most affinity
  // with. Rounds repeat for orphans enclosed by other orphans; an orphan with no labelled neighbour
  // stays.
  for (int round = 0; round < 64; ++round) {
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
      if (it == largest.end() || patch_area[p] > patch_area[it->second])
        largest[patch_label[p]] = p;
    }
    // Affinity from each orphan patch to each neighbouring kept patch. Orphans move into kept
    // patches only (never into another orphan), so kept patches only grow and the rounds end.
    std::vector<std::map<int, double>> toward(patch_label.size());
    auto kept = [&](int p) { return largest[patch_label[p]] == p; };
    for (int e = 0; e < graph.num_edges(); ++e) {
      const int a = patch[graph.from(e)], b = patch[graph.to(e)];
      if (a < 0 || b < 0 || a == b) continue;
      if (kept(b) && !kept(a)) toward[a][patch_label[b]] += graph.affinity(e);
      if (kept(a) && !kept(b)) toward[b][patch_label[a]] += graph.affinity(e);
    }
    std::vector<int> target(patch_label.size(), -1);
    bool any = false;
    for (int p = 0; p < static_cast<int>(patch_label.size()); ++p) {
      if (kept(p) || toward[p].empty()) continue;
      target[p] =
          std::max_element(toward[p].begin(), toward[p].end(), [](const auto& x, const auto& y) {
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
  std::map<int, int> count;  // vertices per label: smoothing never empties a label
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0) ++count[labels(v)];
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
      if (best != labels(v) && count[labels(v)] > 1) {
        next(v) = best;
        --count[labels(v)];
        ++count[best];
        ++changed;
      }
    }
    labels = next;
    changes += changed;
    if (!changed) break;
  }
  return changes;
}

namespace {

// Shared affinity between parts (symmetric, zero diagonal) and each part's volume (total degree).
void part_graph(const MeshGraph& graph, const Eigen::VectorXi& labels, int q, Eigen::MatrixXd& cut,
                Eigen::VectorXd& volume) {
  cut = Eigen::MatrixXd::Zero(q, q);
  volume = Eigen::VectorXd::Zero(q);
  for (int e = 0; e < graph.num_edges(); ++e) {
    const int a = labels(graph.from(e)), b = labels(graph.to(e));
    if (a < 0 || b < 0) continue;
    volume(a) += graph.affinity(e);
    volume(b) += graph.affinity(e);
    if (a != b) cut(a, b) += graph.affinity(e), cut(b, a) += graph.affinity(e);
  }
}

int leaves(const Eigen::MatrixXd& cut, const std::vector<bool>& alive) {
  int count = 0;
  for (int a = 0; a < cut.rows(); ++a) {
    if (!alive[a]) continue;
    int neighbours = 0;
    for (int b = 0; b < cut.rows(); ++b) neighbours += alive[b] && b != a && cut(a, b) > 0;
    count += neighbours == 1;
  }
  return count;
}

double ncut(const Eigen::MatrixXd& cut, const Eigen::VectorXd& volume,
            const std::vector<bool>& alive) {
  double sum = 0;
  for (int a = 0; a < cut.rows(); ++a)
    if (alive[a] && volume(a) > 0) sum += cut.row(a).sum() / volume(a);
  return sum;
}

// Part b joins part a in the part graph.
void merge_part(int a, int b, Eigen::MatrixXd& cut, Eigen::VectorXd& volume,
                std::vector<bool>& alive) {
  cut.row(a) += cut.row(b);
  cut.col(a) += cut.col(b);
  cut(a, a) = 0;
  cut.row(b).setZero();
  cut.col(b).setZero();
  volume(a) += volume(b);
  alive[b] = false;
}

}  // namespace

int count_leaf_parts(const MeshGraph& graph, const Eigen::VectorXi& labels) {
  const int q = labels.size() ? labels.maxCoeff() + 1 : 0;
  if (q <= 0) return 0;
  Eigen::MatrixXd cut;
  Eigen::VectorXd volume;
  part_graph(graph, labels, q, cut, volume);
  return leaves(cut, std::vector<bool>(q, true));
}

int merge_parts_towards_star(const MeshGraph& graph, int target, Eigen::VectorXi& labels) {
  const int q = labels.size() ? labels.maxCoeff() + 1 : 0;
  Eigen::MatrixXd cut;
  Eigen::VectorXd volume;
  part_graph(graph, labels, q, cut, volume);
  std::vector<bool> alive(q, true);
  std::vector<int> into(q);
  for (int a = 0; a < q; ++a) into[a] = a;
  for (int count = q; count > target; --count) {
    int best_a = -1, best_b = -1, best_leaves = -1;
    double best_ncut = 0;
    for (int a = 0; a < q; ++a)
      for (int b = a + 1; b < q; ++b) {
        if (!alive[a] || !alive[b] || cut(a, b) <= 0) continue;
        Eigen::MatrixXd c = cut;
        Eigen::VectorXd v = volume;
        std::vector<bool> live = alive;
        merge_part(a, b, c, v, live);
        const int l = leaves(c, live);
        const double n = ncut(c, v, live);
        if (l > best_leaves || (l == best_leaves && n < best_ncut))
          best_a = a, best_b = b, best_leaves = l, best_ncut = n;
      }
    if (best_a < 0) break;  // no adjacent parts left (should not happen within one component)
    merge_part(best_a, best_b, cut, volume, alive);
    for (int& x : into)
      if (x == best_b) x = best_a;
  }
  std::vector<int> compact(q, -1);
  int next = 0;
  for (int a = 0; a < q; ++a)
    if (alive[a]) compact[a] = next++;
  for (int i = 0; i < labels.size(); ++i)
    if (labels(i) >= 0) labels(i) = compact[into[labels(i)]];
  return leaves(cut, alive);
}

Eigen::VectorXi face_labels_from_vertices(const Eigen::MatrixX3i& F,
                                          const Eigen::VectorXi& labels) {
  Eigen::VectorXi out(F.rows());
  for (int f = 0; f < F.rows(); ++f) {
    const int a = labels(F(f, 0)), b = labels(F(f, 1)), c = labels(F(f, 2));
    out(f) = (b == c && b != a) ? b : a;
  }
  return out;
}

namespace {

// Geodesic distance (along edges, within the vertex's own label) to the nearest vertex that has a
// neighbour of another label; `other` = the label across the nearest boundary (the neighbouring
// label with the most affinity at that boundary vertex), −1 where there is none.
void distance_to_boundary(const MeshGraph& graph, const Adjacency& adj,
                          const Eigen::VectorXi& labels, std::vector<double>& dist,
                          std::vector<int>& other) {
  const int n = graph.num_vertices;
  dist.assign(n, std::numeric_limits<double>::infinity());
  other.assign(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  std::map<int, double> vote;
  for (int v = 0; v < n; ++v) {
    if (labels(v) < 0) continue;
    vote.clear();
    for (int k = adj.start[v]; k < adj.start[v + 1]; ++k) {
      const int l = labels(adj.adj[k]);
      if (l >= 0 && l != labels(v)) vote[l] += graph.affinity(adj.edge[k]);
    }
    if (vote.empty()) continue;
    other[v] = std::max_element(vote.begin(), vote.end(), [](const auto& x, const auto& y) {
                 return x.second < y.second;
               })->first;
    dist[v] = 0.0;
    heap.push({0.0, v});
  }
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > dist[v]) continue;
    for (int k = adj.start[v]; k < adj.start[v + 1]; ++k) {
      const int w = adj.adj[k];
      const double next = d + graph.length(adj.edge[k]);
      if (labels(w) == labels(v) && next < dist[w]) {
        dist[w] = next;
        other[w] = other[v];
        heap.push({next, w});
      }
    }
  }
}

// Random walker (Grady 2006) on the graph: the vertices with seed ≥ 0 are fixed to their label;
// returns #V×q, row v = the probability that a walk from v first reaches a seed of each label
// (seeds: their own label with probability 1). Walks follow the affinities, so the probabilities
// change fastest across concave creases. One sparse Cholesky factorisation of the free vertices'
// Laplacian, q right-hand sides. A free patch that touches no seed keeps all-zero rows.
Eigen::MatrixXd random_walker(const MeshGraph& graph, const Eigen::VectorXi& labels,
                              const std::vector<int>& seed, int q) {
  const int n = graph.num_vertices;
  std::vector<int> index(n, -1);
  int m = 0;
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0 && seed[v] < 0) index[v] = m++;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(n, q);
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0 && seed[v] >= 0) P(v, seed[v]) = 1.0;
  if (m == 0) return P;
  std::vector<Eigen::Triplet<double>> t;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(m, q);
  Eigen::VectorXd degree = Eigen::VectorXd::Zero(m);
  for (int e = 0; e < graph.num_edges(); ++e) {
    const int a = graph.from(e), b = graph.to(e);
    if (labels(a) < 0 || labels(b) < 0) continue;
    const int ia = index[a], ib = index[b];
    if (ia < 0 && ib < 0) continue;
    const double w = graph.affinity(e);
    if (ia >= 0) degree(ia) += w;
    if (ib >= 0) degree(ib) += w;
    if (ia >= 0 && ib >= 0) {
      t.emplace_back(ia, ib, -w);
      t.emplace_back(ib, ia, -w);
    } else if (ia >= 0) {
      B(ia, seed[b]) += w;
    } else {
      B(ib, seed[a]) += w;
    }
  }
  // A relative 1e-9 on the diagonal keeps a free patch without seeds (all-zero right-hand side)
  // solvable; it changes the probabilities by about as much.
  for (int i = 0; i < m; ++i) t.emplace_back(i, i, degree(i) * (1 + 1e-9) + 1e-300);
  Eigen::SparseMatrix<double> L(m, m);
  L.setFromTriplets(t.begin(), t.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  if (solver.info() != Eigen::Success) return P;  // cannot happen for a positive diagonal
  const Eigen::MatrixXd X = solver.solve(B);
  for (int v = 0; v < n; ++v)
    if (index[v] >= 0) P.row(v) = X.row(index[v]);
  return P;
}

}  // namespace

int refine_boundaries_random_walker(const MeshGraph& graph, const Adjacency& adj,
                                    const Eigen::MatrixX3d& V, double band,
                                    Eigen::VectorXi& labels) {
  const int n = graph.num_vertices;
  const int q = labels.size() ? labels.maxCoeff() + 1 : 0;
  if (q < 2 || !(band > 0)) return 0;
  std::vector<double> dist;
  std::vector<int> other;
  distance_to_boundary(graph, adj, labels, dist, other);
  // Radius of each junction (pair of labels a < b): mean distance of the boundary vertices of the
  // pair from their centroid (r for a circular loop).
  const auto pair = [q](int a, int b) { return std::min(a, b) * q + std::max(a, b); };
  Eigen::MatrixXd centre = Eigen::MatrixXd::Zero(q * q, 3);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(q * q), radius = Eigen::VectorXd::Zero(q * q);
  for (int v = 0; v < n; ++v)
    if (dist[v] == 0.0)
      centre.row(pair(labels(v), other[v])) += V.row(v), ++count(pair(labels(v), other[v]));
  for (int p = 0; p < q * q; ++p)
    if (count(p) > 0) centre.row(p) /= count(p);
  for (int v = 0; v < n; ++v)
    if (dist[v] == 0.0)
      radius(pair(labels(v), other[v])) +=
          (V.row(v) - centre.row(pair(labels(v), other[v]))).norm();
  for (int p = 0; p < q * q; ++p)
    if (count(p) > 0) radius(p) /= count(p);
  // Depth of each label: its largest distance to a boundary. The band never takes more than half
  // of it, so that every label keeps seeds.
  std::vector<double> depth(q, 0.0);
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0 && std::isfinite(dist[v]))
      depth[labels(v)] = std::max(depth[labels(v)], dist[v]);
  std::vector<int> seed(n, -1);
  for (int v = 0; v < n; ++v) {
    if (labels(v) < 0) continue;
    const bool free = other[v] >= 0 && dist[v] < band * radius(pair(labels(v), other[v])) &&
                      dist[v] < 0.5 * depth[labels(v)];
    if (!free) seed[v] = labels(v);
  }
  const Eigen::MatrixXd P = random_walker(graph, labels, seed, q);
  int changed = 0;
  for (int v = 0; v < n; ++v) {
    if (labels(v) < 0 || seed[v] >= 0) continue;
    Eigen::Index best = 0;
    if (P.row(v).maxCoeff(&best) > 1e-6 && best != labels(v)) {
      labels(v) = static_cast<int>(best);
      ++changed;
    }
  }
  return changed;
}

int reshape_limb_cuts(const MeshGraph& graph, const Adjacency& adj, double tip_fraction,
                      Eigen::VectorXi& labels, const std::vector<int>& mirror) {
  const int n = graph.num_vertices;
  const int q = labels.size() ? labels.maxCoeff() + 1 : 0;
  if (q < 2 || !(tip_fraction > 0)) return 0;
  Eigen::MatrixXd cut;
  Eigen::VectorXd volume;
  part_graph(graph, labels, q, cut, volume);
  // The hub: a part that touches every other part, and of those the one sharing the most affinity
  // with the others (two trouser legs that touch at the crotch touch every other part too, along a
  // few edges); with two parts, the larger by volume.
  int hub = -1;
  for (int a = 0; a < q; ++a) {
    bool all = true;
    for (int b = 0; b < q; ++b) all = all && (a == b || cut(a, b) > 0);
    if (all && (hub < 0 || cut.row(a).sum() > cut.row(hub).sum())) hub = a;
  }
  if (q == 2) hub = volume(0) >= volume(1) ? 0 : 1;
  if (hub < 0) return 0;
  std::vector<double> dist;
  std::vector<int> other;
  distance_to_boundary(graph, adj, labels, dist, other);
  std::vector<double> depth(q, 0.0);
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0 && std::isfinite(dist[v]))
      depth[labels(v)] = std::max(depth[labels(v)], dist[v]);
  // Mirror limb of each label: the label most mirror images of its vertices carry (pairs that
  // choose each other only).
  std::vector<int> twin(q, -1);
  if (!mirror.empty()) {
    Eigen::MatrixXi votes = Eigen::MatrixXi::Zero(q, q);
    for (int v = 0; v < n; ++v)
      if (labels(v) >= 0 && mirror[v] >= 0 && labels(mirror[v]) >= 0)
        ++votes(labels(v), labels(mirror[v]));
    for (int l = 0; l < q; ++l) {
      Eigen::Index best = 0;
      if (votes.row(l).maxCoeff(&best) > 0) twin[l] = static_cast<int>(best);
    }
    for (int l = 0; l < q; ++l)
      if (twin[l] >= 0 && twin[twin[l]] != l) twin[l] = -1;
  }
  // Seeds: each part's far end (a limb's tip, the hub's core), from tip_fraction of its depth on.
  std::vector<int> seed(n, -1);
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0 && std::isfinite(dist[v]) && dist[v] >= tip_fraction * depth[labels(v)])
      seed[v] = labels(v);
  Eigen::MatrixXd P = random_walker(graph, labels, seed, q);
  if (!mirror.empty()) {
    const Eigen::MatrixXd own = P;
    for (int v = 0; v < n; ++v) {
      if (labels(v) < 0 || mirror[v] < 0 || labels(mirror[v]) < 0) continue;
      for (int l = 0; l < q; ++l)
        if (twin[l] >= 0) P(v, l) = 0.5 * (own(v, l) + own(mirror[v], twin[l]));
    }
  }
  // Level of each limb's cut: the mean of its field over the vertices on the limb–hub boundary
  // (both sides).
  Eigen::VectorXd level = Eigen::VectorXd::Zero(q), count = Eigen::VectorXd::Zero(q);
  for (int e = 0; e < graph.num_edges(); ++e) {
    const int i = graph.from(e), j = graph.to(e), a = labels(i), b = labels(j);
    if (a < 0 || b < 0 || a == b || (a != hub && b != hub)) continue;
    const int limb = a == hub ? b : a;
    level(limb) += P(i, limb) + P(j, limb);
    count(limb) += 2;
  }
  for (int l = 0; l < q; ++l)
    if (count(l) > 0) level(l) /= count(l);
  // Limbs that touch each other (two trouser legs at the crotch): both cuts are the isoline
  // through the crotch, the vertex where the two fields balance highest (the largest
  // min(u_a, u_b)), instead of the mean level of the current cuts. The legs then start at the
  // crotch, and their cuts rise from it towards the outer hips as the fields do.
  for (int a = 0; a < q; ++a)
    for (int b = a + 1; b < q; ++b) {
      if (a == hub || b == hub || !(cut(a, b) > 0)) continue;
      double crotch = 0;
      for (int v = 0; v < n; ++v)
        if (labels(v) >= 0) crotch = std::max(crotch, std::min(P(v, a), P(v, b)));
      if (crotch > 0) level(a) = level(b) = crotch;
    }
  const Eigen::VectorXd own_level = level;
  for (int l = 0; l < q; ++l)
    if (twin[l] >= 0 && twin[l] != l && l != hub && twin[l] != hub)
      level(l) = 0.5 * (own_level(l) + own_level(twin[l]));
  // A vertex belongs to the limb whose field, relative to that limb's cut level, is highest, if
  // it is at or above the level; otherwise to the hub.
  Eigen::VectorXi out = labels;
  int changed = 0;
  for (int v = 0; v < n; ++v) {
    if (labels(v) < 0 || seed[v] >= 0) continue;
    int best = hub;
    double best_ratio = 1.0;
    for (int l = 0; l < q; ++l) {
      if (l == hub || !(level(l) > 0)) continue;
      const double ratio = P(v, l) / level(l);
      if (ratio >= best_ratio) best_ratio = ratio, best = l;
    }
    changed += best != labels(v);
    out(v) = best;
  }
  labels = out;
  return changed;
}

Eigen::VectorXd part_elongation(const MeshGraph& graph, const Adjacency& adj,
                                const Eigen::MatrixX3d& V, const Eigen::VectorXi& labels) {
  const int q = labels.size() ? labels.maxCoeff() + 1 : 0;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(std::max(q, 0));
  if (q < 2) return out;
  std::vector<double> dist;
  std::vector<int> other;
  distance_to_boundary(graph, adj, labels, dist, other);
  Eigen::MatrixX3d centre = Eigen::MatrixX3d::Zero(q, 3);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(q), radius = Eigen::VectorXd::Zero(q),
                  depth = Eigen::VectorXd::Zero(q);
  for (int v = 0; v < graph.num_vertices; ++v) {
    if (labels(v) < 0 || !std::isfinite(dist[v])) continue;
    depth(labels(v)) = std::max(depth(labels(v)), dist[v]);
    if (dist[v] == 0.0) centre.row(labels(v)) += V.row(v), ++count(labels(v));
  }
  for (int l = 0; l < q; ++l)
    if (count(l) > 0) centre.row(l) /= count(l);
  for (int v = 0; v < graph.num_vertices; ++v)
    if (labels(v) >= 0 && dist[v] == 0.0)
      radius(labels(v)) += (V.row(v) - centre.row(labels(v))).norm();
  for (int l = 0; l < q; ++l)
    if (count(l) > 0 && radius(l) > 0) out(l) = depth(l) / (radius(l) / count(l));
  return out;
}

std::vector<int> mirror_vertices(const Eigen::MatrixX3d& V, const Eigen::VectorXd& area,
                                 const std::vector<int>& vertices, const Eigen::Vector3d& normal,
                                 double tolerance, double share) {
  if (vertices.empty() || !(tolerance > 0) || !(normal.norm() > 0)) return {};
  const Eigen::Vector3d nrm = normal.normalized();
  double total = 0, offset = 0;
  for (int v : vertices) total += area(v), offset += area(v) * V.row(v).dot(nrm);
  offset = total > 0 ? offset / total : 0.0;
  // Hash grid of cell `tolerance`: the nearest vertex within it lies in the 27 cells around.
  auto cell = [&](const Eigen::Vector3d& p) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(p.x() / tolerance)),
                                    static_cast<long long>(std::floor(p.y() / tolerance)),
                                    static_cast<long long>(std::floor(p.z() / tolerance))};
  };
  struct CellHash {
    size_t operator()(const std::array<long long, 3>& c) const {
      return static_cast<size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<long long, 3>, std::vector<int>, CellHash> grid;
  grid.reserve(vertices.size());
  for (int v : vertices) grid[cell(V.row(v).transpose())].push_back(v);
  std::vector<int> mirror(V.rows(), -1);
  // Stop as soon as too many vertices lack a mirror vertex.
  const double allowed_misses = (1.0 - share) * static_cast<double>(vertices.size());
  int missed = 0;
  // Every 16th vertex first: a mesh that is not symmetric is found out after a few of them.
  std::vector<int> order;
  order.reserve(vertices.size());
  for (int start = 0; start < 16; ++start)
    for (size_t k = start; k < vertices.size(); k += 16) order.push_back(vertices[k]);
  const size_t sample = (vertices.size() + 15) / 16;  // the first stride
  for (size_t i = 0; i < order.size(); ++i) {
    const int v = order[i];
    const Eigen::Vector3d p = V.row(v).transpose();
    const Eigen::Vector3d image = p - 2 * (p.dot(nrm) - offset) * nrm;
    const auto c = cell(image);
    double best = tolerance;
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (int w : it->second) {
            const double d = (V.row(w).transpose() - image).norm();
            if (d < best) best = d, mirror[v] = w;
          }
        }
    if (mirror[v] < 0 && ++missed > allowed_misses) return {};
    // The first stride is a sample of the whole: twice the allowed share of misses there is enough.
    if (i + 1 == sample && missed > 2 * (1.0 - share) * static_cast<double>(sample)) return {};
  }
  return mirror;
}

}  // namespace dresskit::segmentation
