#include "dresskit/mesh/triangle_mesh.h"

#include <cmath>

#include "dresskit/mesh/errors.h"

namespace dresskit::mesh {

Eigen::AlignedBox3d bounding_box(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (int i = 0; i < mesh.num_vertices(); ++i) box.extend(mesh.V.row(i).transpose());
  return box;
}

Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a);  // length = twice the area: area weighting
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (int i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0.0) N.row(i) /= len;
  }
  return N;
}

void validate_mesh(const TriangleMesh& mesh, const std::string& what) {
  const int nv = mesh.num_vertices();
  if (mesh.num_faces() == 0) throw InputError(what + ": mesh has no faces");
  for (int i = 0; i < nv; ++i) {
    if (!mesh.V.row(i).allFinite()) {
      throw InputError(what + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      if (v < 0 || v >= nv) {
        throw InputError(what + ": face " + std::to_string(f) + " refers to vertex " +
                         std::to_string(v) + " but the mesh has " + std::to_string(nv) +
                         " vertices");
      }
    }
  }
  auto check_rows = [&](Eigen::Index rows, const char* name) {
    if (rows != 0 && rows != nv) {
      throw InputError(what + ": " + name + " has " + std::to_string(rows) + " rows for " +
                       std::to_string(nv) + " vertices");
    }
  };
  check_rows(mesh.N.rows(), "normals");
  check_rows(mesh.UV.rows(), "texture coordinates");
  check_rows(mesh.labels.size(), "labels");
  check_rows(mesh.source_vertex.size(), "source vertex map");
  if (mesh.UV.size() > 0 && !mesh.UV.allFinite()) {
    throw InputError(what + ": a texture coordinate is not finite");
  }
  if (mesh.FTC.rows() != 0 || mesh.TC.rows() != 0) {
    if (mesh.FTC.rows() != mesh.num_faces())
      throw InputError(what + ": corner texture coordinates for " + std::to_string(mesh.FTC.rows()) + " faces of " +
                       std::to_string(mesh.num_faces()));
    if (mesh.FTC.minCoeff() < 0 || mesh.FTC.maxCoeff() >= mesh.TC.rows())
      throw InputError(what + ": a corner refers to a texture coordinate that the mesh does not have");
    if (!mesh.TC.allFinite()) throw InputError(what + ": a texture coordinate is not finite");
  }
  if (mesh.face_groups.size() != 0) {
    if (mesh.face_groups.size() != mesh.num_faces())
      throw InputError(what + ": face groups for " + std::to_string(mesh.face_groups.size()) + " faces of " +
                       std::to_string(mesh.num_faces()));
    if (mesh.face_groups.minCoeff() < -1 || mesh.face_groups.maxCoeff() >= int(mesh.group_names.size()))
      throw InputError(what + ": a face's group has no name");
  }
  if (mesh.N.size() > 0 && !mesh.N.allFinite()) {
    throw InputError(what + ": a vertex normal is not finite");
  }
  for (int q = 0; q < mesh.quads.rows(); ++q) {
    for (int k = 0; k < 4; ++k) {
      if (mesh.quads(q, k) < 0 || mesh.quads(q, k) >= nv) {
        throw InputError(what + ": quad " + std::to_string(q) + " has an index out of range");
      }
    }
  }
}

namespace {
template <typename Matrix>
Matrix select_rows(const Matrix& m, const std::vector<int>& rows) {
  if (m.rows() == 0) return m;
  Matrix out(static_cast<Eigen::Index>(rows.size()), m.cols());
  for (size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = m.row(rows[i]);
  return out;
}

// Renumbers the rows of an index matrix, keeping only rows whose corners all survive.
template <typename IndexMatrix>
IndexMatrix renumber(const IndexMatrix& faces, const std::vector<int>& old_to_new) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index r = 0; r < faces.rows(); ++r) {
    bool ok = true;
    for (Eigen::Index c = 0; c < faces.cols(); ++c) ok = ok && old_to_new[faces(r, c)] >= 0;
    if (ok) kept.push_back(r);
  }
  IndexMatrix out(static_cast<Eigen::Index>(kept.size()), faces.cols());
  for (size_t i = 0; i < kept.size(); ++i) {
    for (Eigen::Index c = 0; c < faces.cols(); ++c) {
      out(static_cast<Eigen::Index>(i), c) = old_to_new[faces(kept[i], c)];
    }
  }
  return out;
}
}  // namespace

TriangleMesh select_vertices(const TriangleMesh& mesh, const std::vector<bool>& keep,
                             std::vector<int>* old_to_new_out) {
  std::vector<int> old_to_new(mesh.V.rows(), -1), new_to_old;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (keep[i]) {
      old_to_new[i] = static_cast<int>(new_to_old.size());
      new_to_old.push_back(i);
    }
  }
  TriangleMesh out;
  out.V = select_rows(mesh.V, new_to_old);
  out.N = select_rows(mesh.N, new_to_old);
  out.UV = select_rows(mesh.UV, new_to_old);
  out.labels = select_rows(mesh.labels, new_to_old);
  out.source_vertex = select_rows(mesh.source_vertex, new_to_old);
  out.label_names = mesh.label_names;
  out.F = renumber(mesh.F, old_to_new);
  out.quads = renumber(mesh.quads, old_to_new);
  if (old_to_new_out) *old_to_new_out = std::move(old_to_new);
  return out;
}

Eigen::Vector3i label_colour(int label) {
  // Colour-blind-friendly palette (Okabe–Ito) followed by a few extra distinct colours.
  static const int palette[][3] = {{230, 159, 0},  {86, 180, 233},  {0, 158, 115}, {240, 228, 66},
                                   {0, 114, 178},  {213, 94, 0},    {204, 121, 167}, {120, 60, 160},
                                   {140, 200, 80}, {200, 60, 60}};
  if (label < 0) return {160, 160, 160};
  const int* c = palette[label % 10];
  return {c[0], c[1], c[2]};
}

TriangleMesh empty_mesh() {
  TriangleMesh m;
  m.V.resize(0, 3);
  m.F.resize(0, 3);
  return m;
}

void append_mesh(TriangleMesh& a, const TriangleMesh& b, const std::string& label_prefix) {
  const Eigen::Index nv = a.V.rows(), nf = a.F.rows();
  const int first_label = static_cast<int>(a.label_names.size());
  if (a.labels.size() != nv) a.labels = Eigen::VectorXi::Constant(nv, -1);
  a.V.conservativeResize(nv + b.V.rows(), 3);
  a.V.bottomRows(b.V.rows()) = b.V;
  a.F.conservativeResize(nf + b.F.rows(), 3);
  a.F.bottomRows(b.F.rows()) = b.F.array() + static_cast<int>(nv);
  a.labels.conservativeResize(nv + b.V.rows());
  for (Eigen::Index i = 0; i < b.V.rows(); ++i)
    a.labels(nv + i) = b.labels.size() == b.V.rows() && b.labels(i) >= 0 ? first_label + b.labels(i) : -1;
  for (const std::string& name : b.label_names) a.label_names.push_back(label_prefix + name);
  a.N.resize(0, 3);
  a.UV.resize(0, 2);
  a.quads.resize(0, 4);
  a.source_vertex.resize(0);
}

}  // namespace dresskit::mesh
