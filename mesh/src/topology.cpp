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

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Eigen::Vector3d>& corners) {
  const int n = static_cast<int>(corners.size());
  std::vector<std::array<int, 3>> out;
  if (n < 3) return out;
  auto fan = [&] {
    out.clear();
    for (int k = 1; k + 1 < n; ++k) out.push_back({0, k, k + 1});
    return out;
  };
  // Ear clipping costs n³ here; a polygon beyond kLargestClipped corners (no modeller writes one for
  // a garment) is fanned so that no input can make loading slow.
  constexpr int kLargestClipped = 256;
  if (n == 3 || n > kLargestClipped) return fan();
  // Newell's normal: the polygon's area vector, robust to non-planar and non-convex polygons.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double size = 0.0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d& a = corners[static_cast<size_t>(k)];
    const Eigen::Vector3d& b = corners[static_cast<size_t>((k + 1) % n)];
    normal += Eigen::Vector3d((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                              (a.x() - b.x()) * (a.y() + b.y()));
    size = std::max(size, (b - a).norm());
  }
  if (!(normal.norm() > 1e-12 * size * size)) return fan();
  normal.normalize();
  const Eigen::Vector3d u = normal.unitOrthogonal(), w = normal.cross(u);
  Eigen::Matrix2Xd p(2, n);  // the corners in the plane
  for (int k = 0; k < n; ++k) p.col(k) << corners[static_cast<size_t>(k)].dot(u), corners[static_cast<size_t>(k)].dot(w);
  auto cross = [&](int a, int b, int c) {
    const Eigen::Vector2d e = p.col(b) - p.col(a), f = p.col(c) - p.col(a);
    return e.x() * f.y() - e.y() * f.x();
  };
  // Twice a triangle's area below this is a straight corner (relative to the polygon's longest side).
  const double straight = 1e-9 * size * size;
  auto inside_or_on = [&](int v, int a, int b, int c) {  // v in the closed triangle abc (counter-clockwise)
    return cross(a, b, v) >= -straight && cross(b, c, v) >= -straight && cross(c, a, v) >= -straight;
  };
  // An ear's shape: its smallest angle's sine, as 2·area / (longest side²), in [0, √3/2].
  auto shape = [&](int a, int b, int c) {
    const double l = std::max({(p.col(a) - p.col(b)).squaredNorm(), (p.col(b) - p.col(c)).squaredNorm(),
                               (p.col(c) - p.col(a)).squaredNorm()});
    return l > 0.0 ? cross(a, b, c) / l : 0.0;
  };
  // An ear: a corner turning the polygon's way with no other corner inside or on its triangle.
  auto ear = [&](const std::vector<int>& ring, int a, int b, int c) {
    if (cross(a, b, c) <= straight) return false;  // reflex or straight
    for (int v : ring)
      if (v != a && v != b && v != c && inside_or_on(v, a, b, c)) return false;
    return true;
  };
  std::vector<int> ring(static_cast<size_t>(n));
  std::iota(ring.begin(), ring.end(), 0);
  // The file's own fan is kept where each of its triangles is an ear (every convex polygon), so a
  // well-formed mesh is triangulated as its authoring tool shows it.
  bool fan_is_fine = true;
  for (int k = 1; k + 1 < n && fan_is_fine; ++k) fan_is_fine = ear(ring, 0, k, k + 1);
  if (fan_is_fine) return fan();
  while (ring.size() > 3) {
    const int m = static_cast<int>(ring.size());
    int best = -1;
    double best_shape = 0.0;
    for (int k = 0; k < m; ++k) {
      const int a = ring[static_cast<size_t>((k + m - 1) % m)], b = ring[static_cast<size_t>(k)],
                c = ring[static_cast<size_t>((k + 1) % m)];
      if (!ear(ring, a, b, c)) continue;
      const double s = shape(a, b, c);
      if (s > best_shape) best = k, best_shape = s;
    }
    if (best < 0) return fan();  // self-overlapping polygon: nothing better than the file's order
    const int a = ring[static_cast<size_t>((best + m - 1) % m)], b = ring[static_cast<size_t>(best)],
              c = ring[static_cast<size_t>((best + 1) % m)];
    out.push_back({a, b, c});
    ring.erase(ring.begin() + best);
  }
  out.push_back({ring[0], ring[1], ring[2]});
  return out;
}

}  // namespace dresskit::mesh
