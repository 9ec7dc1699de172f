#pragma once
// The vertex graph of a triangle mesh with affinities (pure kernels, no state). Layout: one row per
// undirected edge, arrays per attribute.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace dresskit::segmentation {

/// How an edge's affinity is made; every kind is multiplied by the dihedral (concavity) factor.
enum class AffinityKind {
  dihedral,     ///< 1 per edge: the graph's combinatorics plus the dihedral factor (default)
  edge_length,  ///< mean edge length / edge length
  cotangent,    ///< cotangent weight (clamped to a small positive value)
};
/// "dihedral", "edge-length", "cotangent"; throws InputError naming the value otherwise.
AffinityKind parse_affinity(const std::string& text);
std::string to_string(AffinityKind kind);

struct AffinityOptions {
  AffinityKind kind = AffinityKind::dihedral;
  /// η in the angular distance d = η (1 − cos θ) of two faces across an edge: convex edges get η,
  /// concave edges 1, so cuts prefer concave creases (armpits, groin, neck). Unitless, 0–1.
  double convex_weight = 0.1;
};

/// #E undirected edges of the mesh (i < j) with their affinities (> 0, unitless).
struct MeshGraph {
  Eigen::VectorXi from, to;  ///< #E endpoints, from < to
  Eigen::VectorXd affinity;  ///< #E affinity w_ij > 0
  Eigen::VectorXd length;    ///< #E edge length [m]
  Eigen::VectorXi faces;     ///< #E number of triangles at the edge (1 = boundary)
  int num_vertices = 0;
  int num_edges() const { return static_cast<int>(from.size()); }
};

/// Builds the graph: w_ij = base_ij · exp(−d_ij / mean(d)), d_ij = η(1 − cos θ) for convex and
/// (1 − cos θ) for concave edges between the two faces at edge ij (boundary and non-manifold edges:
/// d = 0). V is #V×3, F is #F×3. Degenerate faces (zero area) contribute no angular term.
MeshGraph build_mesh_graph(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                           const AffinityOptions& options = {});

/// Closes gaps such as a blouse's open front: adds an edge (affinity: the mean affinity; length:
/// the distance) between two boundary vertices of one connected component that lie closer than
/// `max_distance` [m] but more than `min_hops` edges apart on the graph. Returns the edges added.
int bridge_boundary_gaps(const Eigen::MatrixX3d& V, double max_distance, int min_hops,
                         MeshGraph& graph);

/// Symmetric #V×#V affinity matrix W of the graph (zero diagonal).
Eigen::SparseMatrix<double> affinity_matrix(const MeshGraph& graph);

/// Connected components of the graph: #V component index per vertex (vertices without an edge get
/// their own component), numbered in order of their first vertex. Returns the number of components.
int connected_components(const MeshGraph& graph, Eigen::VectorXi& component);

/// Normalised cut of a labelling: Σ over labels of (affinity leaving the label) / (its total
/// degree). Vertices labelled −1 are ignored, and so are edges to them.
double normalized_cut(const MeshGraph& graph, const Eigen::VectorXi& labels);

/// Vertices of each boundary loop (connected run of boundary edges) among the edges whose two
/// endpoints satisfy `inside` (e.g. carry one label), and their number.
template <class Inside>
std::vector<std::vector<int>> boundary_loops(const MeshGraph& graph, Inside inside);
template <class Inside>
int count_boundary_loops(const MeshGraph& graph, Inside inside);

/// Vertex adjacency lists (CSR): neighbours of v are adj[start[v] .. start[v+1]), with the edge
/// index of each in edge.
struct Adjacency {
  std::vector<int> start, adj, edge;
};
Adjacency adjacency(const MeshGraph& graph);

/// #V lumped vertex areas (a third of each incident triangle) [m²].
Eigen::VectorXd vertex_areas(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

template <class Inside>
std::vector<std::vector<int>> boundary_loops(const MeshGraph& graph, Inside inside) {
  std::vector<int> parent(graph.num_vertices, -1);  // −1: not on a boundary edge
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (int e = 0; e < graph.num_edges(); ++e) {
    if (graph.faces(e) != 1 || !inside(graph.from(e)) || !inside(graph.to(e))) continue;
    for (int v : {graph.from(e), graph.to(e)})
      if (parent[v] < 0) parent[v] = v;
    const int a = find(graph.from(e)), b = find(graph.to(e));
    if (a != b) parent[a] = b;
  }
  std::vector<int> index(graph.num_vertices, -1);
  std::vector<std::vector<int>> loops;
  for (int v = 0; v < graph.num_vertices; ++v) {
    if (parent[v] < 0) continue;
    const int root = find(v);
    if (index[root] < 0) index[root] = static_cast<int>(loops.size()), loops.emplace_back();
    loops[index[root]].push_back(v);
  }
  return loops;
}

template <class Inside>
int count_boundary_loops(const MeshGraph& graph, Inside inside) {
  return static_cast<int>(boundary_loops(graph, inside).size());
}

}  // namespace dresskit::segmentation
