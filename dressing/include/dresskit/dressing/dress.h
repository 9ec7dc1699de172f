#pragma once
// The dressing pipeline, the product's main job: a body and garments from files to the garments
// settled on the body (docs/dressing.md). Stages, each reported as run or left out, with why and
// how long: load → clean → units → segmentation → wearer → layers → placement → thickness → grading → settle →
// padding.
//
//   const dresskit::dressing::MeshFile body = dresskit::dressing::MeshFile::file("body.obj");
//   const dresskit::dressing::GarmentFile shirt{dresskit::dressing::MeshFile::file("shirt.obj"), "gray-interlock"};
//   const dresskit::dressing::DressResult r = dresskit::dressing::dress(body, {shirt});
//   // r.garments[0].dressed: the settled shirt [m], in r.garments[0].mesh's vertex order
#include <functional>
#include <optional>
#include <array>
#include <string>
#include <vector>

#include "dresskit/alignment/placement.h"
#include "dresskit/alignment/wearer.h"
#include "dresskit/cloth/run.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/segmentation/segment.h"
#include "dresskit/thickness/thickness.h"

namespace dresskit::dressing {

/// How long and how finely to settle: `fast` (the simulator's defaults, at most 0.5 s simulated),
/// `balanced` (the defaults, at most 1 s) or `accurate` (steps up to 1/240 s, 20 projective
/// iterations, at most 2 s); every one stops early once the garments are at rest.
enum class DressQuality { fast, balanced, accurate };
/// "fast", "balanced", "accurate"; throws InputError naming the value otherwise.
DressQuality parse_quality(const std::string& text);
std::string to_string(DressQuality quality);

/// A mesh file and what is known about it.
struct MeshFile {
  std::string path;
  mesh::LoadOptions load;        ///< the file's units and up axis
  std::string labels;      ///< part labels (JSON, the layouts of ../shared/data/labels); "" = segment
  std::string labels_key;  ///< the entry in the labels file; "" = the file's stem
  /// The mesh itself, made in memory rather than read from `path` (which then only names it) [m,
  /// +Y up]; its labels, when it has named ones, are its parts (no segmentation).
  std::optional<mesh::TriangleMesh> mesh;

  /// A file with its units and up axis.
  static MeshFile file(std::string path, mesh::LoadOptions load = {}, std::string labels = "");
  /// A mesh made in memory, called `name` in messages and outputs.
  static MeshFile given(std::string name, mesh::TriangleMesh mesh);
};

struct GarmentFile {
  MeshFile file;
  std::string fabric;  ///< a built-in fabric (docs/cloth.md); "" = gray-interlock
  /// A padded garment (quilted, down, a fleece's pile): dressed as a double layer, its two shells
  /// kept apart by the thickness heat conduction gives for its fabric (DressOptions::padding), within
  /// that method's limits. false: one sheet.
  bool padded = false;
  /// A sewing pattern's own body, the one its panels are placed around (GarmentCode's body mesh for
  /// its patterns), with its units and optional part labels; no path and no mesh: none. Given, the
  /// panels are carried to the body to dress part by part — each panel follows the part of its body
  /// it lies over (a sleeve its arm, turned about the shoulder) — rather than by the bodies' frames
  /// (docs/pattern.md).
  MeshFile pattern_body = {};
};

struct DressOptions {
  DressQuality quality = DressQuality::fast;
  /// Garments given as sewing patterns (.json, docs/pattern.md) are cut into triangles of this edge
  /// length [m], and their stitches are closed to `seam_tolerance` [m] before settling.
  double pattern_edge_length = 0.02, seam_tolerance = 0.001;
  /// A pattern whose sewing leaves a stitch pair further apart than this [m] is refused (InputError
  /// naming the stitch): its garment is not one (a pattern placed for another body, say). Seams
  /// open less are a warning.
  double max_open_seam = 0.05;
  bool settle = true;  ///< false: stop after placement (dressed = placed)
  /// Simulated time settling takes at most [s]; 0 = the quality's (0.5, 1 or 2 s).
  double settle_seconds = 0.0;
  /// Steps a settle (and the padding's growth) takes at most, as a multiple of its nominal steps
  /// (simulated time / the simulator's dt): where the adaptive step stays short (cloth pressed
  /// between the body and other cloth) the run stops there, keeps what it reached and says so in a
  /// warning, rather than taking hours of steps (0: no bound) [unitless].
  double settle_step_budget = 64.0;
  /// false: the garments are worn inside to outside in the order given; true: the order is
  /// inferred from their kinds (bottoms under tops; of one kind, the one lying farther from the body
  /// where both already lie on it, else the larger surface outside).
  bool infer_layers = false;
  /// The largest meshes dressed, in triangles (after quads are split): a larger body or garment is
  /// refused when loaded (0: no bound). Segmentation and the settle take minutes beyond these.
  int max_body_triangles = 400000, max_garment_triangles = 200000;
  /// How a garment mesh is placed: the body rigged and fitted into it where its wearer stood, the
  /// garment carried from there onto the body (alignment/wearer.h), then pushed out of the body by
  /// placement.clearance with its edges' stretch limited (alignment::push_out_of_body).
  alignment::RigOptions rig;
  alignment::WearerFitOptions wearer;
  alignment::CarryOptions carry;
  /// A garment mesh counts as already on the body, and is left where it is, when carrying it from
  /// its wearer would move 95 % of the vertices of each of its parts (body, each sleeve, each leg)
  /// by at most this fraction of the body's height: its sleeves lie around the arms as posed.
  double fit_move = 0.01;
  /// ... or when it lies around the body as it is nearly as evenly as around its wearer: the fit's
  /// cost with the body unmoved at most this many times the wearer's (a skirt says little of the
  /// legs inside it, which the fit may turn a little) [unitless].
  double fit_cost = 1.5;
  alignment::PlacementOptions placement = [] {
    alignment::PlacementOptions o;
    o.push_rings = 4;
    return o;
  }();
  segmentation::SegmentationOptions segmentation;
  /// A sewn pattern's garment counts as on the body, and a garment as lying on it when layers are
  /// inferred, when at most this fraction of its vertices lies deeper than 2 mm inside the body
  /// and its vertices lie within on average `fit_distance` × the body's height of the body's
  /// surface [unitless]. (A garment made for a body often dips a few millimetres into it here and
  /// there; settling pushes them out.)
  double fit_inside = 0.1, fit_distance = 0.03;
  /// Trousers and skirts (pieces with leg or skirt parts and no sleeves) are held while settling by
  /// their vertices within this distance of the piece's top, as by a belt [m]; 0: not held.
  double waistband = 0.015;
  /// The conditions under which a padded garment's thickness and its limits are computed
  /// (docs/thickness.md): 37 °C skin, −10 °C air, one hour, fibre volume fraction 0.25.
  thickness::ThicknessOptions padding;
  /// Called when a stage ends, and while settling with the simulated seconds done of at most total.
  std::function<void(const struct DressStage&)> on_stage;
  std::function<void(double done, double total)> on_settle;
  /// Called when a pattern garment starts sewing (done = 0), then after every sewing step, with its
  /// name, its stitch pairs and the simulated seconds done of at most total (part of `load`).
  std::function<void(const std::string& garment, int pairs, double done, double total)> on_sew;
};

struct DressStage {
  std::string name;      ///< load, clean, units, segmentation, wearer, layers, placement, thickness, grading, settle, padding
  bool ran = false;
  double seconds = 0.0;  ///< wall-clock
  std::string reason;    ///< what it did, or why it was left out
};

/// One named part of a mesh and how sure its name is (1 for parts read from a label file).
struct DressPart {
  std::string name;
  double confidence = 1.0;
  int vertices = 0;
};

/// A garment sewn from a sewing pattern: what cutting and sewing did, and its panels' areas.
struct SewnPattern {
  std::vector<std::string> panels;             ///< panel names, in the pattern's order
  std::vector<double> panel_area;              ///< each panel's area flat [m²]
  std::vector<double> panel_area_dressed;      ///< the same dressed (empty without settling) [m²]
  /// The panels' triangles as cut, in the garment's vertex indices (a seam's two sides share
  /// vertices), and each one's panel: areas per panel at any positions.
  Eigen::MatrixX3i panel_faces;
  Eigen::VectorXi panel_of_face;
  /// Each edge of the panels' triangles (garment vertex indices, smaller first) and its length in
  /// the flat pattern [m] (the mean of both sides' along a seam): the settle's rest lengths.
  std::vector<std::array<int, 2>> flat_edges;
  std::vector<double> flat_edge_length;
  int stitches = 0;        ///< the pattern's stitches (seams, darts, pleats)
  int stitch_pairs = 0;    ///< matching point pairs to sew
  int sewn_pairs = 0;      ///< of those, sewn and welded
  int welded_open_pairs = 0;  ///< pairs left open but welded (within the cut's edge length)
  std::string sew_method;  ///< "drawn" or "seam forces" (pattern::SewResult::method)
  std::string sew_stopped;  ///< why sewing stopped: "closed", or the limit it reached
  int sew_steps = 0;        ///< simulator steps of sewing, both tries
  long long sew_contacts = 0;  ///< cloth–cloth contacts handled sewing (pattern::SewResult::contacts)
  /// Largest stitch pair distance when sewing stopped, before welding [m]: a pair sewn (held by the
  /// simulator) may be left slightly apart by the collision passes after it.
  double max_gap = 0.0;
  bool closed = false;     ///< every pair sewn: came within DressOptions::seam_tolerance, then held
  /// Sewn pairs left unwelded (pattern::SewResult::unwelded), garment vertex pairs: seams hold them
  /// together while settling.
  std::vector<std::array<int, 2>> unwelded;
  /// How far the panels were moved from the pattern's places to this body before sewing [m] (zero
  /// on the body the pattern is placed for; pattern::SewOptions::pattern_body), and how many were
  /// then moved out of it along their normals.
  Eigen::Vector3d moved_by = Eigen::Vector3d::Zero();
  int panels_moved_out = 0;
  /// How the panels came to this body: "as placed" (it is the pattern's body), "frames" (moved
  /// together by the bodies' frames) or "parts" (each by the part of the pattern's body it lies
  /// over, GarmentFile::pattern_body); with parts, each panel's part (torso, head, arm_left, ...).
  std::string carried_by;
  std::vector<std::string> panel_parts;
  int triangles = 0;
  double cut_seconds = 0.0, sew_seconds = 0.0;  ///< wall-clock
  double sew_simulated = 0.0;                   ///< simulated time sewing took [s]
  std::vector<std::string> warnings;            ///< stitched edges of unequal lengths
};

/// A padded garment's double layer: the thickness asked and what the shells did.
struct PaddingFigures {
  /// Heat conduction's thickness for the fabric and its lower and upper limits [m].
  double thickness = 0.0, min = 0.0, max = 0.0;
  /// The shells' distance vertex by vertex, dressed: smallest, 5th percentile, median, largest [m].
  double gap_min = 0.0, gap_p5 = 0.0, gap_median = 0.0, gap_max = 0.0;
  /// Vertices whose shells end closer than `min`: the padding held down by what lies over it.
  int below_min = 0;
  /// Vertices whose outer shell started at the full thickness (the others started nearer, where
  /// anything lay closer over them, and were grown out).
  int start_at_full = 0;
  /// Edge–triangle crossings of the closed double layer (both shells and the rims joining them)
  /// where the outer shell started and dressed; a sheet crossing itself counts in both shells.
  int crossings_start = 0, crossings = 0;
};

/// Samples of the settle's energy and strain over its duration (DressResult::settle_time).
inline constexpr int kSettleSamples = 200;

/// A structural spring strained beyond this counts as over the strain limit in the report: the
/// simulator's 10 % and the length limits' tolerance.
inline constexpr double kOverLimit = 0.11;

/// A pattern's panel whose area dressed differs from its flat area by more than this share is
/// reported (DressedGarment::warnings): cloth drapes by bending, and stretches by a few percent.
inline constexpr double kPanelAreaChange = 0.03;

struct DressedGarment {
  std::string name;    ///< the file's stem, or the name of a mesh given in memory; unique
  std::string fabric;
  MeshFile file;       ///< as given (a mesh given in memory kept: outputs follow its vertex order)
  bool in_memory = false;  ///< given in memory rather than read from file.path
  mesh::TriangleMesh mesh;   ///< as loaded (and cleaned) [m]: its rest shape; labels = its parts
  std::vector<DressPart> parts;
  bool labels_from_file = false;      ///< from a label file or given with the mesh
  bool placed_by_placement = false;   ///< false: it already sat on the body
  alignment::PlacementResult placement;          ///< when placed_by_placement
  /// A garment mesh's wearer: the body fitted into the garment where its own wearer stood (none for
  /// a sewn pattern), and how far carrying the garment from there onto the body moves it: the 95th
  /// percentile of each part's vertex moves, the largest over its parts [m].
  std::optional<alignment::WearerFit> wearer;
  double carry_move = 0.0;
  Eigen::MatrixX3d placed, dressed;   ///< [m], in mesh's vertex order
  /// The rest shape settled from, when placement carried the garment [m]: as made at its wearer's
  /// size, loosened where the body is larger than its wearer (empty: as made).
  Eigen::MatrixX3d rest;
  int layer = 0;                      ///< 0 = worn next to the body
  double thickness = 0.0;             ///< the cloth's own thickness from its fabric [m]
  /// Edge–triangle crossings of its own: as authored, after placement's fit (before untangling),
  /// placed (handed to settling) and dressed.
  int crossings_authored = 0, crossings_fitted = 0, crossings_placed = 0, crossings_dressed = 0;
  int inside_placed = 0, inside_dressed = 0;  ///< vertices deeper than 2 mm inside the body
  double max_strain_dressed = 0.0;    ///< largest structural strain against the rest shape
  double strain_p99_dressed = 0.0;    ///< its 99th percentile over the structural springs
  int springs_over_limit = 0;         ///< structural springs strained beyond kOverLimit
  int waistband_vertices = 0;         ///< vertices held as its waistband while settling
  /// Particles of its own crossings as authored held where placed while settling (0: none; a settle
  /// that left it crossing itself more often than as authored was run again so, and kept).
  int tangle_held_vertices = 0;
  /// A padded garment: `dressed` is its inner shell, dressed_outer its outer one (mesh's vertex
  /// order, [m]), and `padding` says how thick.
  bool padded = false;
  Eigen::MatrixX3d dressed_outer;
  PaddingFigures padding;
  bool from_pattern = false;          ///< sewn from a pattern file (then `pattern` says how)
  SewnPattern pattern;
  /// What the dressed garment got wrong, one sentence each: crossing itself more often than as
  /// authored (a pattern: as sewn), vertices deeper than 2 mm inside the body, a panel's area
  /// changed by more than kPanelAreaChange, a padding that stalled. Empty: none of these.
  std::vector<std::string> warnings;
};

struct DressResult {
  MeshFile body_file;  ///< as given (without its in-memory mesh)
  DressQuality quality = DressQuality::fast;
  mesh::TriangleMesh body;  ///< as loaded (and cleaned) [m]; labels = its parts
  std::vector<DressPart> body_parts;
  bool body_labels_from_file = false;
  std::vector<DressedGarment> garments;  ///< inside to outside (as given unless infer_layers)
  std::vector<DressStage> stages;
  bool settled = false;   ///< the settle stage ran
  cloth::RunResult settle;       ///< when it ran
  /// The padding's growth and settle, when a garment is padded; one that stalled (`stalled`) keeps
  /// its last state, which crosses nothing but has the padding not grown everywhere.
  bool padding_ran = false;
  cloth::RunResult padding_settle;
  /// The settle over time (the attempt kept), sampled after the first step, then after the first
  /// step at least 1/kSettleSamples of the duration later, and after the last step: simulated time
  /// [s], elastic energy [J] and largest structural strain [unitless].
  std::vector<double> settle_time, settle_energy, settle_strain;
  /// Edge–triangle crossings between different garments at the end (0 = the layers kept apart),
  /// and the gap between consecutive layers where they overlap: of the outer garment's vertices
  /// within 2 cm of the inner one (a padded one: its outer shell), their count and the 5th percentile and median of their distance
  /// to it, against the thickness asked for [m].
  int layer_crossings = 0;
  /// What the dressed outfit got wrong as a whole, one sentence each: garments crossing each other.
  /// (Each garment's own problems are in DressedGarment::warnings.)
  std::vector<std::string> warnings;
  std::vector<int> layer_gap_vertices;
  std::vector<double> layer_gap_p5, layer_gap_median, layer_gap_asked;
  double seconds = 0.0;  ///< the whole run, wall-clock
};

/// A refusal by a stage after the meshes were read (a body of implausible height, a garment that is
/// not one for a person or that no fit places): the one line, and the result as far as the stages
/// got (`stages` ends with the one that refused, its reason the line), so that a caller can show
/// what was tried.
class DressRefused : public InputError {
 public:
  DressRefused(const std::string& line, DressResult so_far) : InputError(line), result_(std::move(so_far)) {}
  const DressResult& result() const { return result_; }

 private:
  DressResult result_;
};

/// Dresses the body in the garments, given inside to outside. Throws InputError naming the file
/// and the problem: an unreadable file, a mesh given in memory that is broken (empty, indices out
/// of range, non-finite, labels out of range), an unknown fabric, two garments of one name; and
/// DressRefused (an InputError) when a later stage refuses: a body of implausible height for its
/// units (with the units that would fit), a mesh with no arms or legs given as the body, a garment
/// that is not one for a person or that the placement could not fit.
DressResult dress(const MeshFile& body, const std::vector<GarmentFile>& garments, const DressOptions& options = {});

}  // namespace dresskit::dressing
