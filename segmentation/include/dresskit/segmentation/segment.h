#pragma once
// Spectral segmentation of body and garment meshes into named parts (docs/segmentation.md).
// One-off use: segment_mesh(mesh, options). Units: metres; the mesh's axes as loaded (+Y up unless
// the options say otherwise or ask for an estimate).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/segmentation/graph.h"
#include "dresskit/segmentation/kmeans.h"
#include "dresskit/segmentation/spectral.h"

namespace dresskit::segmentation {

/// The largest number of parts (given or automatic) that segment_mesh accepts.
constexpr int kMaxParts = 64;

struct SegmentationOptions {
  /// Total number of parts over all connected components; 0 = chosen by the largest eigengap of the
  /// union of the components' spectra, between #components + 1 and max_parts.
  int parts = 0;
  int max_parts = 8;  ///< upper bound of the automatic choice
  /// Automatic choice only: after the eigengap, a closed component (a body, no boundary edge) takes
  /// one more part while the result stays a star (a hub and limbs) with one more limb that sticks
  /// out at least as far as its junction is wide (part_elongation ≥ 1); this separates a body's
  /// head, which the eigengap leaves with the torso. Garments are left to the eigengap.
  bool grow_limbs = true;
  AffinityOptions affinity;
  /// Boundary vertices of one component closer than this many mean edge lengths, and more than six
  /// edges apart, are joined (bridge_boundary_gaps: a blouse's open front); 0 = off.
  double bridge_gaps = 2.0;
  LaplacianKind laplacian = LaplacianKind::normalized;
  EigenOptions eigen;
  KMeansOptions kmeans;
  /// Besides k-means with k clusters, k + 1 … k + over_segmentation clusters merged back to k by
  /// structure are tried; the partition with the most limb (leaf) parts, then the lowest normalised
  /// cut wins. 0 = classic spectral clustering only.
  int over_segmentation = 2;
  bool cleanup = true;           ///< one connected patch per part, then boundary smoothing
  int smoothing_iterations = 4;  ///< boundary smoothing sweeps
  /// Half-width of the band in which the random walker re-decides the part boundaries, in radii of
  /// each junction (refine_boundaries_random_walker); 0 = off.
  double boundary_band = 1.0;
  /// Limb cuts reshaped along isolines of the harmonic field from each limb's tip (vertices beyond
  /// this fraction of the limb's depth) to the hub's core (reshape_limb_cuts); 0 = off.
  double limb_tip_fraction = 0.95;
  /// Symmetric cuts: when at least 90 % of a component's vertices have a vertex within this many
  /// mean edge lengths of their mirror image across the sagittal plane (normal: left, through the
  /// component's area centroid), the limb cuts are made mirror-symmetric (reshape_limb_cuts with
  /// mirror_vertices); 0 = off.
  double symmetry_tolerance = 0.5;
  /// A component that is a tube with two openings, the lower one at least as wide as the upper one
  /// (a skirt: detect_skirt), is cut by its own geometry into a waist band and left and right
  /// halves (split_skirt, names skirt_waist, skirt_left, skirt_right) instead of by the spectrum:
  /// it takes three parts of the total, when the given number leaves the other components at least
  /// one each. false = a skirt is one part `skirt` (or whatever the spectrum gives it).
  bool split_skirts = true;
  /// Up and forward (facing) directions of the character; a zero vector = estimate from the mesh
  /// (up: area-weighted PCA; forward: the feet, else the PCA axis of least spread, sign +Z).
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  Eigen::Vector3d forward = Eigen::Vector3d::Zero();
};

/// Up/forward/left axes used for naming; left = up × forward is the character's left.
struct AxesEstimate {
  Eigen::Vector3d up = Eigen::Vector3d::UnitY(), forward = Eigen::Vector3d::UnitZ(),
                  left = Eigen::Vector3d::UnitX();
  bool up_given = false, forward_given = false;
  /// How the forward sign was decided: "given", "feet" or "default +Z"; same for up ("given",
  /// "pca").
  std::string up_source, forward_source;
};

struct NamedPart {
  std::string name;         ///< head, torso, arm_left, …, body, sleeve_left, leg_left, skirt,
                            ///< skirt_waist, skirt_left, part_N
  double confidence = 0.0;  ///< 0–1: how clearly the geometry supports the name
  int component = 0;        ///< connected component the part lies in
  int vertices = 0;
  double area = 0.0;  ///< [m²]
};

/// Wall-clock seconds per phase: graph and affinities; eigenpairs and the number of parts; k-means,
/// clean-up and merging of every candidate; axes and names; all of it.
struct SegmentationTimings {
  double graph = 0, eigen = 0, clustering = 0, naming = 0, total = 0;
};

struct SegmentationResult {
  Eigen::VectorXi vertex_labels;  ///< #V part index per vertex, −1 for vertices without a face
  Eigen::VectorXi face_labels;    ///< #F part index per face
  std::vector<NamedPart> parts;   ///< index = label
  int parts_chosen =
      0;  ///< parts in the result (the number asked for unless a cluster came out empty)
  bool parts_automatic = false;
  int limbs_added = 0;  ///< parts added after the eigengap's choice (grow_limbs)
  int components = 0;   ///< connected components with faces
  std::vector<int> parts_per_component;
  int isolated_vertices = 0;  ///< vertices without a face (label −1)
  int bridged_edges = 0;      ///< edges added across boundary gaps
  Eigen::VectorXd spectrum;   ///< sorted union of the components' smallest eigenvalues
  double eigengap = 0.0;  ///< λ_K / λ_{K−1} of the union spectrum at the chosen K (0 if undefined)
  double eigen_residual = 0.0;    ///< max ‖L x − λ x‖ over every eigenpair computed
  int eigen_iterations = 0;       ///< total Lanczos restarts
  double kmeans_cost = 0.0;       ///< of the winning embedding (last component with ≥ 2 parts)
  int clusters_before_merge = 0;  ///< k-means clusters of the winning candidate (same component)
  double normalized_cut = 0.0;    ///< Σ over parts of cut / volume, summed over the components
  int relabelled_vertices = 0;    ///< vertices changed by the clean-up (candidates without merging)
  int refined_vertices =
      0;  ///< vertices moved by the boundary refinement (random walker, isolines)
  /// Components cut as skirts (split_skirts), and where each one's waist band ends, as a fraction
  /// of the skirt's length from the waist.
  std::vector<int> skirt_components;
  std::vector<double> skirt_band_fraction;
  AxesEstimate axes;
  SegmentationTimings seconds;

  std::vector<std::string> part_names() const;
};

/// Segments the mesh. Throws InputError for an unusable mesh or option (no faces, parts < 0, more
/// parts than vertices or than kMaxParts, fewer parts than components) and EigenSolverError when
/// the eigen-solver does not converge (the message says what was tried).
SegmentationResult segment_mesh(const mesh::TriangleMesh& mesh, const SegmentationOptions& options = {});

}  // namespace dresskit::segmentation
