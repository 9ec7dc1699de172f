#pragma once
// The toolkit's mesh type: arrays per attribute, in metres, +Y up.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace dresskit::mesh {

/// A triangle mesh with optional per-vertex attributes. Every attribute is either empty (0 rows) or has
/// one row per vertex. Units: metres; axes: +Y up (loaders convert, see io.h).
struct TriangleMesh {
  Eigen::MatrixX3d V;  ///< #V×3 vertex positions [m]
  Eigen::MatrixX3i F;  ///< #F×3 vertex indices per triangle, counter-clockwise seen from the outside
  Eigen::MatrixX3d N;  ///< #V×3 unit vertex normals, or empty
  Eigen::MatrixX2d UV;  ///< #V×2 texture coordinates, or empty
  /// Texture coordinates per face corner, for a texture with seams (a garment sewn from panels:
  /// each panel's flat layout): corner k of face f has TC.row(FTC(f, k)). Both empty, or FTC #F×3.
  /// Where set, the writers use them instead of UV (OBJ `vt` with `f v/vt`; glTF and FBX split a
  /// vertex whose corners differ). Cleanup carries them face by face; select_vertices does not.
  Eigen::MatrixX2d TC;
  Eigen::MatrixX3i FTC;
  /// #F group per face (index into group_names, -1 = none), or empty: a sewn pattern's panels.
  /// Written as OBJ groups (`g name` before each run of faces in one group); not read. Cleanup
  /// carries them (a face it made has none); select_vertices does not.
  Eigen::VectorXi face_groups;
  std::vector<std::string> group_names;
  /// #V per-vertex part labels (index into label_names, -1 = unlabelled), or empty.
  Eigen::VectorXi labels;
  std::vector<std::string> label_names;
  /// #Q×4 original quads of the input (indices into V, same orientation as F), or empty. Each quad
  /// (a,b,c,d) is also present in F as the two triangles (a,b,c) and (a,c,d); the cloth takes the quad
  /// diagonals a–c and b–d as shear springs.
  Eigen::MatrixX4i quads;
  /// #V index of each vertex in the source file's own vertex order (OBJ `v` lines; for other formats
  /// the order in which the loader met the vertices); -1 for a vertex that the toolkit created.
  Eigen::VectorXi source_vertex;

  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_faces() const { return static_cast<int>(F.rows()); }
  bool has_labels() const { return labels.size() > 0; }
};

/// Axis-aligned bounding box of the vertices (empty box for an empty mesh).
Eigen::AlignedBox3d bounding_box(const TriangleMesh& mesh);

/// Area-weighted unit vertex normals (#V×3) of the triangles; isolated vertices get (0,0,0).
Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

/// Throws InputError("<what>: <problem>") when the mesh cannot be used: no faces, a non-finite
/// coordinate, a face index out of range, or an attribute whose row count differs from #V.
void validate_mesh(const TriangleMesh& mesh, const std::string& what);

/// Keeps the vertices for which keep[i] is true (and the faces and quads whose corners are all kept),
/// renumbering indices and carrying every per-vertex attribute along. Returns old → new index (-1 when
/// dropped) in old_to_new if it is not null.
TriangleMesh select_vertices(const TriangleMesh& mesh, const std::vector<bool>& keep,
                             std::vector<int>* old_to_new = nullptr);

/// A mesh without vertices or faces (0×3 arrays), to append to.
TriangleMesh empty_mesh();

/// Appends b to a: vertices, faces, and labels with b's part names prefixed by label_prefix (a
/// vertex of b without a label, or of a b without labels, gets −1). Other attributes of a are
/// dropped.
void append_mesh(TriangleMesh& a, const TriangleMesh& b, const std::string& label_prefix);

/// Per-vertex RGB colour (0–255) for a label: a fixed palette, grey for -1.
Eigen::Vector3i label_colour(int label);

}  // namespace dresskit::mesh
