#pragma once
// Cutting: every panel meshed into triangles of about one edge length, its outline resampled so
// that the two edges of every stitch get the same number of points at equal steps of their arc
// lengths (matching points, paired along the stitch), and placed in 3D by the panel's rotation and
// translation. Panels stay separate pieces; sewing joins them (sew.h).
//
//   const CutPattern cut = cut_pattern(read_pattern("shirt.json"), {0.02});
//   // cut.placed: #V×3 [m], cut.faces, cut.stitch_pairs: vertices to be sewn together
#include <Eigen/Core>
#include <array>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/pattern/pattern.h"

namespace dresskit::pattern {

struct CutOptions {
  /// Target triangle edge length [m]: outline edges are cut into pieces no longer than this, and
  /// the panel's inside is refined (CGAL's Delaunay meshing) until no triangle is larger.
  double edge_length = 0.02;
  /// CGAL's shape bound B = 1 / (4 sin² θ) for the smallest angle θ wanted (0.125: about 20.7°);
  /// triangles at the outline may keep smaller angles (the outline is never split further).
  double shape_bound = 0.125;
};

/// Matching point counts: every edge's piece count is ceil(length / edge_length), and the edges
/// joined by stitches (directly or through other stitches) all take the largest count among them.
/// Indexed [panel][edge].
std::vector<std::vector<int>> edge_piece_counts(const Pattern& pattern, double edge_length);

struct CutPattern {
  Eigen::MatrixX2d flat;    ///< #V×2 positions in each vertex's panel plane [m]
  Eigen::MatrixX3d placed;  ///< #V×3 positions in 3D, by each panel's rotation and translation [m]
  /// #F×3 triangles, turning as their panel's outline turns (GarmentCode's outlines turn so that
  /// faces point away from the body once placed).
  Eigen::MatrixX3i faces;
  Eigen::VectorXi panel_of_vertex;  ///< #V
  Eigen::VectorXi panel_of_face;    ///< #F
  /// For each panel and edge, its vertices from the edge's start to its end (corners included).
  std::vector<std::vector<std::vector<int>>> edge_vertices;
  /// Vertex pairs to be sewn together, one per matching point of every stitch (a dart's tip, where
  /// a point would be sewn to itself, is left out), and the stitch each belongs to.
  std::vector<std::array<int, 2>> stitch_pairs;
  std::vector<int> stitch_of_pair;
  Eigen::VectorXd outline_area;   ///< #panels: area enclosed by the panel's curves [m²]
  Eigen::VectorXd triangle_area;  ///< #panels: area of its triangles [m²]
  double seconds = 0.0;           ///< wall-clock time of the cutting
};

/// Cuts, resamples and places every panel. Throws InputError naming the panel when it cannot be
/// meshed (an outline whose resampled polygon crosses itself at this edge length).
CutPattern cut_pattern(const Pattern& pattern, const CutOptions& options = {});

/// The cut panels as one mesh in 3D [m] (separate pieces; labels and face groups = panels, named).
mesh::TriangleMesh placed_mesh(const Pattern& pattern, const CutPattern& cut);
/// Texture coordinates of the cut vertices (#V×2) [m]: each panel flat and seen from the side its
/// faces point to (mirrored along u where its outline turns clockwise in its plane, so that a
/// texture reads the right way round on the garment's outside), laid side by side along u with
/// `gap` between panels, v as the panel's y.
Eigen::MatrixX2d texture_coordinates(const Pattern& pattern, const CutPattern& cut, double gap = 0.05);
/// The cut panels flat (z = 0) as texture_coordinates lays them out: every face towards +z [m].
mesh::TriangleMesh flat_mesh(const Pattern& pattern, const CutPattern& cut, double gap = 0.05);

}  // namespace dresskit::pattern
