#include "dresskit/cloth/mesh_distance.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "dresskit/cloth/geometry.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {

namespace {
Eigen::Vector3d vertex(const TriangleMesh& m, int t, int c) { return m.V.row(m.F(t, c)).transpose(); }

/// Flips parity[point] for every grid point of axis `a`'s lines beyond where they cross the mesh; the
/// prefix XOR along a then gives each point's crossing parity. The lines are shifted by a tiny,
/// irrational-looking fraction of a cell so that they do not pass exactly through edges or vertices.
void flip_crossings(const TriangleMesh& m, int a, const Eigen::Vector3d& origin, double h,
                    const Eigen::Vector3i& size, std::vector<std::uint8_t>& parity) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const double shift_b = 0.1234567e-3 * h, shift_c = 0.2345671e-3 * h;
  auto at = [&](int ia, int ib, int ic) {
    int idx[3];
    idx[a] = ia;
    idx[b] = ib;
    idx[c] = ic;
    return (static_cast<std::size_t>(idx[2]) * size[1] + idx[1]) * size[0] + idx[0];
  };
  for (int t = 0; t < m.num_faces(); ++t) {
    const Eigen::Vector3d p0 = vertex(m, t, 0), p1 = vertex(m, t, 1), p2 = vertex(m, t, 2);
    const double lo_b = std::min({p0[b], p1[b], p2[b]}), hi_b = std::max({p0[b], p1[b], p2[b]});
    const double lo_c = std::min({p0[c], p1[c], p2[c]}), hi_c = std::max({p0[c], p1[c], p2[c]});
    const int jb0 = std::max(0, static_cast<int>(std::ceil((lo_b - origin[b] - shift_b) / h)));
    const int jb1 = std::min(size[b] - 1, static_cast<int>(std::floor((hi_b - origin[b] - shift_b) / h)));
    const int jc0 = std::max(0, static_cast<int>(std::ceil((lo_c - origin[c] - shift_c) / h)));
    const int jc1 = std::min(size[c] - 1, static_cast<int>(std::floor((hi_c - origin[c] - shift_c) / h)));
    // 2D barycentric coordinates of a line's foot in the triangle's projection.
    const double det = (p1[b] - p0[b]) * (p2[c] - p0[c]) - (p2[b] - p0[b]) * (p1[c] - p0[c]);
    if (det == 0.0) continue;  // seen edge-on along a: no line crosses it
    for (int jc = jc0; jc <= jc1; ++jc) {
      const double yc = origin[c] + jc * h + shift_c;
      for (int jb = jb0; jb <= jb1; ++jb) {
        const double yb = origin[b] + jb * h + shift_b;
        const double u = ((p1[b] - yb) * (p2[c] - yc) - (p2[b] - yb) * (p1[c] - yc)) / det;
        const double v = ((p2[b] - yb) * (p0[c] - yc) - (p0[b] - yb) * (p2[c] - yc)) / det;
        const double w = 1.0 - u - v;
        if (u < 0.0 || v < 0.0 || w < 0.0) continue;
        const double xa = u * p0[a] + v * p1[a] + w * p2[a];
        const int ia = static_cast<int>(std::ceil((xa - origin[a]) / h));
        if (ia < 0) parity[at(0, jb, jc)] ^= 1;  // (the grid is padded: does not happen)
        else if (ia < size[a]) parity[at(ia, jb, jc)] ^= 1;
      }
    }
  }
  for (int jc = 0; jc < size[c]; ++jc)
    for (int jb = 0; jb < size[b]; ++jb)
      for (int ia = 1; ia < size[a]; ++ia) parity[at(ia, jb, jc)] ^= parity[at(ia - 1, jb, jc)];
}
}  // namespace

MeshDistance::MeshDistance(const TriangleMesh& body, const MeshDistanceOptions& options) : mesh_(body) {
  const auto start = std::chrono::steady_clock::now();
  validate_mesh(body, "body mesh");
  if (!(options.cell > 0.0) || !std::isfinite(options.cell)) throw InputError("body collider: cell must be positive");
  if (!(options.band > 0.0) || !std::isfinite(options.band)) throw InputError("body collider: band must be positive");
  if (!(options.padding >= 0.0) || !std::isfinite(options.padding))
    throw InputError("body collider: padding must be ≥ 0");
  h_ = options.cell;
  inv_h_ = 1.0 / h_;
  band_ = std::max(options.band, 2.0 * std::sqrt(3.0) * h_);
  const Eigen::AlignedBox3d box = bounding_box(body);
  const double pad = std::max(options.padding, band_ + 2.0 * h_);
  origin_ = box.min().array() - pad;
  const Eigen::Vector3d extent = box.sizes().array() + 2.0 * pad;
  double points = 1.0;  // stored: whole bricks
  for (int a = 0; a < 3; ++a) {
    size_[a] = static_cast<int>(std::ceil(extent[a] * inv_h_)) + 1;
    bricks_[a] = (size_[a] + 7) / 8;
    points *= 8.0 * bricks_[a];
  }
  if (points > 2e8) {
    throw InputError("body collider: cell " + std::to_string(h_) + " m makes a grid of " +
                     std::to_string(points) + " points (at most 2e8): use a larger cell");
  }
  const std::size_t n = static_cast<std::size_t>(points);
  const std::size_t lines = static_cast<std::size_t>(size_.cast<double>().prod());  // the ray-parity grid
  bvh_ = TriangleBvh(body.V, body.F);

  // Exact unsigned distances in the band around each triangle.
  phi_.assign(n, static_cast<float>(band_));
  for (int t = 0; t < body.num_faces(); ++t) {
    const Eigen::Vector3d a = vertex(body, t, 0), b = vertex(body, t, 1), c = vertex(body, t, 2);
    const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c).array() - band_;
    const Eigen::Vector3d hi = a.cwiseMax(b).cwiseMax(c).array() + band_;
    Eigen::Vector3i i0, i1;
    for (int d = 0; d < 3; ++d) {
      i0[d] = std::max(0, static_cast<int>(std::ceil((lo[d] - origin_[d]) * inv_h_)));
      i1[d] = std::min(size_[d] - 1, static_cast<int>(std::floor((hi[d] - origin_[d]) * inv_h_)));
    }
    for (int k = i0[2]; k <= i1[2]; ++k)
      for (int j = i0[1]; j <= i1[1]; ++j)
        for (int i = i0[0]; i <= i1[0]; ++i) {
          const Eigen::Vector3d p = origin_ + h_ * Eigen::Vector3d(i, j, k);
          const double d = (closest_point_on_triangle(p, a, b, c) - p).norm();
          float& slot = phi_[index(i, j, k)];
          if (d < slot) slot = static_cast<float>(d);
        }
  }

  // The sign: ray parity along each axis, majority of three.
  std::vector<std::uint8_t> votes(lines, 0), parity(lines);
  for (int a = 0; a < 3; ++a) {
    std::fill(parity.begin(), parity.end(), 0);
    flip_crossings(body, a, origin_, h_, size_, parity);
    for (std::size_t p = 0; p < lines; ++p) votes[p] += parity[p];
  }
  int disagreements = 0;
  for (int k = 0, p = 0; k < size_[2]; ++k)
    for (int j = 0; j < size_[1]; ++j)
      for (int i = 0; i < size_[0]; ++i, ++p) {
        if (votes[p] == 1 || votes[p] == 2) ++disagreements;
        if (votes[p] >= 2) phi_[index(i, j, k)] = -phi_[index(i, j, k)];
      }

  const TopologyReport topology = analyse_topology(body);
  report_.boundary_edges = topology.num_boundary_edges;
  report_.non_manifold_edges = topology.num_non_manifold_edges;
  report_.closed = report_.boundary_edges == 0 && report_.non_manifold_edges == 0;
  report_.sign_method = report_.closed ? "ray parity along x, y and z (watertight mesh)"
                                       : "majority of the ray parities along x, y and z (not watertight)";
  report_.sign_disagreements = disagreements;
  report_.grid = size_;
  report_.cell = h_;
  report_.band = band_;
  report_.memory_bytes = n * sizeof(float);
  report_.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double MeshDistance::exact_distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward) const {
  Eigen::Vector3d q;
  double d2 = 0.0;
  bvh_.closest(p, &q, &d2);
  const double d = std::sqrt(d2);
  const double s = inside(p) ? -1.0 : 1.0;
  if (d > 1e-12) {
    *outward = s * (p - q) / d;
  } else {
    distance(p + Eigen::Vector3d::Constant(1e-9), outward);  // on the surface: the grid's direction
  }
  return s * d;
}

bool MeshDistance::inside(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d u = (p - origin_) * inv_h_;
  Eigen::Vector3i i;
  for (int a = 0; a < 3; ++a) {
    i[a] = static_cast<int>(std::floor(u[a]));
    if (i[a] < 0 || i[a] >= size_[a] - 1) return false;  // outside the padded grid: outside the mesh
  }
  // The sign of the trilinear value: the grid's best guess, right to the interpolation's accuracy.
  const Eigen::Vector3d f = u - i.cast<double>();
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
    value += (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]) *
             phi_[index(i[0] + dx, i[1] + dy, i[2] + dz)];
  }
  return value < 0.0;
}

double MeshDistance::distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward, Cell* cell) const {
  const Eigen::Vector3d u = (p - origin_) * inv_h_;
  const int i = static_cast<int>(std::floor(u[0])), j = static_cast<int>(std::floor(u[1])),
            k = static_cast<int>(std::floor(u[2]));
  if (i < 0 || j < 0 || k < 0 || i >= size_[0] - 1 || j >= size_[1] - 1 || k >= size_[2] - 1) {
    // Outside the grid, which reaches at least a band beyond the mesh: the band plus the distance to
    // the grid is a lower bound (no contact there needs more), pointing away from the grid's centre.
    const Eigen::Vector3d lo = origin_, hi = origin_ + h_ * (size_ - Eigen::Vector3i::Ones()).cast<double>();
    const Eigen::Vector3d inside = p.cwiseMax(lo).cwiseMin(hi);
    const Eigen::Vector3d away = p - 0.5 * (lo + hi);
    *outward = away.norm() > 0.0 ? Eigen::Vector3d(away.normalized()) : Eigen::Vector3d::UnitY();
    return band_ + (p - inside).norm();
  }
  const double fx = u[0] - i, fy = u[1] - j, fz = u[2] - k;
  const int key = index(i, j, k);
  float local[8];
  float* c = cell ? cell->corner : local;  // x fastest, then y, then z
  if (!cell || cell->key != key) {
    if ((i & 7) != 7 && (j & 7) != 7 && (k & 7) != 7) {  // all eight corners in one brick
      const float* b = &phi_[key];
      c[0] = b[0], c[1] = b[1], c[2] = b[8], c[3] = b[9];
      c[4] = b[64], c[5] = b[65], c[6] = b[72], c[7] = b[73];
    } else {
      c[0] = phi_[key], c[1] = phi_[index(i + 1, j, k)];
      c[2] = phi_[index(i, j + 1, k)], c[3] = phi_[index(i + 1, j + 1, k)];
      c[4] = phi_[index(i, j, k + 1)], c[5] = phi_[index(i + 1, j, k + 1)];
      c[6] = phi_[index(i, j + 1, k + 1)], c[7] = phi_[index(i + 1, j + 1, k + 1)];
    }
    if (cell) cell->key = key;
  }
  const double c000 = c[0], c100 = c[1], c010 = c[2], c110 = c[3];
  const double c001 = c[4], c101 = c[5], c011 = c[6], c111 = c[7];
  const double deep = -band_ * 0.999;
  const double lowest = std::min({c000, c100, c010, c110, c001, c101, c011, c111});
  if (lowest <= deep) return exact_distance(p, outward);
  if (lowest >= -deep) {  // every corner beyond the band outside: no contact; a lower bound will do
    const Eigen::Vector3d away = u - 0.5 * (size_ - Eigen::Vector3i::Ones()).cast<double>();
    *outward = away.norm() > 0.0 ? Eigen::Vector3d(away.normalized()) : Eigen::Vector3d::UnitY();
    return band_;
  }
  // Trilinear value and its exact gradient.
  const double x00 = c000 + fx * (c100 - c000), x10 = c010 + fx * (c110 - c010);
  const double x01 = c001 + fx * (c101 - c001), x11 = c011 + fx * (c111 - c011);
  const double y0 = x00 + fy * (x10 - x00), y1 = x01 + fy * (x11 - x01);
  const double value = y0 + fz * (y1 - y0);
  const double gx = ((1 - fy) * (1 - fz) * (c100 - c000) + fy * (1 - fz) * (c110 - c010) +
                     (1 - fy) * fz * (c101 - c001) + fy * fz * (c111 - c011));
  const double gy = (1 - fz) * (x10 - x00) + fz * (x11 - x01);
  const double gz = y1 - y0;
  const Eigen::Vector3d g(gx, gy, gz);
  const double norm = g.norm();
  if (!(norm > 1e-9)) return exact_distance(p, outward);
  *outward = g / norm;
  return value;
}

}  // namespace dresskit::cloth
