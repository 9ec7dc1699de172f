#pragma once
// Where a garment's own wearer stood, and the garment carried from there onto another body
// (docs/alignment.md#wearer). The body, cut into its parts, is rigged with bones (torso, head, and
// each arm and leg as an upper and a lower bone) and fitted into the garment by articulated
// registration: a similarity of the whole body and a turn of each bone about its joint, so that the
// garment lies around the body at an even ease per bone. The body so posed stands where the
// garment's wearer stood; each garment vertex then takes the bone weights of the posed body near
// it and is carried back onto the body as it is, bone by bone (linear blend skinning inverted).
// No part of the garment needs to be recognised first: only the body's parts are.
//
//   const BodyRig rig = rig_body(body);               // body with part labels [m, +Y up]
//   const WearerFit fit = fit_wearer(rig, body, garment.V);
//   const CarriedGarment carried = carry_garment(rig, fit, garment);
//   // carried.V: the garment on the body; carried.labels: the body part each vertex lies over
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::alignment {

/// The body parts a rig knows; a label file's or segmentation's names are read as one of them
/// ("head_neck" as head, "left_arm" as arm_left, "body" as torso, ...).
enum class BodyPartKind : int { torso = 0, head, arm_left, arm_right, leg_left, leg_right };
/// The part a name means, or torso for a name that means none.
BodyPartKind body_part_kind(const std::string& name);
std::string to_string(BodyPartKind kind);

/// A body's bones and skinning weights.
struct BodyRig {
  std::vector<std::string> bones;          ///< torso, head, arm_left_upper, arm_left_lower, ...
  std::vector<BodyPartKind> part;          ///< the body part of each bone
  std::vector<int> parent;                 ///< -1 for the root (torso)
  std::vector<Eigen::Vector3d> joint;      ///< where each bone turns about [m] (root: the torso's centroid)
  /// Per body vertex, up to kMaxInfluences bones and weights summing to 1 (unused entries: bone −1).
  static constexpr int kMaxInfluences = 3;
  Eigen::Matrix<int, Eigen::Dynamic, kMaxInfluences> influence_bone;
  Eigen::Matrix<double, Eigen::Dynamic, kMaxInfluences> influence_weight;
  Eigen::VectorXi bone_of_vertex;          ///< the bone of largest weight
  Eigen::MatrixX3d normals;                ///< the body's vertex normals
  double height = 0.0;                     ///< [m]
};

struct RigOptions {
  /// Weights blend across a joint over about this width [m] (diffusion of the bones' indicators
  /// along the body's edges).
  double blend_width = 0.05;
  /// A limb bent at least this much along its length [degrees] is split where it bends most (an
  /// elbow, a knee); a straighter one at kElbowFraction / kKneeFraction of its length.
  double min_bend_deg = 20.0;
};

/// Rigs a body whose vertices carry part labels (segmentation or a label file). Throws InputError
/// when no label names an arm or a leg.
BodyRig rig_body(const mesh::TriangleMesh& body, const RigOptions& options = {});

struct WearerFitOptions {
  int iterations = 30;       ///< Gauss–Newton iterations of the articulated fit per start
  int max_samples = 2500;    ///< garment points used (every k-th vertex beyond this)
  /// Residuals (distance along the body's normal beyond the bone's ease) count quadratically up to
  /// this many of the body's heights and linearly beyond (Huber) [unitless].
  double robust_scale = 0.01;
  /// Garment points farther than this many body heights from the posed body do not pull [unitless].
  double max_distance = 0.08;
  /// Starts of the whole body's placement tried (heights and sizes) before the articulated fit;
  /// the `starts_refined` best are refined articulated and the lowest cost kept.
  int starts_refined = 3;
  /// Weight of the priors that keep the body's size (log of the scale) and each bone's turn near
  /// the body's own, relative to the data's total weight [unitless]. A limb that few of the
  /// garment's points cover (a short sleeve) is held near the body's pose: a T-shirt made for an
  /// A-pose turns a T-posed body's upper arms by about 34° of their 45° (a weaker turn prior lets
  /// the legs under a skirt turn to fit the skirt).
  double scale_prior = 0.5, turn_prior = 0.2;
  double smallest_scale = 0.6, largest_scale = 1.6;  ///< the wearer's size against the body's
  /// The ease over a bone at most, in body heights [unitless]: cloth farther out (a skirt around the
  /// legs) stands off the body rather than telling where the limb inside it is, and leaves the
  /// bone to its prior.
  double max_ease = 0.03;
};

struct WearerFit {
  double scale = 1.0;                            ///< wearer against body
  Eigen::Matrix4d global = Eigen::Matrix4d::Identity();  ///< the body's similarity (after the bones)
  std::vector<Eigen::Matrix3d> turn;             ///< per bone, its turn about its joint (parent frame)
  std::vector<Eigen::Matrix4d> bone_transform;   ///< per bone: body → wearer
  std::vector<double> ease;                      ///< per bone, the garment's mean height over it [m]
  std::vector<int> covered;                      ///< per bone, garment points that pulled on it
  /// Mean Huber loss of the garment points' residuals [m²] (points beyond max_distance count as
  /// at it), of the wearer found, and of the body as it is (no move, no turn; eases fitted).
  double cost = 0.0, cost_as_is = 0.0;
  int iterations = 0;
  std::string start;                             ///< which start the kept fit came from
  Eigen::MatrixX3d posed;                        ///< the body posed as the wearer [m]
  double seconds = 0.0;
};

/// The largest turn of a bone the garment covers [degrees].
double largest_turn_degrees(const WearerFit& fit);
/// The garment's RMS distance from an even ease over the wearer, from the fit's cost (for residuals
/// within the robust scale: cost = ½ mean r²) [m].
double rms_from_ease(const WearerFit& fit);

/// Fits the rigged body into the garment's vertices (garment_points, #G×3 [m], +Y up).
WearerFit fit_wearer(const BodyRig& rig, const mesh::TriangleMesh& body, const Eigen::MatrixX3d& garment_points,
                     const WearerFitOptions& options = {});

struct CarryOptions {
  /// Sweeps smoothing the garment's bone weights along its edges, so that cloth hanging between
  /// two limbs (a skirt between the legs) moves with both rather than tearing between them.
  int smoothing_sweeps = 10;
};

struct CarriedGarment {
  Eigen::MatrixX3d V;           ///< the garment on the body [m], in the garment's vertex order
  Eigen::VectorXi labels;       ///< per vertex, the index of the part it lies over
  std::vector<std::string> label_names;  ///< body, hood, sleeve_left, sleeve_right, leg_left, leg_right
  double mean_move = 0.0;       ///< mean distance its vertices moved [m]
};

/// Carries the garment from the fitted wearer onto the body (inverse skinning with the bone weights
/// of the posed body nearest each garment vertex, smoothed along the garment).
CarriedGarment carry_garment(const BodyRig& rig, const WearerFit& fit, const mesh::TriangleMesh& garment,
                             const CarryOptions& options = {});

}  // namespace dresskit::alignment
