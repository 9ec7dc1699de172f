#pragma once
// Mesh repair with CGAL Polygon Mesh Processing (CGAL stays inside cleanup.cpp).
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::mesh {

/// The most triangles a remeshing may make (about 1 GB of halfedge mesh).
constexpr double kMaxRemeshTriangles = 5e6;

struct CleanupOptions {
  bool repair_non_manifold = true;   ///< split non-manifold vertices (needed by every later step)
  bool orient = true;                ///< consistent orientation; closed components face outwards
  bool stitch_borders = true;        ///< stitch coincident border edges
  bool fill_holes = false;           ///< fill boundary loops of at most max_hole_edges edges
  int max_hole_edges = 64;           ///< largest hole filled [edges]; garment openings are larger
  bool keep_largest_component = false;  ///< drop every component but the largest (by faces)
  /// Isotropic remeshing target [m]; 0 = no remeshing. A length that would make more than
  /// kMaxRemeshTriangles triangles of the mesh's area is refused (InputError naming the shortest).
  double remesh_edge_length = 0.0;
  int remesh_iterations = 3;         ///< iterations of split/collapse/flip/relax
};

/// What cleanup changed, with counts, and how long each phase took.
struct CleanupResult {
  TriangleMesh mesh;
  int duplicate_vertices_merged = 0;
  int degenerate_faces_removed = 0;   ///< repeated index or zero area
  int duplicate_faces_removed = 0;
  int isolated_vertices_removed = 0;
  int non_manifold_vertices_split = 0;  ///< vertices added by splitting non-manifold ones
  int faces_reoriented = 0;
  int border_edges_stitched = 0;
  int holes_filled = 0;
  int hole_faces_added = 0;
  int borders_left_open = 0;  ///< loops not filled: the border of an open surface, not a hole in it
  int components_removed = 0;
  bool remeshed = false;
  double seconds_soup = 0.0;     ///< merging, removals, orientation on the polygon soup
  double seconds_mesh = 0.0;     ///< halfedge repair: stitching, degeneracies, holes, components
  double seconds_remesh = 0.0;
  double seconds_attributes = 0.0;  ///< carrying labels, UVs, source indices and quads across
  /// Human-readable lines, one per change ("merged 10 duplicate vertices"), empty when nothing changed.
  std::vector<std::string> changes() const;
};

/// Repairs a mesh: merge duplicate vertices, remove degenerate, duplicate and zero-area faces, remove
/// isolated vertices, split non-manifold vertices, orient consistently (closed parts outwards), stitch
/// borders, and optionally fill small holes, keep the largest component and remesh isotropically.
/// Per-vertex attributes follow their vertex: labels and UVs of a vertex that cleanup created come from
/// the nearest input vertex; source_vertex of a created vertex is -1. Quads survive when both of their
/// triangles do.
CleanupResult cleanup_mesh(const TriangleMesh& mesh, const CleanupOptions& options = {});

}  // namespace dresskit::mesh
