// Mesh writers. OBJ and PLY are written here rather than through assimp's exporters because ours keep
// the exact vertex order, the quads and full double precision (shortest round-trip numbers), and add
// no material files; GLB goes through assimp's glTF 2 exporter.
#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <unistd.h>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "internal.h"

namespace dresskit::mesh {
namespace fs = std::filesystem;

const std::vector<std::string>& saveable_extensions() {
  static const std::vector<std::string> ext = {"obj", "ply", "off", "stl", "glb", "gltf", "fbx"};
  return ext;
}

bool is_saveable(const std::string& path) {
  const auto& ok = saveable_extensions();
  return std::find(ok.begin(), ok.end(), detail::lower_extension(path)) != ok.end();
}

namespace {

// Runs write(tmp_path) in a private temporary folder beside the destination, with the destination's
// file name (so that sidecar files such as a glTF's .bin keep the right name), then moves every file
// written there into place. On any failure the temporary folder is removed and nothing is left.
template <typename Write>
void write_via_temporary(const std::string& path, Write write) {
  const fs::path destination(path);
  const fs::path dir = destination.parent_path().empty() ? fs::path(".") : destination.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw OutputError(path + ": no such directory");
  const fs::path tmp = dir / (".dresskit-tmp-" + std::to_string(::getpid()) + "-" + destination.filename().string());
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec)) throw OutputError(path + ": cannot write: " + ec.message());
  try {
    write((tmp / destination.filename()).string());
    for (const auto& entry : fs::directory_iterator(tmp)) {
      fs::rename(entry.path(), dir / entry.path().filename(), ec);
      if (ec) throw OutputError(path + ": cannot write: " + ec.message());
    }
    fs::remove(tmp, ec);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

void append_number(std::string& out, double value) {
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, result.ptr);
}

void append_int(std::string& out, long value) {
  char buf[24];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, result.ptr);
}


// The faces to write: each quad once (when both of its triangles are in F), the other triangles as
// they are; with `texture`, each polygon's corner texture coordinate rows (TriangleMesh::FTC); with
// `face`, each polygon's first face.
std::vector<std::vector<int>> output_polygons(const TriangleMesh& m, std::vector<std::vector<int>>* texture = nullptr,
                                              std::vector<int>* face = nullptr) {
  std::map<std::array<int, 3>, int> quad_of_triangle;
  const auto tri_key = detail::directed_triangle_key;
  for (int q = 0; q < m.quads.rows(); ++q) {
    const int a = m.quads(q, 0), b = m.quads(q, 1), c = m.quads(q, 2), d = m.quads(q, 3);
    quad_of_triangle[tri_key(a, b, c)] = q;
    quad_of_triangle[tri_key(a, c, d)] = q;
  }
  std::vector<int> found(m.quads.rows(), 0);
  std::vector<int> face_quad(m.F.rows(), -1);
  for (int f = 0; f < m.num_faces(); ++f) {
    auto it = quad_of_triangle.find(tri_key(m.F(f, 0), m.F(f, 1), m.F(f, 2)));
    if (it != quad_of_triangle.end()) {
      face_quad[f] = it->second;
      ++found[it->second];
    }
  }
  std::vector<std::vector<int>> polygons;
  std::vector<std::array<int, 2>> quad_faces(m.quads.rows(), {-1, -1});  // each quad's two triangles
  for (int f = 0; f < m.num_faces(); ++f)
    if (face_quad[f] >= 0) quad_faces[face_quad[f]][quad_faces[face_quad[f]][0] < 0 ? 0 : 1] = f;
  std::vector<bool> written(m.quads.rows(), false);
  // A quad corner's texture coordinate: from whichever of its two triangles has that corner.
  auto corner_texture = [&](int f, int g, int v) {
    for (int face : {f, g})
      for (int k = 0; k < 3; ++k)
        if (m.F(face, k) == v) return m.FTC(face, k);
    return 0;
  };
  if (texture) texture->clear();
  if (face) face->clear();
  for (int f = 0; f < m.num_faces(); ++f) {
    const int q = face_quad[f];
    if (q >= 0 && found[q] == 2) {
      if (written[q]) continue;
      written[q] = true;
      polygons.push_back({m.quads(q, 0), m.quads(q, 1), m.quads(q, 2), m.quads(q, 3)});
      if (face) face->push_back(f);
      if (texture) {
        texture->emplace_back();
        for (int v : polygons.back()) texture->back().push_back(corner_texture(quad_faces[q][0], quad_faces[q][1], v));
      }
    } else {
      polygons.push_back({m.F(f, 0), m.F(f, 1), m.F(f, 2)});
      if (face) face->push_back(f);
      if (texture) texture->push_back({m.FTC(f, 0), m.FTC(f, 1), m.FTC(f, 2)});
    }
  }
  return polygons;
}

// Corner texture coordinates that fit the faces (a mesh whose faces changed after they were set has
// none).
bool has_corner_texture(const TriangleMesh& m) {
  return m.FTC.rows() > 0 && m.FTC.rows() == m.num_faces() && m.FTC.minCoeff() >= 0 && m.FTC.maxCoeff() < m.TC.rows();
}

std::string obj_text(const TriangleMesh& m) {
  std::string out = "# dresskit OBJ\n";
  out.reserve(static_cast<size_t>(m.num_vertices()) * 80 + static_cast<size_t>(m.num_faces()) * 30);
  for (int i = 0; i < m.num_vertices(); ++i) {
    out += "v";
    for (int k = 0; k < 3; ++k) (out += ' ', append_number(out, m.V(i, k)));
    out += '\n';
  }
  // Corner texture coordinates replace the per-vertex ones.
  const bool corners = has_corner_texture(m);
  const Eigen::MatrixX2d& texture = corners ? m.TC : m.UV;
  for (int i = 0; i < texture.rows(); ++i) {
    out += "vt";
    for (int k = 0; k < 2; ++k) (out += ' ', append_number(out, texture(i, k)));
    out += '\n';
  }
  for (int i = 0; i < m.N.rows(); ++i) {
    out += "vn";
    for (int k = 0; k < 3; ++k) (out += ' ', append_number(out, m.N(i, k)));
    out += '\n';
  }
  const bool n = m.N.rows() > 0;
  auto corner = [&](int v, int t) {
    out += ' ';
    append_int(out, v + 1);
    if (t >= 0 || n) {
      out += '/';
      if (t >= 0) append_int(out, t + 1);
      if (n) (out += '/', append_int(out, v + 1));
    }
  };
  const bool uv = m.UV.rows() > 0;
  const bool groups = m.face_groups.size() == m.num_faces() && m.face_groups.size() > 0;
  std::vector<std::vector<int>> corner_rows;
  std::vector<int> first_face;
  const auto polygons = output_polygons(m, corners ? &corner_rows : nullptr, &first_face);
  int group = -1;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    // A new run of faces in one group starts a group line (`g` alone: no group); a name's blanks
    // become underscores, since a `g` line's blanks separate groups.
    const int g = groups && m.face_groups(first_face[p]) < static_cast<int>(m.group_names.size())
                      ? m.face_groups(first_face[p])
                      : -1;
    if (g != group) {
      std::string name = g >= 0 ? m.group_names[static_cast<std::size_t>(g)] : "";
      std::replace_if(name.begin(), name.end(), [](unsigned char c) { return std::isspace(c) != 0; }, '_');
      out += name.empty() ? "g\n" : "g " + name + '\n';
    }
    group = g;
    out += 'f';
    for (std::size_t k = 0; k < polygons[p].size(); ++k) {
      const int v = polygons[p][k];
      corner(v, corners ? corner_rows[p][k] : uv ? v : -1);
    }
    out += '\n';
  }
  return out;
}

template <typename T>
void append_binary(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // little endian on every platform we build for
  out.append(bytes, sizeof(T));
}

std::string ply_bytes(const TriangleMesh& m) {
  const bool colours = m.has_labels(), normals = m.N.rows() > 0;
  const auto polygons = output_polygons(m);
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment dresskit: metres, +Y up\n";
  out += "element vertex " + std::to_string(m.num_vertices()) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  if (normals) out += "property double nx\nproperty double ny\nproperty double nz\n";
  if (colours) out += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty int label\n";
  out += "element face " + std::to_string(polygons.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < m.num_vertices(); ++i) {
    for (int k = 0; k < 3; ++k) append_binary<double>(out, m.V(i, k));
    if (normals) for (int k = 0; k < 3; ++k) append_binary<double>(out, m.N(i, k));
    if (colours) {
      const Eigen::Vector3i c = label_colour(m.labels(i));
      for (int k = 0; k < 3; ++k) append_binary<unsigned char>(out, static_cast<unsigned char>(c(k)));
      append_binary<int>(out, m.labels(i));
    }
  }
  for (const auto& polygon : polygons) {
    append_binary<unsigned char>(out, static_cast<unsigned char>(polygon.size()));
    for (int v : polygon) append_binary<int>(out, v);
  }
  return out;
}

std::string off_text(const TriangleMesh& m) {
  const auto polygons = output_polygons(m);
  std::string out = "OFF\n# dresskit: metres, +Y up\n";
  out += std::to_string(m.num_vertices()) + " " + std::to_string(polygons.size()) + " 0\n";
  for (int i = 0; i < m.num_vertices(); ++i) {
    for (int k = 0; k < 3; ++k) (append_number(out, m.V(i, k)), out += k < 2 ? ' ' : '\n');
  }
  for (const auto& polygon : polygons) {
    append_int(out, long(polygon.size()));
    for (int v : polygon) (out += ' ', append_int(out, v));
    out += '\n';
  }
  return out;
}

// Binary STL: single precision, one facet per triangle (STL has no shared vertices).
std::string stl_bytes(const TriangleMesh& m) {
  std::string out(80, '\0');
  const char header[] = "dresskit binary STL, metres, +Y up";
  out.replace(0, sizeof header - 1, header);
  append_binary<std::uint32_t>(out, static_cast<std::uint32_t>(m.num_faces()));
  for (int f = 0; f < m.num_faces(); ++f) {
    const Eigen::RowVector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).normalized();
    for (const Eigen::RowVector3d& p : {n, a, b, c})
      for (int k = 0; k < 3; ++k) append_binary<float>(out, static_cast<float>(p(k)));
    append_binary<std::uint16_t>(out, 0);
  }
  return out;
}

// One mesh of an assimp scene: positions, normals and texture coordinates in single precision,
// colours from labels. With corner texture coordinates, a vertex is written once for each of its
// texture coordinates (glTF has attributes per vertex only); its normal stays the welded one's.
aiMesh* assimp_mesh(const TriangleMesh& m, const std::string& name) {
  aiMesh* mesh = new aiMesh();
  mesh->mName = aiString(name);
  mesh->mMaterialIndex = 0;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  // The written vertices: (vertex, texture coordinate row or -1), and each face corner's.
  std::vector<std::pair<int, int>> written;
  Eigen::MatrixX3i corners = m.F;
  const bool corner_texture = has_corner_texture(m);
  if (corner_texture) {
    std::map<std::pair<int, int>, int> index;
    for (int f = 0; f < m.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const auto key = std::make_pair(m.F(f, k), m.FTC(f, k));
        const auto [it, fresh] = index.emplace(key, static_cast<int>(written.size()));
        if (fresh) written.push_back(key);
        corners(f, k) = it->second;
      }
  } else {
    for (int i = 0; i < m.num_vertices(); ++i) written.emplace_back(i, m.UV.rows() > 0 ? i : -1);
  }
  const Eigen::MatrixX2d& texture = corner_texture ? m.TC : m.UV;
  mesh->mNumVertices = static_cast<unsigned>(written.size());
  mesh->mVertices = new aiVector3D[mesh->mNumVertices];
  const Eigen::MatrixX3d N = m.N.rows() ? m.N : vertex_normals(m.V, m.F);
  mesh->mNormals = new aiVector3D[mesh->mNumVertices];
  if (m.has_labels()) mesh->mColors[0] = new aiColor4D[mesh->mNumVertices];
  if (texture.rows() > 0) {
    mesh->mTextureCoords[0] = new aiVector3D[mesh->mNumVertices];
    mesh->mNumUVComponents[0] = 2;
  }
  for (unsigned w = 0; w < mesh->mNumVertices; ++w) {
    const auto [i, t] = written[w];
    mesh->mVertices[w] = aiVector3D(static_cast<float>(m.V(i, 0)), static_cast<float>(m.V(i, 1)),
                                    static_cast<float>(m.V(i, 2)));
    mesh->mNormals[w] = aiVector3D(static_cast<float>(N(i, 0)), static_cast<float>(N(i, 1)),
                                   static_cast<float>(N(i, 2)));
    if (t >= 0)
      mesh->mTextureCoords[0][w] = aiVector3D(static_cast<float>(texture(t, 0)), static_cast<float>(texture(t, 1)), 0.f);
    if (m.has_labels()) {
      const Eigen::Vector3i c = label_colour(m.labels(i));
      mesh->mColors[0][w] = aiColor4D(c(0) / 255.f, c(1) / 255.f, c(2) / 255.f, 1.f);
    }
  }
  mesh->mNumFaces = static_cast<unsigned>(m.num_faces());
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    mesh->mFaces[f].mNumIndices = 3;
    mesh->mFaces[f].mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) mesh->mFaces[f].mIndices[k] = static_cast<unsigned>(corners(f, k));
  }
  return mesh;
}

// glTF 2 (binary or text + .bin) and FBX through assimp's exporters: one node per mesh, named.
void write_with_assimp(const std::vector<NamedMesh>& meshes, const std::string& path, const char* format) {
  aiScene scene;  // owns everything below and frees it in its destructor
  const unsigned n = static_cast<unsigned>(meshes.size());
  scene.mRootNode = new aiNode("dresskit");
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMeshes = n;
  scene.mMeshes = new aiMesh*[n];
  scene.mRootNode->mNumChildren = n;
  scene.mRootNode->mChildren = new aiNode*[n];
  for (unsigned k = 0; k < n; ++k) {
    scene.mMeshes[k] = assimp_mesh(meshes[k].mesh, meshes[k].name);
    aiNode* node = new aiNode(meshes[k].name);
    node->mParent = scene.mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{k};
    scene.mRootNode->mChildren[k] = node;
  }
  Assimp::Exporter exporter;
  if (exporter.Export(&scene, format, path) != aiReturn_SUCCESS) {
    throw OutputError(path + ": cannot write " + format + ": " + exporter.GetErrorString());
  }
}

void write_bytes(const std::string& path, const std::string& contents) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputError(path + ": cannot open for writing");
  out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
  out.close();
  if (!out) throw OutputError(path + ": write failed");
}

}  // namespace

void save_mesh(const TriangleMesh& mesh, const std::string& path) {
  if (!mesh.V.allFinite()) throw OutputError(path + ": refusing to write a non-finite coordinate");
  const std::string ext = detail::lower_extension(path);
  std::function<void(const std::string&)> write;
  if (ext == "obj") write = [&](const std::string& tmp) { write_bytes(tmp, obj_text(mesh)); };
  else if (ext == "ply") write = [&](const std::string& tmp) { write_bytes(tmp, ply_bytes(mesh)); };
  else if (ext == "off") write = [&](const std::string& tmp) { write_bytes(tmp, off_text(mesh)); };
  else if (ext == "stl") write = [&](const std::string& tmp) { write_bytes(tmp, stl_bytes(mesh)); };
  else if (ext == "glb" || ext == "gltf" || ext == "fbx") return save_scene({{"mesh", mesh}}, path);
  else throw OutputError(path + ": cannot save '." + ext + "' files (supported: obj, ply, off, stl, glb, gltf, fbx)");
  write_via_temporary(path, write);
}

void save_scene(const std::vector<NamedMesh>& meshes, const std::string& path) {
  for (const NamedMesh& m : meshes)
    if (!m.mesh.V.allFinite()) throw OutputError(path + ": refusing to write a non-finite coordinate (" + m.name + ")");
  const std::string ext = detail::lower_extension(path);
  // ASCII FBX: the binary FBX exporter of assimp 5.2 writes files that its own reader rejects
  // ("FBX-Tokenize block offset is out of range"; assimp GitHub #4686).
  const char* format = ext == "glb" ? "glb2" : ext == "gltf" ? "gltf2" : ext == "fbx" ? "fbxa" : nullptr;
  if (!format) throw OutputError(path + ": cannot save a scene of meshes as '." + ext + "' (supported: glb, gltf, fbx)");
  write_via_temporary(path, [&](const std::string& tmp) { write_with_assimp(meshes, tmp, format); });
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  write_via_temporary(path, [&](const std::string& tmp) { write_bytes(tmp, contents); });
}

}  // namespace dresskit::mesh
