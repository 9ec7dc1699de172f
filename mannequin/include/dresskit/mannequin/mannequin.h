#pragma once
// The embedded default body: a procedural mannequin, the smooth union of ellipsoids and round cones,
// meshed by marching tetrahedra and remeshed isotropically. Every vertex carries its true part label:
// the part of the primitive nearest to it. Axes: +Y up, feet at y = 0, facing +Z; the character's
// left is +X (as in the MakeHuman data).
#include <array>
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/mannequin/implicit.h"

namespace dresskit::mannequin {

/// Body parts; the names match ../shared/data/labels/mh_body_part_labels.json.
enum class BodyPart : int { torso = 0, head_neck, arm_left, arm_right, leg_left, leg_right };
const std::vector<std::string>& body_part_names();

enum class Pose { a_pose, t_pose };
/// "a" / "a-pose" or "t" / "t-pose"; throws InputError naming the value otherwise.
Pose parse_pose(const std::string& text);

struct MannequinOptions {
  double height = 1.75;       ///< [m] sole to top of head, 1.0–2.5
  double girth = 1.0;         ///< horizontal scale of torso and limbs (1 = average adult), 0.6–1.8
  Pose pose = Pose::a_pose;   ///< A-pose: arms 45° below horizontal; T-pose: arms horizontal
  double edge_length = 0.02;  ///< [m] target edge length of the mesh
};

/// Joint positions [m]; index 0 = left (+X), 1 = right.
struct Skeleton {
  Eigen::Vector3d neck_base, head_top, pelvis;
  std::array<Eigen::Vector3d, 2> shoulder, elbow, wrist, hip, knee, ankle;
  double waist_y = 0.0;  ///< [m] height of the natural waist
};

/// The implicit body: primitives, joints and field. Cheap to build; meshing is make_mannequin.
class BodyShape {
 public:
  explicit BodyShape(const MannequinOptions& options = {});
  const MannequinOptions& options() const { return options_; }
  const Skeleton& skeleton() const { return skeleton_; }
  const ImplicitUnion& field() const { return field_; }
  /// Signed distance-like field of the body [m], negative inside.
  double value(const Eigen::Vector3d& p) const { return field_.value(p); }
  /// Body part of the primitive nearest to p.
  BodyPart part_at(const Eigen::Vector3d& p) const;

 private:
  MannequinOptions options_;
  Skeleton skeleton_;
  ImplicitUnion field_;
};

/// Throws InputError naming the field when an option is out of its documented range.
void check_options(const MannequinOptions& options);

/// A closed, manifold, outward-oriented triangle mesh of the body with per-vertex part labels
/// (label_names = body_part_names()).
mesh::TriangleMesh make_mannequin(const BodyShape& body);

}  // namespace dresskit::mannequin
