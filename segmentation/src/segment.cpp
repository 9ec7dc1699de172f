// The stateful part of segmentation: phases in order (graph, eigenpairs per component, number of
// parts, k-means, clean-up, naming), each a pure kernel from the other files.
#include "dresskit/segmentation/segment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "dresskit/mesh/errors.h"
#include "dresskit/segmentation/label_cleanup.h"
#include "dresskit/segmentation/naming.h"
#include "dresskit/segmentation/skirt.h"

using namespace dresskit::mesh;

namespace dresskit::segmentation {

std::vector<std::string> SegmentationResult::part_names() const {
  std::vector<std::string> names;
  for (const auto& p : parts) names.push_back(p.name);
  return names;
}

namespace {

// Rows of eigenvectors 1..dims, each scaled by 1/√λ (low frequencies weigh more), put on the unit
// sphere (Ng, Jordan & Weiss) so that k-means sees directions from the hub, not distances.
Eigen::MatrixXd spectral_embedding(const EigenResult& eigen, int dims) {
  Eigen::MatrixXd Y = eigen.vectors.middleCols(1, dims);
  for (int k = 0; k < dims; ++k) Y.col(k) /= std::sqrt(std::max(eigen.values(k + 1), 1e-300));
  for (int i = 0; i < Y.rows(); ++i) {
    const double norm = Y.row(i).norm();
    if (norm > 0) Y.row(i) /= norm;
  }
  return Y;
}

void clean_up(const MeshGraph& graph, const Adjacency& adj, const Eigen::VectorXd& area,
              int smoothing, Eigen::VectorXi& labels) {
  merge_orphan_patches(graph, adj, area, labels);
  smooth_label_boundaries(graph, adj, smoothing, labels);
  merge_orphan_patches(graph, adj, area, labels);
}

// Renumbers the labels ≥ 0 to 0..m−1 in order of their value (a cluster may have vanished).
void compact_labels(Eigen::VectorXi& labels) {
  std::map<int, int> index;
  for (int i = 0; i < labels.size(); ++i)
    if (labels(i) >= 0) index.emplace(labels(i), 0);
  int next = 0;
  for (auto& [label, k] : index) k = next++;
  for (int i = 0; i < labels.size(); ++i)
    if (labels(i) >= 0) labels(i) = index[labels(i)];
}

// Labels in a fixed order of names within each component (torso, head, arm_left, …, body,
// sleeve_left, …), so that a part has the same label, and colour, from mesh to mesh.
void order_parts(std::vector<NamedPart>& parts, Eigen::VectorXi& labels) {
  static const std::vector<std::string> order = {
      "torso",       "head",         "arm_left", "arm_right",   "leg_left",   "leg_right",  "body",
      "sleeve_left", "sleeve_right", "skirt",    "skirt_waist", "skirt_left", "skirt_right"};
  auto rank = [&](const NamedPart& p) {
    const auto it = std::find(order.begin(), order.end(), p.name);
    return std::make_tuple(p.component, static_cast<int>(it - order.begin()), p.name);
  };
  std::vector<int> by(parts.size());
  for (size_t k = 0; k < by.size(); ++k) by[k] = static_cast<int>(k);
  std::stable_sort(by.begin(), by.end(),
                   [&](int a, int b) { return rank(parts[a]) < rank(parts[b]); });
  std::vector<int> new_label(parts.size());
  std::vector<NamedPart> sorted;
  for (size_t k = 0; k < by.size(); ++k)
    new_label[by[k]] = static_cast<int>(k), sorted.push_back(parts[by[k]]);
  parts = sorted;
  for (int i = 0; i < labels.size(); ++i)
    if (labels(i) >= 0) labels(i) = new_label[labels(i)];
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Component {
  std::vector<int> vertices;  // mesh vertex indices
  EigenResult eigen;
  int parts = 0;
  SkirtFrame skirt;    // skirt.is_skirt: a tube with two openings (detect_skirt)
  bool split = false;  // cut by split_skirt into three parts, not by the spectrum
  bool closed = true;  // no boundary edge (a body, not a garment)
};

// The affinity matrix restricted to one component's vertices.
Eigen::SparseMatrix<double> sub_affinity(const MeshGraph& g, const std::vector<int>& local,
                                         const Eigen::VectorXi& component, int c, int n) {
  std::vector<Eigen::Triplet<double>> t;
  for (int e = 0; e < g.num_edges(); ++e) {
    if (component(g.from(e)) != c) continue;
    const int i = local[g.from(e)], j = local[g.to(e)];
    t.emplace_back(i, j, g.affinity(e));
    t.emplace_back(j, i, g.affinity(e));
  }
  Eigen::SparseMatrix<double> W(n, n);
  W.setFromTriplets(t.begin(), t.end());
  return W;
}

// Names of a split skirt's parts: the one highest along the skirt's axis is the waist band, the
// others its left and right halves along the skirt's left; confidence of the halves: the lateral
// share of the distance between their centroids.
void name_skirt_parts(const Eigen::MatrixX3d& V, const Eigen::VectorXd& area,
                      const Eigen::VectorXi& labels, int component, const SkirtFrame& frame,
                      std::vector<NamedPart>& parts) {
  std::vector<int> ls;
  for (int l = 0; l < static_cast<int>(parts.size()); ++l)
    if (parts[l].component == component) ls.push_back(l);
  if (ls.empty()) return;
  std::map<int, Eigen::Vector3d> centroid;
  std::map<int, double> weight;
  for (int v = 0; v < labels.size(); ++v) {
    if (labels(v) < 0 || parts[labels(v)].component != component) continue;
    auto [it, fresh] = centroid.emplace(labels(v), Eigen::Vector3d::Zero());
    it->second += area(v) * V.row(v).transpose();
    weight[labels(v)] += area(v);
  }
  for (auto& [l, c] : centroid)
    if (weight[l] > 0) c /= weight[l];
  std::sort(ls.begin(), ls.end(), [&](int a, int b) {
    return centroid[a].dot(frame.axis) > centroid[b].dot(frame.axis);
  });
  parts[ls[0]].name = "skirt_waist";
  parts[ls[0]].confidence = 1.0;
  std::vector<int> halves(ls.begin() + 1, ls.end());
  std::sort(halves.begin(), halves.end(), [&](int a, int b) {
    return centroid[a].dot(frame.left) > centroid[b].dot(frame.left);
  });
  double lateral = 0.5;
  if (halves.size() == 2) {
    const Eigen::Vector3d d = centroid[halves[0]] - centroid[halves[1]];
    lateral = d.norm() > 0 ? std::clamp(std::abs(d.dot(frame.left)) / d.norm(), 0.0, 1.0) : 0.0;
  }
  for (size_t k = 0; k < halves.size(); ++k) {
    parts[halves[k]].name = k == 0 ? "skirt_left" : k == 1 ? "skirt_right" : "skirt_part";
    parts[halves[k]].confidence = lateral;
  }
}

// Number of parts per component from the union of the spectra: every component takes its zero
// eigenvalue, the other K − C parts go to the smallest remaining eigenvalues. Automatic K: the
// largest ratio λ_K / λ_{K−1} of the sorted union. Skirts that are split take three parts each and
// no part of the spectrum (their eigenpairs are not computed).
int choose_parts(std::vector<Component>& comps, const SegmentationOptions& o,
                 SegmentationResult& r) {
  struct Entry {
    double value;
    int comp, index;
  };
  std::vector<Entry> rest;
  std::vector<double> all;
  int fixed = 0, C = 0;  // parts of the split skirts; components cut by the spectrum
  for (int c = 0; c < static_cast<int>(comps.size()); ++c) {
    if (comps[c].split) {
      comps[c].parts = 3;
      fixed += 3;
      continue;
    }
    ++C;
    comps[c].parts = 1;
    for (int k = 0; k < comps[c].eigen.values.size(); ++k) {
      all.push_back(k == 0 ? 0.0 : comps[c].eigen.values(k));
      if (k > 0) rest.push_back({comps[c].eigen.values(k), c, k});
    }
  }
  std::sort(all.begin(), all.end());
  std::sort(rest.begin(), rest.end(), [](const Entry& a, const Entry& b) {
    return a.value != b.value ? a.value < b.value
           : a.comp != b.comp ? a.comp < b.comp
                              : a.index < b.index;
  });
  r.spectrum = Eigen::Map<Eigen::VectorXd>(all.data(), static_cast<Eigen::Index>(all.size()));
  const int total = static_cast<int>(all.size());
  auto gap = [&](int K) { return K < total && all[K - 1] > 0 ? all[K] / all[K - 1] : 0.0; };
  int K = o.parts - fixed;
  if (o.parts == 0) {
    K = C;
    double best = 0;
    for (int k = C + 1; k <= std::min(std::max(o.max_parts - fixed, C), total - 1); ++k)
      if (gap(k) > best) best = gap(k), K = k;
  }
  K = std::min(K, total);
  r.eigengap = C > 0 ? gap(K) : 0.0;
  for (int k = 0; k < K - C; ++k) ++comps[rest[k].comp].parts;
  return K + fixed;
}

}  // namespace

SegmentationResult segment_mesh(const TriangleMesh& mesh, const SegmentationOptions& o) {
  const auto start = Clock::now();
  validate_mesh(mesh, "mesh");
  if (o.parts < 0)
    throw InputError("parts: " + std::to_string(o.parts) +
                     " (must be at least 1, or 0 for automatic)");
  // The eigen-solver needs about 2·K vectors of #V numbers: K in the hundreds is not segmentation
  // into parts any more and would take minutes and gigabytes.
  if (o.parts > kMaxParts || o.max_parts > kMaxParts)
    throw InputError("parts: " + std::to_string(std::max(o.parts, o.max_parts)) + " is more than " +
                     std::to_string(kMaxParts) + ", the most this segmentation handles");
  if (o.max_parts < 1)
    throw InputError("max_parts: " + std::to_string(o.max_parts) + " (must be at least 1)");
  if (!(o.boundary_band >= 0))
    throw InputError("boundary_band: " + std::to_string(o.boundary_band) + " (must be 0 or more)");
  if (!(o.limb_tip_fraction >= 0 && o.limb_tip_fraction < 1))
    throw InputError("limb_tip_fraction: " + std::to_string(o.limb_tip_fraction) +
                     " (must be at least 0 and less than 1)");
  if (!(o.over_segmentation >= 0 && o.over_segmentation <= kMaxParts))
    throw InputError("over_segmentation: " + std::to_string(o.over_segmentation) + " (must be 0 to " +
                     std::to_string(kMaxParts) + ")");
  if (!(o.symmetry_tolerance >= 0 && std::isfinite(o.symmetry_tolerance)))
    throw InputError("symmetry_tolerance: " + std::to_string(o.symmetry_tolerance) + " (must be 0 or more)");
  if (!(o.bridge_gaps >= 0 && std::isfinite(o.bridge_gaps)))
    throw InputError("bridge_gaps: " + std::to_string(o.bridge_gaps) + " (must be 0 or more)");
  if (o.smoothing_iterations < 0)
    throw InputError("smoothing_iterations: " + std::to_string(o.smoothing_iterations) + " (must be 0 or more)");
  if (o.eigen.ncv < 0 || o.eigen.ncv > mesh.num_vertices())
    throw InputError("ncv: " + std::to_string(o.eigen.ncv) + " (must be 0 for automatic, or at most the " +
                     std::to_string(mesh.num_vertices()) + " vertices)");
  if (!(o.eigen.tolerance > 0 && o.eigen.tolerance < 1) || o.eigen.max_iterations <= 0)
    throw InputError("eigen-solver: tolerance must be in (0, 1) and iterations positive");
  SegmentationResult r;
  r.parts_automatic = o.parts == 0;
  const int n = mesh.num_vertices();

  auto t = Clock::now();
  MeshGraph graph = build_mesh_graph(mesh.V, mesh.F, o.affinity);
  if (o.bridge_gaps > 0 && graph.num_edges() > 0)
    r.bridged_edges = bridge_boundary_gaps(mesh.V, o.bridge_gaps * graph.length.mean(), 6, graph);
  const Eigen::VectorXd area = vertex_areas(mesh.V, mesh.F);
  Eigen::VectorXi component;
  const int raw_components = connected_components(graph, component);
  std::vector<bool> used(n, false);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) used[mesh.F(f, c)] = true;
  // Components with faces, renumbered; isolated vertices get −1 (documented fallback).
  std::vector<int> renumber(raw_components, -1);
  std::vector<Component> comps;
  std::vector<int> local(n, -1);
  for (int v = 0; v < n; ++v) {
    if (!used[v]) {
      ++r.isolated_vertices;
      component(v) = -1;
      continue;
    }
    int& c = renumber[component(v)];
    if (c < 0) c = static_cast<int>(comps.size()), comps.emplace_back();
    component(v) = c;
    local[v] = static_cast<int>(comps[c].vertices.size());
    comps[c].vertices.push_back(v);
  }
  const int C = static_cast<int>(comps.size());
  const int usable = n - r.isolated_vertices;
  r.components = C;
  if (o.parts > usable)
    throw InputError("parts: " + std::to_string(o.parts) + " is more than the " +
                     std::to_string(usable) + " vertices of the mesh");
  if (o.parts > 0 && o.parts < C)
    throw InputError("parts: " + std::to_string(o.parts) + " is fewer than the " +
                     std::to_string(C) + " connected components (each needs at least one part)");
  for (int e = 0; e < graph.num_edges(); ++e)
    if (graph.faces(e) == 1 && component(graph.from(e)) >= 0)
      comps[component(graph.from(e))].closed = false;
  // Axes now: skirts are cut along them (their names come later).
  // Feet only on a body: a closed surface, where a garment is open (its hem is no foot).
  const bool closed = std::any_of(comps.begin(), comps.end(), [](const auto& c) { return c.closed; });
  r.axes = estimate_axes(mesh.V, area, o.up, o.forward, closed);
  if (o.split_skirts) {
    int skirts = 0;
    for (auto& comp : comps) {
      comp.skirt = detect_skirt(graph, mesh.V, area, comp.vertices, r.axes);
      skirts += comp.skirt.is_skirt;
    }
    // A given number of parts must leave every other component at least one.
    const bool room = o.parts == 0 || o.parts >= 3 * skirts + (C - skirts);
    for (auto& comp : comps) comp.split = comp.skirt.is_skirt && room;
  }
  r.seconds.graph = since(t);

  t = Clock::now();
  const int k_max = o.parts > 0 ? o.parts : std::max(o.max_parts, C);
  for (int c = 0; c < C; ++c) {
    if (comps[c].split) continue;  // cut by its geometry, not by the spectrum
    const int nc = static_cast<int>(comps[c].vertices.size());
    // One more than the most parts it can get (for the gap) and the over-segmentation.
    const int nev = std::min(nc, k_max - C + 2 + std::max(0, o.over_segmentation));
    const Eigen::SparseMatrix<double> L =
        graph_laplacian(sub_affinity(graph, local, component, c, nc), o.laplacian);
    comps[c].eigen = smallest_eigenpairs(L, nev, o.eigen);
    r.eigen_residual = std::max(r.eigen_residual, comps[c].eigen.residual);
    r.eigen_iterations += comps[c].eigen.iterations;
  }
  r.parts_chosen = choose_parts(comps, o, r);
  r.seconds.eigen = since(t);

  t = Clock::now();
  Eigen::VectorXi labels = Eigen::VectorXi::Constant(n, -1);
  std::vector<int> label_component;
  const Adjacency adj = adjacency(graph);
  // Boundaries: re-decided by a random walker in a band around each cut, then the limb cuts
  // reshaped along the harmonic field from the limb tips (docs/segmentation.md, "Boundaries").
  const double mean_edge = graph.num_edges() ? graph.length.mean() : 0.0;
  auto refine_cuts = [&](Eigen::VectorXi& own, const std::vector<int>& vertices) {
    if (o.boundary_band > 0) {
      r.refined_vertices +=
          refine_boundaries_random_walker(graph, adj, mesh.V, o.boundary_band, own);
      if (o.cleanup) clean_up(graph, adj, area, o.smoothing_iterations, own);
    }
    if (o.limb_tip_fraction > 0) {
      const std::vector<int> mirror = o.symmetry_tolerance > 0
                                          ? mirror_vertices(mesh.V, area, vertices, r.axes.left,
                                                            o.symmetry_tolerance * mean_edge)
                                          : std::vector<int>();
      r.refined_vertices += reshape_limb_cuts(graph, adj, o.limb_tip_fraction, own, mirror);
      if (o.cleanup) clean_up(graph, adj, area, o.smoothing_iterations, own);
    }
  };
  int total_parts = r.parts_chosen;
  for (int c = 0; c < C; ++c) {
    const Component& comp = comps[c];
    const int base = static_cast<int>(label_component.size());
    r.parts_per_component.push_back(comp.parts);
    for (int p = 0; p < comp.parts; ++p) label_component.push_back(c);
    if (comp.parts == 1) {
      for (int v : comp.vertices) labels(v) = base;
      continue;
    }
    if (comp.split) {  // a skirt: waist band and halves (docs/segmentation.md, "Skirts")
      Eigen::VectorXi own = Eigen::VectorXi::Constant(n, -1);
      SkirtFrame frame = comp.skirt;
      split_skirt(graph, mesh.V, area, comp.vertices, frame, own);
      // One patch per part, but no smoothing and no boundary steps: the cuts are a level line of
      // the height and a plane already, a skirt has neither creases nor narrow places for the
      // boundary steps to move them to, and smoothing would only hand the vertices on the plane
      // to one side by the triangulation's diagonals (docs/segmentation.md, "Skirts").
      if (o.cleanup) merge_orphan_patches(graph, adj, area, own);
      compact_labels(own);
      for (int v : comp.vertices) labels(v) = own(v) >= 0 ? base + own(v) : -1;
      r.skirt_components.push_back(c);
      r.skirt_band_fraction.push_back(frame.band_fraction);
      continue;
    }
    // Candidates: k-means with k, k + 1, …, k + over_segmentation clusters, each cleaned up and
    // merged back to k parts by structure (merge_parts_towards_star), until one is a star. A
    // candidate replaces the previous best only with more leaf parts (limbs hanging off a hub):
    // plain k-means wins ties. (The normalised cut is no tie-breaker: on the bodies it prefers
    // partitions that are worse against the truth.)
    struct Candidate {
      Eigen::VectorXi labels;
      int leaves = -1, clusters = 0, relabelled = 0;
      double ncut = 0, cost = 0;
    };
    // k-means with q clusters, cleaned up: kept, as the next number of parts tries it again.
    struct Clustering {
      Eigen::VectorXi raw, clean;
      double cost = 0;
    };
    std::map<int, Clustering> clusterings;
    auto clustering = [&](int q) -> const Clustering& {
      auto it = clusterings.find(q);
      if (it != clusterings.end()) return it->second;
      const KMeansResult km = kmeans(spectral_embedding(comp.eigen, q - 1), q, o.kmeans);
      Clustering k;
      k.raw = Eigen::VectorXi::Constant(n, -1);
      for (size_t i = 0; i < comp.vertices.size(); ++i) k.raw(comp.vertices[i]) = km.labels(i);
      k.clean = k.raw;
      if (o.cleanup) clean_up(graph, adj, area, o.smoothing_iterations, k.clean);
      compact_labels(k.clean);
      k.cost = km.cost;
      return clusterings.emplace(q, std::move(k)).first->second;
    };
    auto cluster = [&](int parts, int over) {
      Candidate best;
      for (int q = parts; q <= parts + std::max(0, over); ++q) {
        if (q > static_cast<int>(comp.vertices.size()) || q > comp.eigen.values.size()) break;
        const Clustering& km = clustering(q);
        const Eigen::VectorXi& raw = km.raw;
        Eigen::VectorXi own = km.clean;
        if (own.maxCoeff() + 1 > parts) {
          merge_parts_towards_star(graph, parts, own);
          if (o.cleanup) clean_up(graph, adj, area, o.smoothing_iterations, own);
          compact_labels(own);
        }
        const int leaf_parts = count_leaf_parts(graph, own);
        if (leaf_parts > best.leaves) {
          best.leaves = leaf_parts;
          best.ncut = normalized_cut(graph, own);
          best.labels = own;
          best.cost = km.cost;
          best.clusters = q;
          best.relabelled =
              q == parts ? static_cast<int>((own.array() != raw.array()).count()) : -1;
        }
        // A star (one hub, every other part a leaf) is as good as structure gets: stop there.
        if (best.leaves >= (parts == 2 ? 2 : parts - 1)) break;
      }
      return best;
    };
    int parts = comp.parts;
    Candidate chosen = cluster(parts, o.over_segmentation);
    // Automatic number of parts, closed surfaces (bodies) only: one more part is taken while the
    // result stays a star with one more limb that sticks out at least as far as its junction is
    // wide (part_elongation ≥ 1). The eigengap puts a body's head with the torso (the four limbs'
    // eigenvalues come first, then the gap); a sixth part then separates the head. On garments a
    // leaf can be a flap of the hub or a piece of hem: they are left to the eigengap. An attempt
    // tries one over-segmentation only (k + 1 and k + 2 clusters): the attempt that fails, at the
    // seventh part of a body, would otherwise run the costliest k-means (k + 3 clusters, 0.3 s on
    // the 24k-vertex body).
    while (o.parts == 0 && o.grow_limbs && comp.closed && chosen.leaves == parts - 1 &&
           parts >= 3 && total_parts + 1 <= o.max_parts) {
      const Candidate more = cluster(parts + 1, std::min(o.over_segmentation, 1));
      if (more.leaves != parts || more.labels.size() == 0 ||
          more.labels.maxCoeff() + 1 != parts + 1)
        break;
      const Eigen::VectorXd elongation = part_elongation(graph, adj, mesh.V, more.labels);
      Eigen::MatrixXd touching = Eigen::MatrixXd::Zero(parts + 1, parts + 1);
      for (int e = 0; e < graph.num_edges(); ++e) {
        const int a = more.labels(graph.from(e)), b = more.labels(graph.to(e));
        if (a >= 0 && b >= 0 && a != b) touching(a, b) = touching(b, a) = 1;
      }
      bool limbs = true;
      for (int l = 0; l <= parts; ++l)
        if (touching.row(l).sum() == 1 && elongation(l) < 1.0) limbs = false;
      if (!limbs) break;
      chosen = more;
      ++parts;
      ++total_parts;
      ++r.limbs_added;
    }
    Eigen::VectorXi best = chosen.labels;
    const double best_ncut = chosen.ncut;
    const int relabelled = chosen.relabelled;
    r.kmeans_cost = chosen.cost;
    r.clusters_before_merge = chosen.clusters;
    for (int p = comp.parts; p < parts; ++p) label_component.push_back(c);
    refine_cuts(best, comp.vertices);
    compact_labels(best);
    for (int v : comp.vertices) labels(v) = best(v) >= 0 ? base + best(v) : -1;
    r.normalized_cut += best_ncut;
    if (relabelled >= 0) r.relabelled_vertices += relabelled;
  }
  // Compact the labels (a k-means cluster or a patch may have vanished), keeping their order.
  std::vector<int> compact(label_component.size(), -1);
  std::vector<int> kept_component;
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0 && compact[labels(v)] < 0) compact[labels(v)] = 0;
  for (size_t l = 0; l < compact.size(); ++l)
    if (compact[l] == 0)
      compact[l] = static_cast<int>(kept_component.size()),
      kept_component.push_back(label_component[l]);
  for (int v = 0; v < n; ++v)
    if (labels(v) >= 0) labels(v) = compact[labels(v)];
  r.parts_per_component.assign(C, 0);
  for (int c : kept_component) ++r.parts_per_component[c];
  r.parts_chosen = static_cast<int>(kept_component.size());  // a k-means cluster can come out empty
  r.seconds.clustering = since(t);

  t = Clock::now();
  r.parts = name_parts(mesh.V, graph, area, labels, kept_component, r.axes);
  for (int c : r.skirt_components)
    name_skirt_parts(mesh.V, area, labels, c, comps[c].skirt, r.parts);
  order_parts(r.parts, labels);
  std::map<std::string, int> seen;  // names are unique in a mesh: body, body_2, …
  for (auto& p : r.parts)
    if (++seen[p.name] > 1) p.name += "_" + std::to_string(seen[p.name]);
  r.seconds.naming = since(t);

  r.vertex_labels = labels;
  r.face_labels = face_labels_from_vertices(mesh.F, labels);
  r.seconds.total = since(start);
  return r;
}

}  // namespace dresskit::segmentation
