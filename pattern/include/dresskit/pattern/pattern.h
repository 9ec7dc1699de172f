#pragma once
// Sewing patterns: flat panels with curved edges, their places in 3D, and the stitches between
// their edges, read from GarmentCode's pattern JSON (`*_specification.json`, docs/pattern.md).
//
//   const dresskit::pattern::Pattern p =
//   dresskit::pattern::read_pattern("shirt_specification.json");
//   // p.panels[i].vertices [m], p.stitches, p.warnings (stitched edges of unequal length)
#include <Eigen/Core>
#include <string>
#include <vector>

namespace dresskit::pattern {

/// The shape of a panel edge between its two end vertices.
enum class CurveKind { straight, quadratic, cubic, arc };

/// One edge of a panel's outline, in the panel's plane [m].
struct Edge {
  int start = 0, end = 0;  ///< indices into Panel::vertices
  CurveKind kind = CurveKind::straight;
  /// Bézier control points between the ends (quadratic: 1, cubic: 2), absolute panel coordinates
  /// [m].
  std::vector<Eigen::Vector2d> controls;
  /// Circular arc (as an SVG arc from start to end): radius [m], whether it is the larger of the
  /// two arcs through the ends, and whether it turns counter-clockwise (angle increasing) from
  /// start to end.
  double radius = 0.0;
  bool large_arc = false, counter_clockwise = false;
  std::string label;  ///< the file's label for the edge, "" if none
};

/// A flat piece of fabric: an outline of edges, each from the end of the one before (a closed
/// loop).
struct Panel {
  std::string name;
  Eigen::MatrixX2d vertices;  ///< #V×2 outline corners in the panel's plane [m]
  std::vector<Edge> edges;    ///< in outline order
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< [m]
  /// Euler angles about x, then y, then z (fixed axes) [degrees]: a point p of the panel's plane is
  /// at rotation() (p.x, p.y, 0) + translation in 3D.
  Eigen::Vector3d euler_degrees = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation() const;
  /// The panel-plane point p [m] placed in 3D [m].
  Eigen::Vector3d place(const Eigen::Vector2d& p) const;
};

/// One side of a stitch: an edge of a panel.
struct StitchSide {
  int panel = 0, edge = 0;
};

/// Two edges sewn together along their whole lengths. GarmentCode's convention: the start of one
/// edge meets the end of the other (outlines of the two panels run opposite ways along a seam);
/// `same_direction` (the file's "right_wrong" marker) makes starts meet starts.
struct Stitch {
  StitchSide a, b;
  bool same_direction = false;
};

struct ReadOptions {
  /// A stitch whose longer edge is more than this times its shorter one gets a warning naming both
  /// edges (the seam will gather or stretch the longer one) [unitless, ≥ 1].
  double max_length_ratio = 1.05;
  /// Edges shorter than this are refused as zero-length [m].
  double min_edge_length = 1e-5;
};

struct Pattern {
  std::string name;               ///< the file name without its directory and `.json`
  std::string file;               ///< as given
  double units_in_meter = 100.0;  ///< the file's unit: this many per metre (cm: 100)
  std::vector<Panel> panels;      ///< in the file's `panel_order` when it has one
  std::vector<Stitch> stitches;
  /// One line each: stitched edges whose lengths differ by more than ReadOptions::max_length_ratio;
  /// a stitch that repeats another; an edge sewn by two stitches.
  std::vector<std::string> warnings;

  int panel_index(const std::string& name) const;  ///< −1 when there is none of that name
  /// "panel 'left_ftorso' edge 3": how messages and pictures name an edge.
  std::string edge_name(int panel, int edge) const;
};

/// Reads and checks a GarmentCode pattern file. Throws InputError with one line naming the file and
/// the panel, edge or stitch for: an unreadable or malformed file, no `properties.units_in_meter`,
/// an edge whose end vertex does not exist, an outline that is not a closed loop, an edge of zero
/// length, a self-intersecting outline, a stitch naming a panel or an edge that does not exist.
Pattern read_pattern(const std::string& path, const ReadOptions& options = {});
/// The same from the file's text; `file` names it in messages and gives the pattern its name.
Pattern parse_pattern(const std::string& text, const std::string& file,
                      const ReadOptions& options = {});

/// The name of a pattern file: its file name without the directory and `.json`
/// ("gc_shirt_mean_specification.json" → "gc_shirt_mean_specification"); outputs are named by it.
std::string pattern_name(const std::string& path);

/// Whether a path names a pattern file (ends in .json) rather than a mesh.
bool is_pattern_file(const std::string& path);

}  // namespace dresskit::pattern
