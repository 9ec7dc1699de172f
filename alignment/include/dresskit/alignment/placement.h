#pragma once
// Part-wise placement of a garment on a body of another size and pose: part matching, a global
// similarity from the junctions between parts, per-part ICP, blending of the part transforms across
// part boundaries, and a push out of the body by a clearance (docs/alignment.md).
#include <string>
#include <vector>

#include "dresskit/alignment/icp.h"
#include "dresskit/alignment/part_matching.h"
#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::alignment {

struct PlacementOptions {
  MatchingOptions matching;
  /// Per-part refinement: point-to-plane with hard correspondences only. The soft stage models the
  /// source as a noisy sample of the target's surface; a garment part stands off its body part by
  /// the ease instead, and with the soft stage the casualsuit → child placement was further from
  /// the reference (docs/alignment.md).
  IcpOptions part_icp = [] {
    IcpOptions o;
    o.soft_neighbours = 0;
    return o;
  }();
  /// Per-part similarity instead of rigid ICP. Off: the global similarity already carries the size
  /// ratio, and on the casualsuit → child case rigid parts are closer to the reference
  /// (docs/alignment.md).
  bool part_scale = false;
  /// Per-part ICP onto the body part's surface raised by the part's ease (the median height of its
  /// points over the body part under the global placement) instead of onto the skin. Measured
  /// (docs/alignment.md): the male casualsuit on its own body 2.28 → 0.49 % from its refit and
  /// 224 → 0 crossings; the casualsuit on the child 1.05 → 1.11 %, stretch 33 → 48 %; off by
  /// default until more outfits say which is better.
  bool keep_ease = false;
  int min_part_vertices = 50;  ///< smaller parts keep the global transform (reported)
  /// A part's ICP is rejected (global transform kept, reported) when it turns the part by more than
  /// this relative to the global placement [degrees] ...
  double max_part_rotation_deg = 30.0;
  /// ... or changes its scale by more than this factor.
  double max_part_scale_change = 1.3;
  double blend_radius = 0.06;  ///< [m] part transforms blend within this distance of a boundary
  double clearance = 0.003;    ///< [m] garment vertices end at least this far outside the body
  int push_iterations = 3;     ///< rounds of (limit stretch, push out)
  /// Edges longer than (1 + this) × their rest length are shortened (position-based strain
  /// limiting, both ends moved) before each push, so that blending and pushing do not tear the
  /// garment.
  double max_edge_stretch = 0.3;
  int stretch_sweeps = 10;  ///< Gauss–Seidel sweeps over the edges per round
  /// An outfit of several pieces (connected components: a t-shirt and jeans) is worn in layers, a
  /// piece whose top is higher outside those whose top is lower; in each push round every vertex
  /// of an outer piece ends at least this far outside the nearest vertex of an inner piece, along
  /// the body's normal there, so that the pieces start the simulation apart [m]; < 0 = off.
  double layer_gap = 0.003;
  /// Per garment vertex, its layer (0 = innermost) when an outfit's pieces are worn in a given
  /// order (several garment files placed together); empty = pieces ordered by the height of their
  /// tops. Pieces of one layer are ordered by their tops too, and pushed out of one another when
  /// pieces_of_a_layer_apart (false: a garment's own pieces — buttons, a collar, pockets — stay
  /// as they are to each other).
  Eigen::VectorXi vertex_layers;
  bool pieces_of_a_layer_apart = true;
  /// Pushes out of the body shared: every sheet over one place of the body pushed as far as the
  /// deepest one there (gathered per body vertex and spread over this many rings of the body), then
  /// smoothed over as many rings of the garment, so that a garment leaves the body as a bulge, its
  /// layered details (buttons, collars) with it, rather than as a tent of stretched edges; 0 = each
  /// vertex pushed on its own.
  int push_rings = 0;
};

struct PartPlacement {
  std::string garment_part, body_part;
  int vertices = 0;
  IcpResult icp;          ///< the part's refinement (transform: garment part → body)
  bool used_icp = false;  ///< false: the global transform was kept
  std::string note;       ///< why not, when not
};

struct PlacementResult {
  Eigen::MatrixX3d V;  ///< posed garment vertices [m], in the garment mesh's order
  MatchingResult matching;
  Eigen::Matrix4d global = Eigen::Matrix4d::Identity();  ///< garment → body similarity
  double global_scale = 1.0;
  /// The global fit kept, of "junctions (N landmarks)", "junctions (2 landmarks, upright)" and
  /// "multi-start ICP": the one whose parts lie nearest their matched body parts.
  std::string global_method;
  std::vector<std::string> junctions;  ///< the part pairs used as landmarks
  std::vector<PartPlacement> parts;
  int pushed_out = 0;             ///< garment vertices moved out of the body
  /// Pieces (connected components) from the innermost layer out, by their first vertex's index,
  /// and the vertices of outer pieces moved out of inner ones (layer_gap).
  std::vector<int> layer_pieces;
  int layer_pushed = 0;
  int stretch_limited_edges = 0;  ///< edges over the strain limit in the last round's first sweep
  double seconds = 0.0;
};

/// Places a labelled garment on a labelled body (both in metres, +Y up). Throws InputError when the
/// inputs cannot be used (no labels, no matched parts, unusable point sets).
PlacementResult place_garment(const mesh::TriangleMesh& garment, const mesh::TriangleMesh& body,
                              const PlacementOptions& options = {});

/// How a placement ends (place_garment's last step, and the dressing pipeline's after carrying a
/// garment by its wearer): rounds of strain limiting — edges longer than (1 + max_edge_stretch) ×
/// limit_scale × their length in `garment` shortened, both ends moved — and of pushes out of the
/// body to `clearance` outside, along the normal of the nearest body vertex; pieces worn over others
/// (PlacementOptions::layer_gap, vertex_layers) moved out over them, where a vertex of the inner
/// piece lies within two of its mean edges (× reach_scale) across the body. Works on out.V; sets
/// pushed_out, layer_pieces, layer_pushed and stretch_limited_edges.
void push_out_of_body(const mesh::TriangleMesh& garment, const mesh::TriangleMesh& body,
                      const Eigen::MatrixX3d& body_normals, const PlacementOptions& options, double limit_scale,
                      double reach_scale, PlacementResult& out);

/// Sweeps of position-based strain limiting on a garment at positions V (PlacementOptions::
/// stretch_sweeps): each edge longer than (1 + max_edge_stretch) × scale × its length in `garment`
/// shortened, both ends moved. Returns the edges over the limit in the first sweep.
int limit_stretch(const mesh::TriangleMesh& garment, double scale, const PlacementOptions& options, Eigen::MatrixX3d& V);

/// Comparison of a posed garment with a reference placement (same vertex order): `align --reference`.
struct PlacementQuality {
  double body_height = 0.0;       ///< [m] extent of the body along +Y
  double mean_distance = 0.0;     ///< mean vertex distance to the reference / body height
  double p95_distance = 0.0;      ///< 95th percentile / body height
  double inside_fraction = 0.0;   ///< garment vertices inside the body (winding number > 0.5)
  double max_edge_stretch = 0.0;  ///< max over edges of posed length / rest length − 1
};
PlacementQuality placement_quality(const Eigen::MatrixX3d& posed, const mesh::TriangleMesh& garment_rest,
                                   const Eigen::MatrixX3d& reference, const mesh::TriangleMesh& body);

/// Fraction of the points inside a closed mesh (generalised winding number > 0.5).
double inside_fraction(const Eigen::MatrixX3d& points, const mesh::TriangleMesh& closed_mesh);

}  // namespace dresskit::alignment
