#pragma once
// Mesh files in and out. Loading goes through assimp (OBJ, PLY, OFF, STL, glTF/GLB, FBX); saving writes
// OBJ, PLY, OFF and STL with our own writers (exact vertex order, quads, shortest round-trip numbers)
// and glTF/GLB/FBX through assimp's exporters. Formats and conventions: docs/formats.md.
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::mesh {

/// Length unit of a source file, as metres per file unit.
struct Units {
  double metres_per_unit = 1.0;
  std::string name = "m";
  /// "m", "dm", "cm", "mm", or a positive number (metres per file unit, e.g. "0.00333" for the
  /// GarmentCode t-shirt in metres × 300). Throws InputError naming the value otherwise.
  static Units parse(const std::string& text);
};

/// Which axis of the source file points up; the loader rotates it to +Y (a proper rotation).
enum class UpAxis { pos_x, neg_x, pos_y, neg_y, pos_z, neg_z };
/// "+x", "-x", "+y", "y", "-y", "+z", "z", "-z". Throws InputError naming the value otherwise.
UpAxis parse_up_axis(const std::string& text);

/// The named unit (m, dm, cm, mm) under which a body whose extent in its file's own units is
/// `file_extent` measures between 0.5 m and 2.5 m (a person), or "" when none does: what to
/// suggest when a forgotten --units makes a body 1,720 m or 1.7 mm tall.
std::string units_for_body(double file_extent);
std::string to_string(UpAxis axis);

struct LoadOptions {
  Units units;                  ///< source units; default metres
  UpAxis up = UpAxis::pos_y;    ///< source up axis; default +Y
};

/// The proper rotation that takes the source up axis to +Y (applied by load_mesh).
Eigen::Matrix3d up_rotation(UpAxis up);

/// Positions in the toolkit's frame (metres, +Y up) back in a file's frame (its units and up axis):
/// the inverse of what load_mesh applied with these options.
Eigen::MatrixX3d to_file_frame(const Eigen::MatrixX3d& V, const LoadOptions& options);

/// The file extensions (lower case, without dot) that load_mesh reads.
const std::vector<std::string>& loadable_extensions();

/// Loads a mesh, converts it to metres and +Y up, triangulates polygons (quads are also kept in
/// TriangleMesh::quads) and checks it with validate_mesh. For OBJ files the vertices are exactly the
/// file's `v` lines in file order, in double precision (source_vertex = identity); for other formats
/// they are assimp's vertices after joining identical ones. Throws InputError naming the file for a
/// missing, empty, unsupported, unreadable or unusable file.
TriangleMesh load_mesh(const std::string& path, const LoadOptions& options = {});

/// Saves by extension: .obj (quads kept, with vt/vn when present), .ply (binary little endian, double
/// positions, vertex colours and an int `label` property from labels when present), .off (quads
/// kept), .stl (binary, single precision), and through assimp .glb / .gltf (glTF 2, colours from
/// labels) and .fbx. Files are written in a temporary folder beside the destination and moved into
/// place, so a failure leaves nothing.
/// Throws OutputError naming the path.
void save_mesh(const TriangleMesh& mesh, const std::string& path);

/// A mesh with a name: one node of a scene file.
struct NamedMesh {
  std::string name;
  TriangleMesh mesh;
};

/// Saves several meshes as one scene, each a named node (.glb, .gltf or .fbx, through assimp), with
/// save_mesh's temporary-folder-and-move. Throws OutputError naming the path.
void save_scene(const std::vector<NamedMesh>& meshes, const std::string& path);

/// The file extensions (lower case, without dot) that save_mesh writes.
const std::vector<std::string>& saveable_extensions();
/// Whether save_mesh can write this path's extension (case-insensitive).
bool is_saveable(const std::string& path);

/// Writes text to path through a temporary file and a rename (no partial file on failure).
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace dresskit::mesh
