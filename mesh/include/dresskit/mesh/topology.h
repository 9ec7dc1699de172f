#pragma once
// Topology and geometry facts about a triangle soup. Written on the index arrays, not on CGAL's
// halfedge structures, because it must describe any input, including the non-manifold ones that a
// halfedge structure cannot even hold.
#include <array>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::mesh {

struct TopologyReport {
  int num_vertices = 0;
  int num_faces = 0;
  int num_edges = 0;                 ///< distinct undirected edges
  int num_components = 0;            ///< face sets connected through shared vertices
  int num_boundary_edges = 0;        ///< edges used by exactly one face
  int num_boundary_loops = 0;        ///< connected sets of boundary edges
  double boundary_length = 0.0;      ///< summed length of the boundary edges [m]
  int num_non_manifold_edges = 0;    ///< edges used by three or more faces
  int num_non_manifold_vertices = 0; ///< vertices whose faces form more than one fan
  int num_isolated_vertices = 0;     ///< vertices used by no face
  int num_inconsistent_edges = 0;    ///< two-face edges whose faces traverse it the same way
  int num_degenerate_faces = 0;      ///< faces with a repeated index or zero area
  bool manifold = false;             ///< no non-manifold edge or vertex
  bool closed = false;               ///< manifold with no boundary edge
  bool consistently_oriented = false;
  double area = 0.0;                 ///< [m²]
  double signed_volume = 0.0;        ///< [m³], meaningful when closed
  bool outward = false;              ///< closed, consistently oriented and signed_volume > 0
  int euler_characteristic = 0;      ///< V − E + F over the used vertices
};

TopologyReport analyse_topology(const TriangleMesh& mesh);

/// Connected component (through shared vertices) of each face, numbered 0..n-1 in order of first face.
std::vector<int> face_components(const Eigen::MatrixX3i& F, int num_vertices, int* num_components);

/// Each vertex's neighbours along the faces' edges, sorted, each once.
std::vector<std::vector<int>> vertex_neighbours(const Eigen::MatrixX3i& F, int num_vertices);

/// One mesh per connected component, largest (most faces) first, with every attribute carried along.
std::vector<TriangleMesh> split_components(const TriangleMesh& mesh);

/// Triangles covering one polygon face, as indices into `corners` (its corners in order), keeping
/// the polygon's winding. Ear clipping in the plane of the polygon's Newell normal, the best-shaped
/// ear first: a corner on the straight line between its neighbours (where a side of a neighbouring
/// polygon meets this one, a T-junction) is never an ear's tip and no ear may have a corner on its
/// sides, so no triangle has zero area and no diagonal repeats a side of the polygon (a fan from
/// the first corner would do both, and make that side's edge non-manifold). A polygon of no area is
/// fanned, and so is one of more than 256 corners.
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Eigen::Vector3d>& corners);

/// Reverses the faces of every closed component whose signed volume is negative, so closed components
/// face outwards. Returns the number of faces flipped.
int orient_closed_components_outward(TriangleMesh& mesh);

}  // namespace dresskit::mesh
