#include "dresskit/mesh/isosurface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace dresskit::mesh {
namespace {

// The six tetrahedra of a cube around its main diagonal 0–7 (corner c = i + 2j + 4k). Every face of
// the cube is then split along the diagonal from its lowest to its highest corner, so neighbouring
// cubes agree and the surface is watertight.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                             {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

std::uint64_t edge_key(std::int64_t a, std::int64_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
}

}  // namespace

TriangleMesh marching_tetrahedra(const ScalarField& field, const Eigen::AlignedBox3d& box,
                                 double spacing) {
  const Eigen::Vector3d origin = box.min();
  const Eigen::Vector3i n =
      ((box.max() - box.min()) / spacing).array().ceil().cast<int>().max(1).matrix() +
      Eigen::Vector3i::Ones();  // grid points per axis
  const std::int64_t count = std::int64_t(n.x()) * n.y() * n.z();
  auto point_index = [&](int i, int j, int k) {
    return (std::int64_t(k) * n.y() + j) * n.x() + i;
  };
  auto position = [&](std::int64_t id) {
    const int i = int(id % n.x()), j = int((id / n.x()) % n.y()), k = int(id / (std::int64_t(n.x()) * n.y()));
    return Eigen::Vector3d(origin + spacing * Eigen::Vector3d(i, j, k));
  };

  Eigen::VectorXd values(count);
  {
    // Evaluate one z-slab at a time to bound memory.
    const std::int64_t slab = std::int64_t(n.x()) * n.y();
    Eigen::MatrixX3d points(slab, 3);
    Eigen::VectorXd slab_values;
    for (int k = 0; k < n.z(); ++k) {
      for (int j = 0; j < n.y(); ++j)
        for (int i = 0; i < n.x(); ++i) points.row(std::int64_t(j) * n.x() + i) = position(point_index(i, j, k)).transpose();
      field(points, slab_values);
      values.segment(k * slab, slab) = slab_values;
    }
  }
  for (std::int64_t i = 0; i < count; ++i) {
    if (values(i) == 0.0) values(i) = 1e-12;  // keep the zero set off the grid points: manifold
  }

  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  std::unordered_map<std::uint64_t, int> edge_vertex;
  auto crossing = [&](std::int64_t a, std::int64_t b) {
    auto [it, inserted] = edge_vertex.emplace(edge_key(a, b), int(vertices.size()));
    if (inserted) {
      const double t = values(a) / (values(a) - values(b));
      vertices.push_back(position(a) + t * (position(b) - position(a)));
    }
    return it->second;
  };
  // Adds a triangle facing away from the inside (from inside corners towards outside corners).
  auto add = [&](int a, int b, int c, const Eigen::Vector3d& outward) {
    const Eigen::Vector3d nrm = (vertices[b] - vertices[a]).cross(vertices[c] - vertices[a]);
    if (nrm.dot(outward) >= 0.0) faces.emplace_back(a, b, c);
    else faces.emplace_back(a, c, b);
  };

  for (int k = 0; k + 1 < n.z(); ++k)
    for (int j = 0; j + 1 < n.y(); ++j)
      for (int i = 0; i + 1 < n.x(); ++i) {
        std::int64_t corner[8];
        for (int c = 0; c < 8; ++c) corner[c] = point_index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
        bool any_in = false, any_out = false;
        for (int c = 0; c < 8; ++c) (values(corner[c]) < 0.0 ? any_in : any_out) = true;
        if (!any_in || !any_out) continue;
        for (const auto& tet : kTets) {
          std::int64_t in[4], out[4];
          int nin = 0, nout = 0;
          for (int c : tet) {
            const std::int64_t id = corner[c];
            if (values(id) < 0.0) in[nin++] = id;
            else out[nout++] = id;
          }
          if (nin == 0 || nout == 0) continue;
          Eigen::Vector3d centre_in = Eigen::Vector3d::Zero(), centre_out = Eigen::Vector3d::Zero();
          for (int q = 0; q < nin; ++q) centre_in += position(in[q]) / nin;
          for (int q = 0; q < nout; ++q) centre_out += position(out[q]) / nout;
          const Eigen::Vector3d outward = centre_out - centre_in;
          if (nin == 1 || nout == 1) {
            const std::int64_t apex = nin == 1 ? in[0] : out[0];
            const std::int64_t* others = nin == 1 ? out : in;
            add(crossing(apex, others[0]), crossing(apex, others[1]), crossing(apex, others[2]), outward);
          } else {  // two in, two out: a quad, as two triangles
            const int q0 = crossing(in[0], out[0]), q1 = crossing(in[0], out[1]),
                      q2 = crossing(in[1], out[1]), q3 = crossing(in[1], out[0]);
            add(q0, q1, q2, outward);
            add(q0, q2, q3, outward);
          }
        }
      }

  TriangleMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (size_t v = 0; v < vertices.size(); ++v) mesh.V.row(static_cast<Eigen::Index>(v)) = vertices[v].transpose();
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) mesh.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return mesh;
}

TriangleMesh cut_mesh(const TriangleMesh& mesh, const Eigen::VectorXd& value_in) {
  Eigen::VectorXd value = value_in;
  for (Eigen::Index i = 0; i < value.size(); ++i) {
    if (value(i) == 0.0) value(i) = 1e-12;  // a vertex exactly on the line counts as cut away
  }
  const int nv = mesh.num_vertices();
  std::vector<Eigen::RowVector3d> V, N;
  std::vector<Eigen::RowVector2d> UV;
  std::vector<int> labels, source;
  for (int i = 0; i < nv; ++i) {
    V.push_back(mesh.V.row(i));
    if (mesh.N.rows()) N.push_back(mesh.N.row(i));
    if (mesh.UV.rows()) UV.push_back(mesh.UV.row(i));
    if (mesh.has_labels()) labels.push_back(mesh.labels(i));
    source.push_back(mesh.source_vertex.size() ? mesh.source_vertex(i) : i);
  }
  std::unordered_map<std::uint64_t, int> edge_vertex;
  // The new vertex on edge kept–dropped (kept has value < 0).
  auto crossing = [&](int kept, int dropped) {
    auto [it, inserted] = edge_vertex.emplace(edge_key(kept, dropped), int(V.size()));
    if (inserted) {
      const double t = value(kept) / (value(kept) - value(dropped));
      V.push_back((1 - t) * mesh.V.row(kept) + t * mesh.V.row(dropped));
      if (mesh.N.rows()) N.push_back(((1 - t) * mesh.N.row(kept) + t * mesh.N.row(dropped)).normalized());
      if (mesh.UV.rows()) UV.push_back((1 - t) * mesh.UV.row(kept) + t * mesh.UV.row(dropped));
      if (mesh.has_labels()) labels.push_back(mesh.labels(kept));
      source.push_back(-1);
    }
    return it->second;
  };
  std::vector<Eigen::Vector3i> faces;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    int c[3] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    const int kept = (value(c[0]) < 0) + (value(c[1]) < 0) + (value(c[2]) < 0);
    if (kept == 0) continue;
    if (kept == 3) {
      faces.emplace_back(c[0], c[1], c[2]);
      continue;
    }
    // Rotate (keeping orientation) so that c[0] is the odd one out: the only kept vertex (kept == 1)
    // or the only dropped one (kept == 2).
    const bool odd_is_kept = kept == 1;
    while ((value(c[0]) < 0) != odd_is_kept) std::rotate(c, c + 1, c + 3);
    if (odd_is_kept) {
      faces.emplace_back(c[0], crossing(c[0], c[1]), crossing(c[0], c[2]));
    } else {
      const int e1 = crossing(c[1], c[0]), e2 = crossing(c[2], c[0]);
      faces.emplace_back(e1, c[1], c[2]);
      faces.emplace_back(e1, c[2], e2);
    }
  }
  TriangleMesh out;
  const Eigen::Index n = static_cast<Eigen::Index>(V.size());
  out.V.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) out.V.row(i) = V[i];
  if (!N.empty()) {
    out.N.resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) out.N.row(i) = N[i];
  }
  if (!UV.empty()) {
    out.UV.resize(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) out.UV.row(i) = UV[i];
  }
  if (!labels.empty()) out.labels = Eigen::Map<Eigen::VectorXi>(labels.data(), n);
  out.source_vertex = Eigen::Map<Eigen::VectorXi>(source.data(), n);
  out.label_names = mesh.label_names;
  out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) out.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  // Drop the vertices that no kept face uses.
  std::vector<bool> used(static_cast<size_t>(n), false);
  for (int f = 0; f < out.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) used[out.F(f, k)] = true;
  return select_vertices(out, used);
}

double project_to_zero_set(const ScalarField& field, Eigen::MatrixX3d& V, int iterations,
                           double max_step) {
  const Eigen::Index n = V.rows();
  const double h = 1e-5;  // [m] central-difference step
  Eigen::MatrixX3d samples(7 * n, 3);
  Eigen::VectorXd f;
  double worst = 0.0;
  for (int it = 0; it <= iterations; ++it) {
    for (int k = 0; k < 7; ++k) {
      samples.middleRows(k * n, n) = V;
      if (k > 0) samples.middleRows(k * n, n).col((k - 1) / 2).array() += (k % 2 ? h : -h);
    }
    field(samples, f);
    worst = f.head(n).cwiseAbs().maxCoeff();
    if (it == iterations) break;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d grad((f(n + i) - f(2 * n + i)) / (2 * h), (f(3 * n + i) - f(4 * n + i)) / (2 * h),
                                 (f(5 * n + i) - f(6 * n + i)) / (2 * h));
      const double g2 = grad.squaredNorm();
      if (g2 < 1e-12) continue;
      Eigen::Vector3d step = -f(i) * grad / g2;
      if (step.norm() > max_step) step *= max_step / step.norm();
      V.row(i) += step.transpose();
    }
  }
  return worst;
}

}  // namespace dresskit::mesh
