// Mesh loading through assimp. For OBJ the toolkit keeps the file's own vertex order: assimp splits
// vertices at UV seams and drops unused ones, so the `v` lines are read here too (in double precision)
// and every assimp vertex is mapped back to its `v` line by position.
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <map>
#include <unordered_map>

#include "dresskit/mesh/names.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/topology.h"
#include "internal.h"

namespace dresskit::mesh {
namespace fs = std::filesystem;

Units Units::parse(const std::string& text) {
  if (text == "m") return {1.0, "m"};
  if (text == "dm") return {0.1, "dm"};
  if (text == "cm") return {0.01, "cm"};
  if (text == "mm") return {0.001, "mm"};
  char* end = nullptr;
  const double scale = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(scale) || scale <= 0.0) {
    throw InputError("units: '" + text +
                     "' is not m, dm, cm, mm or a positive number of metres per file unit");
  }
  return {scale, text + " m"};
}

std::string units_for_body(double file_extent) {
  for (const char* name : {"m", "dm", "cm", "mm"}) {
    const double metres = file_extent * Units::parse(name).metres_per_unit;
    if (metres >= 0.5 && metres <= 2.5) return name;
  }
  return "";
}

const NameTable<UpAxis> kUpAxes = {{"+x", UpAxis::pos_x}, {"x", UpAxis::pos_x}, {"-x", UpAxis::neg_x},
    {"+y", UpAxis::pos_y}, {"y", UpAxis::pos_y}, {"-y", UpAxis::neg_y}, {"+z", UpAxis::pos_z}, {"z", UpAxis::pos_z},
    {"-z", UpAxis::neg_z}};
UpAxis parse_up_axis(const std::string& text) { return parse_name(text, kUpAxes, "up axis"); }
std::string to_string(UpAxis axis) { return name_of(axis, kUpAxes); }

const std::vector<std::string>& loadable_extensions() {
  static const std::vector<std::string> ext = {"obj", "ply", "off", "stl", "gltf", "glb", "fbx"};
  return ext;
}

Eigen::Matrix3d up_rotation(UpAxis up) {
  Eigen::Matrix3d R;
  switch (up) {
    case UpAxis::pos_y: R.setIdentity(); break;
    case UpAxis::neg_y: R << 1, 0, 0, 0, -1, 0, 0, 0, -1; break;
    case UpAxis::pos_z: R << 1, 0, 0, 0, 0, 1, 0, -1, 0; break;
    case UpAxis::neg_z: R << 1, 0, 0, 0, 0, -1, 0, 1, 0; break;
    case UpAxis::pos_x: R << 0, -1, 0, 1, 0, 0, 0, 0, 1; break;
    case UpAxis::neg_x: R << 0, 1, 0, -1, 0, 0, 0, 0, 1; break;
  }
  return R;
}

Eigen::MatrixX3d to_file_frame(const Eigen::MatrixX3d& V, const LoadOptions& options) {
  // Loading applied x_toolkit = s R x_file (row vectors: V_toolkit = s V_file Rᵀ); R is a rotation.
  return V * up_rotation(options.up) / options.units.metres_per_unit;
}

namespace {

// The `v` lines of an OBJ file, in order and in double precision. Throws on a malformed or
// non-finite coordinate, or a face line of fewer than three corners, naming the line.
Eigen::MatrixX3d read_obj_vertex_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<double> xyz;
  std::string line;
  long line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.size() >= 2 && line[0] == 'f' && (line[1] == ' ' || line[1] == '\t')) {
      // A face of fewer than three corners (a file cut short in a face line) is named by its line,
      // rather than by assimp's structure check, which names no line.
      std::istringstream corners(line.substr(2));
      int count = 0;
      for (std::string corner; corners >> corner && corner[0] != '#';) ++count;
      if (count < 3)
        throw InputError(path + ":" + std::to_string(line_number) + ": face line with " + std::to_string(count) +
                         (count == 1 ? " corner" : " corners") + " (a face needs three; is the file cut short?)");
      continue;
    }
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
    const char* p = line.c_str() + 2;
    for (int k = 0; k < 3; ++k) {
      char* end = nullptr;
      const double value = std::strtod(p, &end);
      if (end == p) {
        throw InputError(path + ":" + std::to_string(line_number) +
                         ": vertex line does not hold three numbers");
      }
      if (!std::isfinite(value)) {
        throw InputError(path + ":" + std::to_string(line_number) +
                         ": non-finite vertex coordinate");
      }
      xyz.push_back(value);
      p = end;
    }
  }
  Eigen::MatrixX3d V(static_cast<Eigen::Index>(xyz.size() / 3), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) V.row(i) << xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2];
  return V;
}

// Maps positions (as assimp read them, in single precision) to rows of the file's vertex table: the
// nearest file vertex within a tolerance that covers single-precision rounding.
class PositionIndex {
 public:
  explicit PositionIndex(const Eigen::MatrixX3d& V) : V_(V) {
    const double diag = V.rows() ? (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm() : 1.0;
    const double max_abs = V.rows() ? V.cwiseAbs().maxCoeff() : 1.0;
    cell_ = std::max({1e-6 * diag, 8.0 * FLT_EPSILON * max_abs, 1e-12});
    map_.reserve(static_cast<size_t>(V.rows()));
    for (int i = 0; i < V.rows(); ++i) map_.emplace(key(cell_of(V.row(i))), i);
  }
  int find(const Eigen::RowVector3d& p) const {
    const Eigen::Vector3i c = cell_of(p);
    const double limit = cell_ * cell_;
    int best = -1;
    double best_d = 0.0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto range = map_.equal_range(key(c + Eigen::Vector3i(dx, dy, dz)));
          for (auto it = range.first; it != range.second; ++it) {
            const double d = (V_.row(it->second) - p).squaredNorm();
            if (d > limit) continue;
            // Ties (duplicate `v` lines) go to the first line, as in the file.
            if (best < 0 || d < best_d || (d == best_d && it->second < best)) {
              best_d = d;
              best = it->second;
            }
          }
        }
    return best;
  }

 private:
  // Cells are clamped to ±10⁹ so that a cell and its neighbours stay within int whatever the
  // coordinates (a mesh far from the origin, or huge ones): far cells then share a boundary cell,
  // which costs distance checks, not correctness.
  Eigen::Vector3i cell_of(const Eigen::RowVector3d& p) const {
    return (p / cell_)
        .array()
        .unaryExpr([](double c) { return std::isfinite(c) ? std::clamp(std::floor(c), -1e9, 1e9) : 0.0; })
        .cast<int>()
        .transpose();
  }
  static std::uint64_t key(const Eigen::Vector3i& c) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.x()) * 73856093u) ^
            (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.y())) * 19349663u) ^
            (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.z())) * 83492791u));
  }
  const Eigen::MatrixX3d& V_;
  double cell_ = 1.0;
  std::unordered_multimap<std::uint64_t, int> map_;
};

void check_readable(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": file not found");
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": not a regular file");
  const std::string ext = detail::lower_extension(path);
  const auto& known = loadable_extensions();
  if (std::find(known.begin(), known.end(), ext) == known.end()) {
    std::string list;
    for (const auto& e : known) list += (list.empty() ? "" : ", ") + e;
    throw InputError(path + ": unsupported extension '" + ext + "' (supported: " + list + ")");
  }
  if (fs::file_size(path, ec) == 0) throw InputError(path + ": empty file");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw InputError(path + ": cannot open for reading");
  detail::check_declared_counts(path);
}

// Vertex data gathered from the scene graph, with node transforms applied.
struct Gathered {
  std::vector<Eigen::Vector3d> positions, normals;
  std::vector<Eigen::Vector2d> uvs;
  std::vector<std::vector<int>> polygons;
  bool all_normals = true, all_uvs = true;
};

void gather(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, Gathered& out,
            const std::string& path) {
  const aiMatrix4x4 transform = parent * node->mTransformation;
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T(r, c) = transform[r][c];
  const Eigen::Matrix3d normal_matrix = T.topLeftCorner<3, 3>().inverse().transpose();
  for (unsigned m = 0; m < node->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    const int base = static_cast<int>(out.positions.size());
    const bool has_n = mesh->HasNormals(), has_uv = mesh->HasTextureCoords(0);
    out.all_normals = out.all_normals && has_n;
    out.all_uvs = out.all_uvs && has_uv;
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& p = mesh->mVertices[i];
      out.positions.push_back((T * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>());
      if (has_n) {
        const aiVector3D& n = mesh->mNormals[i];
        out.normals.push_back((normal_matrix * Eigen::Vector3d(n.x, n.y, n.z)).normalized());
      }
      if (has_uv) out.uvs.emplace_back(mesh->mTextureCoords[0][i].x, mesh->mTextureCoords[0][i].y);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines are not surface
      std::vector<int> polygon(face.mNumIndices);
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          throw InputError(path + ": face index " + std::to_string(face.mIndices[k]) +
                           " out of range");
        }
        polygon[k] = base + static_cast<int>(face.mIndices[k]);
      }
      out.polygons.push_back(std::move(polygon));
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) gather(scene, node->mChildren[c], transform, out, path);
}

}  // namespace

TriangleMesh load_mesh(const std::string& path, const LoadOptions& options) {
  check_readable(path);
  const bool is_obj = detail::lower_extension(path) == "obj";
  Eigen::MatrixX3d file_vertices;
  if (is_obj) file_vertices = read_obj_vertex_lines(path);

  Assimp::Importer importer;
  // No triangulation here: quads are kept for the cloth's shear springs and triangulated below.
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode) {
    std::string why = importer.GetErrorString();
    std::replace(why.begin(), why.end(), '\n', ' ');
    // assimp's checks of its own structures, said as what they mean for the file.
    if (why.find("mNumMeshes is 0") != std::string::npos || why.find("contains no faces") != std::string::npos)
      throw InputError(path + ": mesh has no faces");
    throw InputError(path + ": cannot read mesh: " + (why.empty() ? "unknown reason" : why));
  }
  Gathered g;
  gather(scene, scene->mRootNode, aiMatrix4x4(), g, path);
  if (g.polygons.empty()) throw InputError(path + ": mesh has no faces");

  // Vertex table and the map from gathered vertices to it.
  TriangleMesh mesh;
  std::vector<int> to_row(g.positions.size());
  if (is_obj) {
    const PositionIndex index(file_vertices);
    mesh.V = file_vertices;
    for (size_t i = 0; i < g.positions.size(); ++i) {
      to_row[i] = index.find(g.positions[i].transpose());
      if (to_row[i] < 0) {
        throw InputError(path + ": a face corner matches no vertex line (file changed while read?)");
      }
    }
  } else if (detail::lower_extension(path) == "stl") {
    // STL stores every triangle's corners anew (and a normal per face, so assimp keeps them apart):
    // corners at one position are one vertex, numbered in the order first met.
    std::map<std::array<double, 3>, int> row_of;
    std::vector<Eigen::Vector3d> rows;
    for (size_t i = 0; i < g.positions.size(); ++i) {
      const Eigen::Vector3d& p = g.positions[i];
      const auto [at, fresh] = row_of.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, static_cast<int>(rows.size()));
      if (fresh) rows.push_back(p);
      to_row[i] = at->second;
    }
    mesh.V.resize(static_cast<Eigen::Index>(rows.size()), 3);
    for (size_t r = 0; r < rows.size(); ++r) mesh.V.row(static_cast<Eigen::Index>(r)) = rows[r].transpose();
  } else {
    mesh.V.resize(static_cast<Eigen::Index>(g.positions.size()), 3);
    for (size_t i = 0; i < g.positions.size(); ++i) {
      mesh.V.row(static_cast<Eigen::Index>(i)) = g.positions[i].transpose();
      to_row[i] = static_cast<int>(i);
    }
  }
  const Eigen::Index nv = mesh.V.rows();
  mesh.source_vertex = Eigen::VectorXi::LinSpaced(nv, 0, static_cast<int>(nv) - 1);
  // Per-vertex normals and UVs: the first gathered vertex that maps to a row wins (UV seams split).
  if (g.all_normals && !g.normals.empty()) mesh.N = Eigen::MatrixX3d::Zero(nv, 3);
  if (g.all_uvs && !g.uvs.empty()) mesh.UV = Eigen::MatrixX2d::Zero(nv, 2);
  std::vector<bool> seen(nv, false);
  for (size_t i = 0; i < g.positions.size(); ++i) {
    const int row = to_row[i];
    if (seen[row]) continue;
    seen[row] = true;
    if (mesh.N.rows()) mesh.N.row(row) = g.normals[i].transpose();
    if (mesh.UV.rows()) mesh.UV.row(row) = g.uvs[i].transpose();
  }

  // A vertex with two texture coordinates lies on a UV seam: the faces' corners then keep their
  // own (TriangleMesh::TC, FTC), so that the writers can keep the seam.
  bool seams = false;
  for (size_t i = 0; i < g.positions.size() && mesh.UV.rows() && !seams; ++i)
    seams = mesh.UV.row(to_row[i]) != g.uvs[i].transpose();
  std::vector<int> tc_row(seams ? g.uvs.size() : 0, -1);
  std::vector<Eigen::Vector2d> tc;
  std::vector<Eigen::Vector3i> tris, tri_tc;
  std::vector<Eigen::Vector4i> quads;
  for (const auto& polygon : g.polygons) {
    std::vector<int> p(polygon.size()), t(polygon.size(), 0);
    for (size_t k = 0; k < p.size(); ++k) {
      p[k] = to_row[polygon[k]];
      if (!seams) continue;
      int& row = tc_row[static_cast<size_t>(polygon[k])];
      if (row < 0) row = static_cast<int>(tc.size()), tc.push_back(g.uvs[static_cast<size_t>(polygon[k])]);
      t[k] = row;
    }
    std::vector<Eigen::Vector3d> corners;
    for (int v : p) corners.push_back(mesh.V.row(v).transpose());
    const auto triangles = triangulate_polygon(corners);
    if (p.size() == 4 && triangles.size() == 2) {
      // A quad is kept (its diagonals are the cloth's shear springs) starting at the corner its
      // diagonal leaves from, so that its triangles are (a, b, c) and (a, c, d) as the writers expect.
      auto in_both = [&](int corner) {
        return std::count(triangles[0].begin(), triangles[0].end(), corner) +
                   std::count(triangles[1].begin(), triangles[1].end(), corner) == 2;
      };
      const int a = in_both(0) ? 0 : 1;
      quads.emplace_back(p[a], p[(a + 1) % 4], p[(a + 2) % 4], p[(a + 3) % 4]);
    }
    for (const auto& tri : triangles) {
      tris.emplace_back(p[tri[0]], p[tri[1]], p[tri[2]]);
      tri_tc.emplace_back(t[tri[0]], t[tri[1]], t[tri[2]]);
    }
  }
  mesh.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t f = 0; f < tris.size(); ++f) mesh.F.row(static_cast<Eigen::Index>(f)) = tris[f].transpose();
  if (seams) {
    mesh.TC.resize(static_cast<Eigen::Index>(tc.size()), 2);
    for (size_t r = 0; r < tc.size(); ++r) mesh.TC.row(static_cast<Eigen::Index>(r)) = tc[r].transpose();
    mesh.FTC.resize(mesh.F.rows(), 3);
    for (size_t f = 0; f < tri_tc.size(); ++f) mesh.FTC.row(static_cast<Eigen::Index>(f)) = tri_tc[f].transpose();
  }
  mesh.quads.resize(static_cast<Eigen::Index>(quads.size()), 4);
  for (size_t q = 0; q < quads.size(); ++q) mesh.quads.row(static_cast<Eigen::Index>(q)) = quads[q].transpose();

  // Units and axes: metres, +Y up.
  const Eigen::Matrix3d R = up_rotation(options.up);
  mesh.V = (mesh.V * R.transpose()) * options.units.metres_per_unit;
  if (mesh.N.rows()) mesh.N = mesh.N * R.transpose();
  validate_mesh(mesh, path);
  return mesh;
}

}  // namespace dresskit::mesh
