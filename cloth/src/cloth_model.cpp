#include "dresskit/cloth/cloth_model.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

#include "dresskit/mesh/errors.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// Angle [rad] between an edge and the warp direction projected into a face's plane.
double warp_angle(const Eigen::Vector3d& edge, const Eigen::Vector3d& face_normal,
                  const Eigen::Vector3d& warp) {
  const Eigen::Vector3d w = warp - warp.dot(face_normal) * face_normal;
  if (w.norm() < 1e-12 || edge.norm() < 1e-12) return 0.0;
  return std::acos(std::clamp(std::abs(edge.normalized().dot(w.normalized())), 0.0, 1.0));
}

}  // namespace

int SpringSet::count(SpringType t) const {
  return static_cast<int>(std::count(type.begin(), type.end(), t));
}

TriangleMesh make_grid(const Eigen::Vector2d& size, const Eigen::Vector2i& resolution,
                       const Eigen::Vector3d& center, const Eigen::Vector3d& normal) {
  if (!size.allFinite() || size.minCoeff() <= 0.0) throw InputError("grid size: must be positive");
  if (resolution.minCoeff() < 2 || resolution.maxCoeff() > 4096) {
    throw InputError("grid resolution: must be 2–4096 vertices per side");
  }
  if (!center.allFinite()) throw InputError("grid center: not finite");
  if (!normal.allFinite() || normal.norm() < 1e-12) throw InputError("grid normal: not a direction");
  const Eigen::Vector3d n = normal.normalized();
  Eigen::Vector3d a1 = Eigen::Vector3d::UnitX() - n.x() * n;
  if (a1.norm() < 1e-6) a1 = Eigen::Vector3d::UnitZ() - n.z() * n;
  a1.normalize();
  const Eigen::Vector3d a2 = n.cross(a1);  // a1 × a2 = n: quads face the normal
  const int nx = resolution.x(), ny = resolution.y();
  TriangleMesh m;
  m.V.resize(nx * ny, 3);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m.V.row(j * nx + i) = (center + (double(i) / (nx - 1) - 0.5) * size.x() * a1 +
                             (double(j) / (ny - 1) - 0.5) * size.y() * a2)
                                .transpose();
    }
  m.quads.resize((nx - 1) * (ny - 1), 4);
  m.F.resize(2 * m.quads.rows(), 3);
  int q = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i, ++q) {
      const int a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      m.quads.row(q) << a, b, c, d;
      m.F.row(2 * q) << a, b, c;
      m.F.row(2 * q + 1) << a, c, d;
    }
  m.source_vertex = Eigen::VectorXi::LinSpaced(nx * ny, 0, nx * ny - 1);
  return m;
}

ClothModel build_cloth(const TriangleMesh& mesh, const Fabric& fabric, const ClothBuildOptions& o) {
  if (!(fabric.areal_density > 0.0) || !std::isfinite(fabric.areal_density)) {
    throw InputError("fabric " + fabric.name + ": areal density must be positive");
  }
  if (!(o.total_mass >= 0.0) || !std::isfinite(o.total_mass)) {
    throw InputError("total_mass: must be positive (or 0 for the fabric's density)");
  }
  ClothModel model;
  const int nv = mesh.num_vertices();
  model.rest_positions = mesh.V;
  model.mass = Eigen::VectorXd::Zero(nv);
  model.layer = Eigen::VectorXi::Zero(nv);

  // Faces with area; their normals and the area each gives to the edges around it: half its quad's
  // area when it is half of a quad (so a square grid's edge gets h²), else its own area (the factor
  // 2 for triangle meshes matches a near-equilateral lattice's stretch stiffness; docs/cloth.md).
  std::vector<int> kept;
  std::vector<Eigen::Vector3d> normal;
  std::vector<double> area;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                          c = mesh.V.row(mesh.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() <= 0.0) {
      ++model.skipped_zero_area_faces;
      continue;
    }
    kept.push_back(f);
    normal.push_back(n.normalized());
    area.push_back(0.5 * n.norm());
  }
  model.faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  std::map<std::array<int, 3>, int> face_of_triangle;  // sorted corners → kept index
  for (size_t k = 0; k < kept.size(); ++k) {
    model.faces.row(static_cast<Eigen::Index>(k)) = mesh.F.row(kept[k]);
    std::array<int, 3> key{mesh.F(kept[k], 0), mesh.F(kept[k], 1), mesh.F(kept[k], 2)};
    std::sort(key.begin(), key.end());
    face_of_triangle[key] = static_cast<int>(k);
    for (int c = 0; c < 3; ++c) model.mass(mesh.F(kept[k], c)) += fabric.areal_density * area[k] / 3.0;
  }
  if (o.total_mass > 0.0 && model.mass.sum() > 0.0) model.mass *= o.total_mass / model.mass.sum();

  // Quads whose two triangles survive: their diagonals are shear springs, not structural edges.
  std::vector<double> edge_area(kept.size());
  for (size_t k = 0; k < kept.size(); ++k) edge_area[k] = area[k];
  std::unordered_map<std::uint64_t, bool> is_diagonal;
  std::vector<std::array<int, 4>> shear_quads;
  std::vector<double> quad_area;
  for (int q = 0; q < mesh.quads.rows(); ++q) {
    const int a = mesh.quads(q, 0), b = mesh.quads(q, 1), c = mesh.quads(q, 2), d = mesh.quads(q, 3);
    std::array<int, 3> t1{a, b, c}, t2{a, c, d};
    std::sort(t1.begin(), t1.end());
    std::sort(t2.begin(), t2.end());
    auto f1 = face_of_triangle.find(t1), f2 = face_of_triangle.find(t2);
    if (f1 == face_of_triangle.end() || f2 == face_of_triangle.end()) continue;
    const double qa = area[f1->second] + area[f2->second];
    edge_area[f1->second] = edge_area[f2->second] = qa / 2.0;
    is_diagonal[edge_key(a, c)] = true;
    shear_quads.push_back({a, b, c, d});
    quad_area.push_back(qa);
  }

  // Edge → adjacent kept faces and their opposite vertices.
  struct Adjacent {
    int face, opposite;
  };
  std::unordered_map<std::uint64_t, std::vector<Adjacent>> edges;
  std::vector<std::uint64_t> edge_order;  // first-seen order: deterministic spring order
  for (size_t k = 0; k < kept.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      const int a = model.faces(k, c), b = model.faces(k, (c + 1) % 3), opp = model.faces(k, (c + 2) % 3);
      auto [it, inserted] = edges.try_emplace(edge_key(a, b));
      if (inserted) edge_order.push_back(it->first);
      it->second.push_back({static_cast<int>(k), opp});
    }
  }

  SpringSet& s = model.springs;
  auto add = [&](int i, int j, double k_rest, double k_knee, SpringType type) {
    const double L0 = (mesh.V.row(j) - mesh.V.row(i)).norm();
    if (L0 <= 0.0) {
      ++model.skipped_zero_length_springs;
      return;
    }
    s.i.push_back(i);
    s.j.push_back(j);
    s.rest_length.push_back(L0);
    s.k_rest.push_back(k_rest / (L0 * L0));
    s.k_knee.push_back(k_knee / (L0 * L0));
    s.type.push_back(type);
  };
  for (std::uint64_t key : edge_order) {
    if (is_diagonal.count(key)) continue;
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    const auto& adj = edges[key];
    const Eigen::Vector3d e = mesh.V.row(b) - mesh.V.row(a);
    const double theta = warp_angle(e, normal[adj[0].face], o.warp_direction);
    double A = 0.0;
    for (const auto& f : adj) A += edge_area[f.face];
    // k = c(θ) A / L0² (the /L0² is applied in add).
    add(a, b, fabric.stiffness_at_rest(theta) * A, fabric.stiffness_at_knee(theta) * A,
        SpringType::structural);
  }
  for (size_t q = 0; q < shear_quads.size(); ++q) {
    const auto& v = shear_quads[q];
    // Two diagonals of a quad carry its shear: k = C33 · 2A / L0² (exact for a square cell).
    const double k = fabric.shear_stiffness() * 2.0 * quad_area[q];
    add(v[0], v[2], k, k, SpringType::shear);
    add(v[1], v[3], k, k, SpringType::shear);
  }
  if (o.bending_springs) {
    for (std::uint64_t key : edge_order) {
      const auto& adj = edges[key];
      if (is_diagonal.count(key) || adj.size() != 2) continue;
      const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
      const double theta = warp_angle(mesh.V.row(b) - mesh.V.row(a), normal[adj[0].face], o.warp_direction);
      // k = B(θ) / L0²: a spring approximation of bending (docs/cloth.md).
      const double k = fabric.bending_stiffness(theta);
      add(adj[0].opposite, adj[1].opposite, k, k, SpringType::bending);
    }
  }
  return model;
}

}  // namespace dresskit::cloth
