#include "dresskit/mesh/names.h"
#include "dresskit/segmentation/graph.h"

#include "dresskit/mesh/union_find.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "dresskit/mesh/errors.h"

using namespace dresskit::mesh;

namespace dresskit::segmentation {

const NameTable<AffinityKind> kAffinities = {{"dihedral", AffinityKind::dihedral},
    {"edge-length", AffinityKind::edge_length}, {"edge_length", AffinityKind::edge_length},
    {"cotangent", AffinityKind::cotangent}};
AffinityKind parse_affinity(const std::string& text) { return parse_name(text, kAffinities, "affinity"); }
std::string to_string(AffinityKind kind) { return name_of(kind, kAffinities); }

namespace {

struct HalfEdge {
  long long key;  // from * n + to with from < to
  int face, opposite;
};

// Unit normal and centroid of a face; a zero normal for a degenerate face.
Eigen::Vector3d face_normal(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int f) {
  const Eigen::Vector3d n =
      (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0))).transpose();
  const double norm = n.norm();
  return norm > 0 && std::isfinite(norm) ? Eigen::Vector3d(n / norm) : Eigen::Vector3d::Zero();
}

}  // namespace

MeshGraph build_mesh_graph(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                           const AffinityOptions& options) {
  const long long n = V.rows();
  std::vector<HalfEdge> half;
  half.reserve(3 * static_cast<size_t>(F.rows()));
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const long long a = F(f, c), b = F(f, (c + 1) % 3);
      if (a != b)  // a face with a repeated corner has no edge there
        half.push_back({std::min(a, b) * n + std::max(a, b), f, F(f, (c + 2) % 3)});
    }
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.key != y.key ? x.key < y.key : x.face < y.face;
  });

  // One row per undirected edge: the range of its half-edges in `half`.
  std::vector<size_t> first;
  for (size_t h = 0; h < half.size(); ++h)
    if (h == 0 || half[h].key != half[h - 1].key) first.push_back(h);
  first.push_back(half.size());
  const int m = static_cast<int>(first.size()) - 1;

  MeshGraph g;
  g.num_vertices = static_cast<int>(n);
  g.from.resize(m);
  g.to.resize(m);
  g.length.resize(m);
  g.faces.resize(m);
  g.affinity.resize(m);
  Eigen::VectorXd angular = Eigen::VectorXd::Zero(m), base = Eigen::VectorXd::Ones(m);
  for (int e = 0; e < m; ++e) {
    const size_t h0 = first[e], h1 = first[e + 1];
    const int i = static_cast<int>(half[h0].key / n), j = static_cast<int>(half[h0].key % n);
    g.from(e) = i;
    g.to(e) = j;
    g.length(e) = (V.row(i) - V.row(j)).norm();
    g.faces(e) = static_cast<int>(h1 - h0);
    if (options.kind == AffinityKind::cotangent) {
      double cot = 0.0;
      for (size_t h = h0; h < h1; ++h) {
        const Eigen::Vector3d a = (V.row(i) - V.row(half[h].opposite)).transpose();
        const Eigen::Vector3d b = (V.row(j) - V.row(half[h].opposite)).transpose();
        const double s = a.cross(b).norm();
        if (s > 0) cot += 0.5 * a.dot(b) / s;
      }
      base(e) = cot;
    }
    if (h1 - h0 == 2) {  // a manifold interior edge: the angular distance of its two faces
      const int f1 = half[h0].face, f2 = half[h0 + 1].face;
      const Eigen::Vector3d n1 = face_normal(V, F, f1), n2 = face_normal(V, F, f2);
      if (n1.squaredNorm() > 0 && n2.squaredNorm() > 0) {
        // Convex when the second face's far corner lies behind the first face's plane.
        const Eigen::Vector3d d = (V.row(half[h0 + 1].opposite) - V.row(i)).transpose();
        const bool convex = n1.dot(d) <= 0;
        angular(e) =
            (convex ? options.convex_weight : 1.0) * (1.0 - std::clamp(n1.dot(n2), -1.0, 1.0));
      }
    }
  }
  if (options.kind == AffinityKind::edge_length && m > 0) {
    const double mean = g.length.mean();
    for (int e = 0; e < m; ++e) base(e) = g.length(e) > 0 ? mean / g.length(e) : 1.0;
  }
  if (options.kind == AffinityKind::cotangent && m > 0) {
    // Obtuse triangles give negative weights; a small positive floor keeps W a valid affinity.
    const double floor = 1e-3 * std::max(base.cwiseAbs().mean(), 1e-12);
    for (int e = 0; e < m; ++e) base(e) = std::isfinite(base(e)) ? std::max(base(e), floor) : floor;
  }
  const double mean_angular = m > 0 ? angular.mean() : 0.0;
  for (int e = 0; e < m; ++e)
    g.affinity(e) = base(e) * (mean_angular > 0 ? std::exp(-angular(e) / mean_angular) : 1.0);
  return g;
}

int bridge_boundary_gaps(const Eigen::MatrixX3d& V, double max_distance, int min_hops,
                         MeshGraph& graph) {
  std::vector<int> boundary;
  std::vector<char> on_boundary(graph.num_vertices, 0);
  for (int e = 0; e < graph.num_edges(); ++e)
    if (graph.faces(e) == 1) on_boundary[graph.from(e)] = on_boundary[graph.to(e)] = 1;
  for (int v = 0; v < graph.num_vertices; ++v)
    if (on_boundary[v]) boundary.push_back(v);
  if (boundary.empty() || !(max_distance > 0)) return 0;
  Eigen::VectorXi component;
  connected_components(graph, component);
  const Adjacency adj = adjacency(graph);
  // Vertices within min_hops of v (breadth-first, depth-limited).
  std::vector<int> depth(graph.num_vertices, -1), touched;
  auto near_on_graph = [&](int v) {
    for (int t : touched) depth[t] = -1;
    touched.assign(1, v);
    depth[v] = 0;
    for (size_t k = 0; k < touched.size(); ++k) {
      const int u = touched[k];
      if (depth[u] == min_hops) continue;
      for (int a = adj.start[u]; a < adj.start[u + 1]; ++a)
        if (depth[adj.adj[a]] < 0) depth[adj.adj[a]] = depth[u] + 1, touched.push_back(adj.adj[a]);
    }
  };
  // Boundary vertices sorted along x: candidates of v lie within max_distance in x.
  std::sort(boundary.begin(), boundary.end(), [&](int a, int b) { return V(a, 0) < V(b, 0); });
  std::vector<std::pair<int, int>> added;
  for (size_t i = 0; i < boundary.size(); ++i) {
    const int v = boundary[i];
    bool searched = false;
    for (size_t j = i + 1; j < boundary.size() && V(boundary[j], 0) - V(v, 0) < max_distance; ++j) {
      const int w = boundary[j];
      if (component(v) != component(w) || (V.row(v) - V.row(w)).norm() >= max_distance) continue;
      if (!searched) near_on_graph(v), searched = true;
      if (depth[w] < 0) added.emplace_back(std::min(v, w), std::max(v, w));
    }
  }
  if (added.empty()) return 0;
  const int m = graph.num_edges(), extra = static_cast<int>(added.size());
  const double mean_affinity = graph.affinity.mean();
  for (Eigen::VectorXi* a : {&graph.from, &graph.to, &graph.faces})
    a->conservativeResize(m + extra);
  for (Eigen::VectorXd* a : {&graph.affinity, &graph.length}) a->conservativeResize(m + extra);
  for (int k = 0; k < extra; ++k) {
    graph.from(m + k) = added[k].first;
    graph.to(m + k) = added[k].second;
    graph.faces(m + k) = 0;  // no triangle: not a boundary edge, not an interior one
    graph.affinity(m + k) = mean_affinity;
    graph.length(m + k) = (V.row(added[k].first) - V.row(added[k].second)).norm();
  }
  return extra;
}

Eigen::SparseMatrix<double> affinity_matrix(const MeshGraph& graph) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(2 * graph.num_edges());
  for (int e = 0; e < graph.num_edges(); ++e) {
    t.emplace_back(graph.from(e), graph.to(e), graph.affinity(e));
    t.emplace_back(graph.to(e), graph.from(e), graph.affinity(e));
  }
  Eigen::SparseMatrix<double> W(graph.num_vertices, graph.num_vertices);
  W.setFromTriplets(t.begin(), t.end());
  return W;
}

int connected_components(const MeshGraph& graph, Eigen::VectorXi& component) {
  UnionFind sets(graph.num_vertices);
  for (int e = 0; e < graph.num_edges(); ++e) sets.unite(graph.from(e), graph.to(e));
  component.setConstant(graph.num_vertices, -1);
  std::vector<int> index(graph.num_vertices, -1);
  int count = 0;
  for (int v = 0; v < graph.num_vertices; ++v) {
    const int root = sets.find(v);
    if (index[root] < 0) index[root] = count++;
    component(v) = index[root];
  }
  return count;
}

double normalized_cut(const MeshGraph& graph, const Eigen::VectorXi& labels) {
  const int k = labels.size() ? labels.maxCoeff() + 1 : 0;
  std::vector<double> cut(std::max(k, 0), 0.0), volume(std::max(k, 0), 0.0);
  for (int e = 0; e < graph.num_edges(); ++e) {
    const int a = labels(graph.from(e)), b = labels(graph.to(e));
    if (a < 0 || b < 0) continue;
    volume[a] += graph.affinity(e);
    volume[b] += graph.affinity(e);
    if (a != b) cut[a] += graph.affinity(e), cut[b] += graph.affinity(e);
  }
  double ncut = 0.0;
  for (int l = 0; l < k; ++l)
    if (volume[l] > 0) ncut += cut[l] / volume[l];
  return ncut;
}

Adjacency adjacency(const MeshGraph& graph) {
  Adjacency a;
  a.start.assign(graph.num_vertices + 1, 0);
  for (int e = 0; e < graph.num_edges(); ++e) {
    ++a.start[graph.from(e) + 1];
    ++a.start[graph.to(e) + 1];
  }
  std::partial_sum(a.start.begin(), a.start.end(), a.start.begin());
  a.adj.resize(a.start.back());
  a.edge.resize(a.start.back());
  std::vector<int> fill(a.start.begin(), a.start.end() - 1);
  for (int e = 0; e < graph.num_edges(); ++e) {
    const int i = graph.from(e), j = graph.to(e);
    a.adj[fill[i]] = j;
    a.edge[fill[i]++] = e;
    a.adj[fill[j]] = i;
    a.edge[fill[j]++] = e;
  }
  return a;
}

Eigen::VectorXd vertex_areas(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(V.rows());
  for (int f = 0; f < F.rows(); ++f) {
    const double a =
        0.5 * (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0))).norm();
    for (int c = 0; c < 3; ++c) area(F(f, c)) += a / 3.0;
  }
  return area;
}

}  // namespace dresskit::segmentation
