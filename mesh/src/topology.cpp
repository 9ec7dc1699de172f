#include "dresskit/mesh/topology.h"

#include "dresskit/mesh/union_find.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace dresskit::mesh {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// Per undirected edge: how many faces use it and how many of those traverse it as (min → max).
struct EdgeUse {
  int faces = 0;
  int forward = 0;
};

bool is_degenerate(const TriangleMesh& m, int f) {
  const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
  if (a == b || b == c || a == c) return true;
  const Eigen::RowVector3d e1 = m.V.row(b) - m.V.row(a), e2 = m.V.row(c) - m.V.row(a);
  return e1.cross(e2).squaredNorm() == 0.0;
}

}  // namespace

std::vector<int> face_components(const Eigen::MatrixX3i& F, int num_vertices, int* num_components) {
  UnionFind uf(num_vertices);
  for (int f = 0; f < F.rows(); ++f) {
    uf.unite(F(f, 0), F(f, 1));
    uf.unite(F(f, 0), F(f, 2));
  }
  std::vector<int> root_to_component(num_vertices, -1), component(F.rows());
  int n = 0;
  for (int f = 0; f < F.rows(); ++f) {
    int& c = root_to_component[uf.find(F(f, 0))];
    if (c < 0) c = n++;
    component[f] = c;
  }
  if (num_components) *num_components = n;
  return component;
}

TopologyReport analyse_topology(const TriangleMesh& mesh) {
  TopologyReport r;
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  r.num_vertices = nv;
  r.num_faces = nf;

  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(static_cast<size_t>(nf) * 2);
  std::vector<int> valence(nv, 0);
  for (int f = 0; f < nf; ++f) {
    if (is_degenerate(mesh, f)) ++r.num_degenerate_faces;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      ++valence[a];
      if (a == b) continue;
      EdgeUse& e = edges[edge_key(a, b)];
      ++e.faces;
      if (a < b) ++e.forward;
    }
    const Eigen::RowVector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                             c = mesh.V.row(mesh.F(f, 2));
    r.area += 0.5 * (b - a).cross(c - a).norm();
    r.signed_volume += a.dot(b.cross(c)) / 6.0;
  }
  r.num_edges = static_cast<int>(edges.size());

  UnionFind boundary(nv);
  std::vector<bool> on_boundary(nv, false);
  for (const auto& [key, use] : edges) {
    if (use.faces == 1) {
      ++r.num_boundary_edges;
      const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
      boundary.unite(a, b);
      on_boundary[a] = on_boundary[b] = true;
      r.boundary_length += (mesh.V.row(a) - mesh.V.row(b)).norm();
    } else if (use.faces == 2) {
      if (use.forward != 1) ++r.num_inconsistent_edges;
    } else {
      ++r.num_non_manifold_edges;
    }
  }
  for (int v = 0; v < nv; ++v) {
    if (on_boundary[v] && boundary.find(v) == v) ++r.num_boundary_loops;
  }

  // Fans around each vertex: faces at v that share an edge (v, w) belong to the same fan.
  std::vector<int> start(nv + 1, 0);
  for (int v = 0; v < nv; ++v) start[v + 1] = start[v] + valence[v];
  std::vector<int> incident(start[nv]), fill(start.begin(), start.end() - 1);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) incident[fill[mesh.F(f, k)]++] = f;
  }
  std::unordered_map<int, int> first_face_at_neighbour;
  UnionFind fan;
  for (int v = 0; v < nv; ++v) {
    const int n = valence[v];
    if (n == 0) {
      ++r.num_isolated_vertices;
      continue;
    }
    fan.reset(n);
    first_face_at_neighbour.clear();
    for (int i = 0; i < n; ++i) {
      const int f = incident[start[v] + i];
      for (int k = 0; k < 3; ++k) {
        const int w = mesh.F(f, k);
        if (w == v) continue;
        auto [it, inserted] = first_face_at_neighbour.emplace(w, i);
        if (!inserted) fan.unite(i, it->second);
      }
    }
    int fans = 0;
    for (int i = 0; i < n; ++i) fans += fan.find(i) == i;
    if (fans > 1) ++r.num_non_manifold_vertices;
  }

  face_components(mesh.F, nv, &r.num_components);
  r.manifold = r.num_non_manifold_edges == 0 && r.num_non_manifold_vertices == 0;
  r.closed = r.manifold && r.num_boundary_edges == 0 && nf > 0;
  r.consistently_oriented = r.num_inconsistent_edges == 0 && r.num_non_manifold_edges == 0;
  r.outward = r.closed && r.consistently_oriented && r.signed_volume > 0.0;
  r.euler_characteristic = (nv - r.num_isolated_vertices) - r.num_edges + nf;
  return r;
}

std::vector<TriangleMesh> split_components(const TriangleMesh& mesh) {
  int n = 0;
  const std::vector<int> component = face_components(mesh.F, mesh.num_vertices(), &n);
  std::vector<int> faces_per(n, 0);
  for (int c : component) ++faces_per[c];
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return faces_per[a] > faces_per[b]; });
  std::vector<TriangleMesh> parts;
  for (int c : order) {
    std::vector<bool> keep(mesh.num_vertices(), false);
    for (int f = 0; f < mesh.num_faces(); ++f) {
      if (component[f] != c) continue;
      for (int k = 0; k < 3; ++k) keep[mesh.F(f, k)] = true;
    }
    parts.push_back(select_vertices(mesh, keep));
  }
  return parts;
}

int orient_closed_components_outward(TriangleMesh& mesh) {
  int n = 0;
  const std::vector<int> component = face_components(mesh.F, mesh.num_vertices(), &n);
  std::vector<double> volume(n, 0.0);
  std::unordered_map<std::uint64_t, int> edge_faces;
  std::vector<bool> closed(n, true);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::RowVector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                             c = mesh.V.row(mesh.F(f, 2));
    volume[component[f]] += a.dot(b.cross(c)) / 6.0;
    for (int k = 0; k < 3; ++k) ++edge_faces[edge_key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))];
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (edge_faces[edge_key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))] != 2) closed[component[f]] = false;
    }
  }
  int flipped = 0;
  std::vector<bool> flip_vertex(mesh.num_vertices(), false);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const int c = component[f];
    if (closed[c] && volume[c] < 0.0) {
      std::swap(mesh.F(f, 1), mesh.F(f, 2));
      for (int k = 0; k < 3; ++k) flip_vertex[mesh.F(f, k)] = true;
      ++flipped;
    }
  }
  // A quad (a,b,c,d) reversed is (a,d,c,b), whose triangles (a,d,c) and (a,c,b) are the flipped ones.
  for (int q = 0; q < mesh.quads.rows(); ++q) {
    if (flip_vertex[mesh.quads(q, 0)]) std::swap(mesh.quads(q, 1), mesh.quads(q, 3));
  }
  return flipped;
}

std::vector<std::vector<int>> vertex_neighbours(const Eigen::MatrixX3i& F, int num_vertices) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(num_vertices));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      out[static_cast<std::size_t>(a)].push_back(b);
      out[static_cast<std::size_t>(b)].push_back(a);
    }
  for (std::vector<int>& n : out) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return out;
}

}  // namespace dresskit::mesh
