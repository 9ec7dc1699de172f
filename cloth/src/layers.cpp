#include "dresskit/cloth/layers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <unordered_map>

#include "dresskit/cloth/geometry.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/triangle_mesh.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {
namespace {

void append_spring(SpringSet& s, int i, int j, double rest, double k_rest, double k_knee,
                   SpringType type) {
  s.i.push_back(i);
  s.j.push_back(j);
  s.rest_length.push_back(rest);
  s.k_rest.push_back(k_rest);
  s.k_knee.push_back(k_knee);
  s.type.push_back(type);
}

void append_springs(SpringSet& to, const SpringSet& from, int offset) {
  const int base = to.size();
  for (int k = 0; k < from.size(); ++k)
    append_spring(to, from.i[k] + offset, from.j[k] + offset, from.rest_length[k], from.k_rest[k],
                  from.k_knee[k], from.type[k]);
  for (std::size_t k = 0; k < from.limited.size(); ++k) {
    to.limited.push_back(from.limited[k] + base);
    to.limit_min.push_back(from.limit_min[k]);
    to.limit_max.push_back(from.limit_max[k]);
  }
}

void append_seams(SeamSet& to, const SeamSet& from, int offset) {
  for (int k = 0; k < from.size(); ++k) {
    to.a.push_back(from.a[k] + offset);
    to.b0.push_back(from.b0[k] + offset);
    to.b1.push_back(from.b1[k] + offset);
    to.t.push_back(from.t[k]);
    to.stiffness.push_back(from.stiffness[k]);
    to.max_force.push_back(from.max_force[k]);
  }
}

int layer_count(const ClothModel& m) { return m.layer.size() ? m.layer.maxCoeff() + 1 : 1; }

}  // namespace

Eigen::MatrixX3d rest_vertex_normals(const ClothModel& m) {
  return vertex_normals(m.rest_positions, m.faces);
}

ClothModel make_double_layer(const ClothModel& single, const LayerThickness& t) {
  if (!(t.thickness > 0.0 && t.min > 0.0 && t.min <= t.thickness && t.max >= t.thickness) ||
      !std::isfinite(t.max)) {
    throw InputError("layer thickness " + std::to_string(t.thickness) + " m with limits [" +
                     std::to_string(t.min) + ", " + std::to_string(t.max) +
                     "] m: need 0 < min ≤ thickness ≤ max");
  }
  if (layer_count(single) != 1)
    throw InputError("a double layer is made from a single-layer cloth");
  if (single.faces.rows() == 0) throw InputError("a double layer needs a cloth with faces");
  const int nv = static_cast<int>(single.rest_positions.rows());
  const Eigen::MatrixX3d normals = rest_vertex_normals(single);

  ClothModel d;
  d.rest_positions.resize(2 * nv, 3);
  d.rest_positions.topRows(nv) = single.rest_positions;
  d.rest_positions.bottomRows(nv) = single.rest_positions + t.thickness * normals;
  d.mass.resize(2 * nv);
  d.mass << single.mass, single.mass;
  d.layer.resize(2 * nv);
  d.layer << Eigen::VectorXi::Zero(nv), Eigen::VectorXi::Ones(nv);
  d.layer_offset = {0.0, t.thickness};
  // The inter-layer springs and their limits hold the gap; the guard keeps the outer layer half the
  // compression limit above the inner one. Measured on a double layer on a sphere: with the whole
  // limit the guard lifted the cloth off the sphere, with none the layers crossed.
  d.layer_min_gap = {0.0, 0.5 * t.min};
  d.skipped_zero_area_faces = single.skipped_zero_area_faces;
  d.skipped_zero_length_springs = single.skipped_zero_length_springs;
  append_springs(d.springs, single.springs, 0);
  append_springs(d.springs, single.springs, nv);
  append_seams(d.seams, single.seams, 0);  // both shells are sewn alike
  append_seams(d.seams, single.seams, nv);

  // The layer's own coefficients at each vertex: the mean spring constant [N/m] of its structural
  // springs (k_rest and k_knee are already per spring, k = c A / L0²).
  Eigen::VectorXd k_rest = Eigen::VectorXd::Zero(nv), k_knee = Eigen::VectorXd::Zero(nv);
  Eigen::VectorXi count = Eigen::VectorXi::Zero(nv);
  const SpringSet& s = single.springs;
  for (int k = 0; k < s.size(); ++k) {
    if (s.type[k] != SpringType::structural) continue;
    for (int v : {s.i[k], s.j[k]}) {
      k_rest[v] += s.k_rest[k];
      k_knee[v] += s.k_knee[k];
      ++count[v];
    }
  }
  auto limit_last = [&](double lo, double hi) {
    d.springs.limited.push_back(d.springs.size() - 1);
    d.springs.limit_min.push_back(lo);
    d.springs.limit_max.push_back(hi);
  };
  for (int v = 0; v < nv; ++v) {
    if (count[v] == 0 || normals.row(v).squaredNorm() == 0.0) continue;  // no faces, no springs
    append_spring(d.springs, v, v + nv, t.thickness, k_rest[v] / count[v], k_knee[v] / count[v],
                  SpringType::layer_structural);
    limit_last(t.min, t.max);
  }
  // Shear across each structural edge (i, j): i to j's copy and j to i's copy, with the edge's own
  // constant. Not length-limited: the structural pair above holds the gap.
  for (int k = 0; k < s.size(); ++k) {
    if (s.type[k] != SpringType::structural) continue;
    const int i = s.i[k], j = s.j[k];
    for (auto [a, b] : {std::pair{i, j + nv}, std::pair{j, i + nv}}) {
      const double rest = (d.rest_positions.row(b) - d.rest_positions.row(a)).norm();
      append_spring(d.springs, a, b, rest, s.k_rest[k], s.k_knee[k], SpringType::layer_shear);
    }
  }

  // Faces: the inner layer reversed (it faces the body), the outer one, and the rim.
  std::map<std::pair<int, int>, int> directed;  // directed edge → count, to find boundary edges
  for (Eigen::Index f = 0; f < single.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++directed[{single.faces(f, c), single.faces(f, (c + 1) % 3)}];
  std::vector<Eigen::Vector3i> faces;
  for (Eigen::Index f = 0; f < single.faces.rows(); ++f) {
    const Eigen::Vector3i tri = single.faces.row(f);
    faces.emplace_back(tri[0], tri[2], tri[1]);
    faces.emplace_back(tri[0] + nv, tri[1] + nv, tri[2] + nv);
  }
  for (const auto& [edge, n] : directed) {
    const auto [a, b] = edge;
    if (directed.count({b, a})) continue;  // interior edge
    faces.emplace_back(a, b, b + nv);
    faces.emplace_back(a, b + nv, a + nv);
  }
  d.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    d.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return d;
}

std::vector<int> garment_offsets(const std::vector<ClothModel>& garments) {
  std::vector<int> offsets{0};
  for (const ClothModel& g : garments)
    offsets.push_back(offsets.back() + static_cast<int>(g.rest_positions.rows()));
  return offsets;
}

ClothModel stack_layers(const std::vector<ClothModel>& garments, double separation) {
  const std::vector<int> offsets = garment_offsets(garments);
  const int nv = offsets.back();
  ClothModel m;
  m.rest_positions.resize(nv, 3);
  m.mass.resize(nv);
  m.layer.resize(nv);
  m.layer_offset.clear();
  m.layer_min_gap.clear();
  Eigen::Index nf = 0;
  for (const ClothModel& g : garments) nf += g.faces.rows();
  m.faces.resize(nf, 3);
  nf = 0;
  double base = 0.0;  // offset of this garment's innermost layer
  int first_layer = 0;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    const ClothModel& g = garments[k];
    const int n = static_cast<int>(g.rest_positions.rows());
    m.rest_positions.middleRows(offsets[k], n) = g.rest_positions;
    m.mass.segment(offsets[k], n) = g.mass;
    m.layer.segment(offsets[k], n) = g.layer.array() + first_layer;
    m.faces.middleRows(nf, g.faces.rows()) = g.faces.array() + offsets[k];
    nf += g.faces.rows();
    append_springs(m.springs, g.springs, offsets[k]);
    append_seams(m.seams, g.seams, offsets[k]);
    m.skipped_zero_area_faces += g.skipped_zero_area_faces;
    m.skipped_zero_length_springs += g.skipped_zero_length_springs;
    if (k > 0) base = m.layer_offset.back() + separation;
    for (double offset : g.layer_offset) m.layer_offset.push_back(base + offset);
    for (std::size_t l = 0; l < g.layer_offset.size(); ++l)
      m.layer_min_gap.push_back(l == 0 ? (k > 0 ? separation : 0.0) : g.layer_min_gap[l]);
    first_layer += layer_count(g);
  }
  return m;
}

LayerGap layer_gap(const ClothModel& m, const Eigen::MatrixX3d& x) {
  LayerGap gap;
  gap.min = std::numeric_limits<double>::infinity();
  double sum = 0.0;
  const SpringSet& s = m.springs;
  for (int k = 0; k < s.size(); ++k) {
    if (s.type[k] != SpringType::layer_structural) continue;
    const double L = (x.row(s.j[k]) - x.row(s.i[k])).norm();
    gap.min = std::min(gap.min, L);
    gap.max = std::max(gap.max, L);
    sum += L;
    ++gap.springs;
  }
  if (gap.springs == 0) gap.min = 0.0;
  gap.mean = gap.springs ? sum / gap.springs : 0.0;
  return gap;
}

LayerContacts match_layers(const ClothModel& m, const Eigen::MatrixX3d& x,
                           const std::vector<Collider>& colliders, bool highest) {
  const int nv = static_cast<int>(x.rows());
  LayerContacts c;
  c.below_face.assign(nv, -1);
  c.below_weights = Eigen::MatrixX3d::Zero(nv, 3);
  c.collider.assign(nv, -1);
  c.distance = Eigen::VectorXd::Constant(nv, std::numeric_limits<double>::infinity());
  c.normal = Eigen::MatrixX3d::Zero(nv, 3);
  const int layers = layer_count(m);
  if (colliders.empty() || layers < 2) return c;
  // Nearest collider of every particle: its index, the distance, the normal and the projection.
  Eigen::MatrixX3d projected(nv, 3);
  for (int p = 0; p < nv; ++p) {
    for (std::size_t k = 0; k < colliders.size(); ++k) {
      Eigen::Vector3d n;
      const double d = colliders[k].distance(x.row(p), &n);
      if (d < c.distance[p]) {
        c.distance[p] = d;
        c.collider[p] = static_cast<int>(k);
        c.normal.row(p) = n.transpose();
        projected.row(p) = x.row(p) - d * n.transpose();
      }
    }
  }
  // Faces per layer (a double layer's rim faces join two layers and belong to neither) and the
  // longest projected edge, which sets the grid cell.
  std::vector<std::vector<int>> faces(layers);
  double cell_size = 0.0;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    const int l = m.layer[m.faces(f, 0)];
    if (m.layer[m.faces(f, 1)] != l || m.layer[m.faces(f, 2)] != l) continue;
    faces[l].push_back(static_cast<int>(f));
    for (int k = 0; k < 3; ++k)
      cell_size =
          std::max(cell_size,
                   (projected.row(m.faces(f, k)) - projected.row(m.faces(f, (k + 1) % 3))).norm());
  }
  if (cell_size <= 0.0) return c;
  auto cell = [cell_size](const Eigen::Vector3d& p) { return grid_cell_key(p, cell_size); };
  for (int below = 0; below + 1 < layers; ++below) {
    // Each face of the layer beneath in the cell of its projected centroid; a point inside a face
    // is within one longest edge of its centroid, so the 27 cells around the point hold it.
    std::unordered_map<std::int64_t, std::vector<int>> grid;
    for (int f : faces[below]) {
      const Eigen::Vector3d centroid = (projected.row(m.faces(f, 0)) +
                                        projected.row(m.faces(f, 1)) + projected.row(m.faces(f, 2)))
                                           .transpose() /
                                       3.0;
      grid[cell(centroid)].push_back(f);
    }
    for (int p = 0; p < nv; ++p) {
      if (m.layer[p] != below + 1) continue;
      const Eigen::Vector3d P = projected.row(p);
      // Of the faces whose projection contains P (a fold of the layer beneath gives several), the
      // one whose point at P's weights is nearest to p in space, or the highest over the collider.
      double best = std::numeric_limits<double>::infinity();
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find(cell(P + cell_size * Eigen::Vector3d(dx, dy, dz)));
            if (it == grid.end()) continue;
            for (int f : it->second) {
              // Barycentric coordinates of P in the projected triangle (in its plane).
              const Eigen::Vector3d A = projected.row(m.faces(f, 0)),
                                    e0 = projected.row(m.faces(f, 1)).transpose() - A,
                                    e1 = projected.row(m.faces(f, 2)).transpose() - A, e2 = P - A;
              const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = e2.dot(e0),
                           d21 = e2.dot(e1);
              const double denom = d00 * d11 - d01 * d01;
              if (denom <= 1e-30) continue;
              const double v = (d11 * d20 - d01 * d21) / denom, w = (d00 * d21 - d01 * d20) / denom,
                           u = 1.0 - v - w;
              if (std::min({u, v, w}) < -1e-6) continue;
              const double d2 =
                  highest ? -(u * c.distance[m.faces(f, 0)] + v * c.distance[m.faces(f, 1)] + w * c.distance[m.faces(f, 2)])
                          : (u * x.row(m.faces(f, 0)) + v * x.row(m.faces(f, 1)) + w * x.row(m.faces(f, 2)) - x.row(p))
                                .squaredNorm();
              if (d2 < best) {
                best = d2;
                c.below_face[p] = f;
                c.below_weights.row(p) << u, v, w;
              }
            }
          }
    }
  }
  return c;
}

double LayerContacts::height_below(int p, const ClothModel& m, const Eigen::MatrixX3d& x,
                                   const std::vector<Collider>& colliders) const {
  const int f = below_face[p];
  double h = 0.0;
  Eigen::Vector3d unused;
  for (int k = 0; k < 3; ++k)
    h += below_weights(p, k) * colliders[collider[p]].distance(x.row(m.faces(f, k)), &unused);
  return h;
}

namespace {

/// For each particle of layer l, its side of the layer beneath: the signed distance from its
/// nearest point q on that layer along the layer's angle-weighted pseudo-normal at q (Bærentzen &
/// Aanæs 2005: the face's normal when q is inside a face, the sum of the two faces' normals on an
/// edge, the angle-weighted sum around a vertex), or NaN when q lies on the layer's border (p is
/// beside it, not over or under it) or farther than reach. With q inside a face, p − q is along
/// that face's normal, so the sign is exact; vertex normals interpolated at q (the first version)
/// turn against the face's own normal where a hem folds back sharply and flagged particles lying
/// on the outer side of the face their nearest point is in (docs/cloth.md, Layers).
Eigen::VectorXd sides(const ClothModel& m, const Eigen::MatrixX3d& x, int l, double reach) {
  Eigen::VectorXd side =
      Eigen::VectorXd::Constant(x.rows(), std::numeric_limits<double>::quiet_NaN());
  std::vector<int> beneath;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f)
    if (m.layer[m.faces(f, 0)] == l - 1) beneath.push_back(static_cast<int>(f));
  if (beneath.empty()) return side;
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(beneath.size()), 3);
  for (std::size_t k = 0; k < beneath.size(); ++k)
    F.row(static_cast<Eigen::Index>(k)) = m.faces.row(beneath[k]);
  // Border edges and particles of the layer beneath (an edge of one face).
  std::map<std::pair<int, int>, int> edge_faces;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++edge_faces[std::minmax(F(f, k), F(f, (k + 1) % 3))];
  std::vector<char> border_particle(static_cast<std::size_t>(x.rows()), 0);
  for (const auto& [e, count] : edge_faces)
    if (count == 1) border_particle[e.first] = border_particle[e.second] = 1;
  // Pseudo-normals: per face, per edge (sum of its faces' unit normals) and per vertex (the faces'
  // unit normals weighted by their angles there).
  Eigen::MatrixX3d face_normal(F.rows(), 3);
  Eigen::MatrixX3d vertex_normal = Eigen::MatrixX3d::Zero(x.rows(), 3);
  std::map<std::pair<int, int>, Eigen::Vector3d> edge_normal;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d P[3] = {x.row(F(f, 0)).transpose(), x.row(F(f, 1)).transpose(),
                                  x.row(F(f, 2)).transpose()};
    const Eigen::Vector3d n = (P[1] - P[0]).cross(P[2] - P[0]).normalized();
    face_normal.row(f) = n.transpose();
    for (int k = 0; k < 3; ++k) {
      const double angle = std::acos(
          std::clamp((P[(k + 1) % 3] - P[k]).normalized().dot((P[(k + 2) % 3] - P[k]).normalized()),
                     -1.0, 1.0));
      vertex_normal.row(F(f, k)) += angle * n.transpose();
      auto [it, added] = edge_normal.try_emplace(std::minmax(F(f, k), F(f, (k + 1) % 3)), n);
      if (!added) it->second += n;
    }
  }
  const TriangleBvh bvh(x, F);
  for (Eigen::Index p = 0; p < x.rows(); ++p) {
    if (m.layer[p] != l) continue;
    Eigen::Vector3d q;
    double d2 = 0.0;
    const int f = bvh.closest(x.row(p).transpose(), &q, &d2, reach * reach);
    if (f < 0) continue;
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    Eigen::Vector3d w;
    closest_point_on_triangle(x.row(p).transpose(), x.row(a).transpose(), x.row(b).transpose(),
                              x.row(c).transpose(), &w);
    // On the face's edge opposite corner k when w[k] ≈ 0: a border edge (or, at a corner, a border
    // particle) means p lies beyond the layer's border.
    const int corner[3] = {a, b, c};
    bool beyond = false;
    for (int k = 0; k < 3; ++k) {
      if (w[k] > 1e-9) continue;
      const int u = corner[(k + 1) % 3], v = corner[(k + 2) % 3];
      if (edge_faces[std::minmax(u, v)] == 1) beyond = true;
      if (w[(k + 1) % 3] <= 1e-9 && border_particle[v]) beyond = true;
      if (w[(k + 2) % 3] <= 1e-9 && border_particle[u]) beyond = true;
    }
    if (beyond) continue;
    // The feature q lies on: a face (no zero weight), an edge (one: the edge opposite that corner)
    // or a vertex (two: the third corner).
    int zeros = 0, zero = 0, other = 0;
    for (int k = 0; k < 3; ++k) {
      if (w[k] > 0.0) {
        other = k;
      } else {
        zero = k;
        ++zeros;
      }
    }
    const Eigen::Vector3d n =
        zeros == 0   ? Eigen::Vector3d(face_normal.row(f).transpose())
        : zeros == 1 ? edge_normal[std::minmax(corner[(zero + 1) % 3], corner[(zero + 2) % 3])]
                     : Eigen::Vector3d(vertex_normal.row(corner[other]).transpose());
    if (!(n.norm() > 0.0)) continue;
    side[p] = (x.row(p).transpose() - q).dot(n.normalized());
  }
  return side;
}

}  // namespace

LayerOrder layer_order(const ClothModel& m, const Eigen::MatrixX3d& x,
                       const std::vector<Collider>& colliders) {
  (void)colliders;
  LayerOrder order;
  const int layers = static_cast<int>(m.layer_offset.size());
  for (int l = 1; l < layers; ++l) {
    const double spacing = std::max(m.layer_offset[l] - m.layer_offset[l - 1], 1e-4);
    const double reach = 10.0 * spacing, tolerance = 0.25 * spacing;
    // Which side is outside: the side the layer lies on at rest, where the layers are in order (the
    // faces' winding is the input's).
    const Eigen::VectorXd rest =
        sides(m, m.rest_positions, l, std::numeric_limits<double>::infinity());
    double outward = 0.0;
    for (Eigen::Index p = 0; p < rest.size(); ++p)
      if (!std::isnan(rest[p])) outward += rest[p];
    const double sign = outward < 0.0 ? -1.0 : 1.0;
    const Eigen::VectorXd now = sides(m, x, l, reach);
    for (Eigen::Index p = 0; p < now.size(); ++p) {
      if (std::isnan(now[p])) continue;
      ++order.checked;
      order.violations += sign * now[p] < -tolerance;
    }
  }
  return order;
}

}  // namespace dresskit::cloth
