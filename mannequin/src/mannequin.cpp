#include "dresskit/mesh/names.h"
#include "dresskit/mannequin/mannequin.h"

#include <cmath>
#include <stdexcept>

#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/isosurface.h"
#include "dresskit/mesh/topology.h"
#include "mesh_field.h"

using namespace dresskit::mesh;

namespace dresskit::mannequin {

const std::vector<std::string>& body_part_names() {
  static const std::vector<std::string> names = {"torso",   "head_neck", "arm_left",
                                                 "arm_right", "leg_left", "leg_right"};
  return names;
}

Pose parse_pose(const std::string& text) {
  return parse_name<Pose>(text, {{"a-pose", Pose::a_pose}, {"a", Pose::a_pose}, {"A", Pose::a_pose}, {"t-pose", Pose::t_pose},
                           {"t", Pose::t_pose}, {"T", Pose::t_pose}},
                    "pose");
}

void check_options(const MannequinOptions& o) {
  auto need = [](bool ok, const std::string& what) {
    if (!ok) throw InputError(what);
  };
  need(std::isfinite(o.height) && o.height >= 1.0 && o.height <= 2.5,
       "height: " + std::to_string(o.height) + " m is outside 1.0–2.5 m");
  need(std::isfinite(o.girth) && o.girth >= 0.6 && o.girth <= 1.8,
       "girth: " + std::to_string(o.girth) + " is outside 0.6–1.8");
  need(std::isfinite(o.edge_length) && o.edge_length >= 0.004 && o.edge_length <= 0.1,
       "edge length: " + std::to_string(o.edge_length) + " m is outside 0.004–0.1 m");
}

// Proportions are fractions of the height H (y from the soles); horizontal sizes of the torso and
// limbs scale with the girth g as well. They follow the usual eight-head canon closely enough for a
// mannequin: chin at 0.86 H, shoulders at 0.80 H, hip joints at 0.50 H, knees at 0.28 H.
BodyShape::BodyShape(const MannequinOptions& options) : options_(options) {
  check_options(options);
  const double H = options.height, g = options.girth;
  auto P = [H](double x, double y, double z) { return Eigen::Vector3d(x * H, y * H, z * H); };
  auto& prims = field_.primitives;
  field_.blend = 0.025 * H;
  const int torso = int(BodyPart::torso), head = int(BodyPart::head_neck);

  prims.push_back(Primitive::ellipsoid(P(0, 0.928, 0.008), P(0.052, 0.068, 0.062), head, "head"));
  prims.push_back(Primitive::round_cone(P(0, 0.79, -0.004), P(0, 0.875, 0.004), 0.034 * H * g,
                                        0.03 * H * g, head, "neck"));
  prims.push_back(Primitive::ellipsoid(P(0, 0.715, 0), P(0.092 * g, 0.095, 0.062 * g), torso, "chest"));
  prims.push_back(Primitive::ellipsoid(P(0, 0.605, 0.002), P(0.080 * g, 0.075, 0.056 * g), torso, "abdomen"));
  prims.push_back(Primitive::ellipsoid(P(0, 0.525, -0.004), P(0.094 * g, 0.07, 0.062 * g), torso, "pelvis"));

  Skeleton& s = skeleton_;
  s.neck_base = P(0, 0.80, 0);
  s.head_top = P(0, 0.996, 0.008);
  s.pelvis = P(0, 0.525, 0);
  s.waist_y = 0.60 * H;
  const double arm_angle = options.pose == Pose::a_pose ? M_PI / 4 : 0.0;  // below horizontal
  const double leg_angle = 3.0 * M_PI / 180.0;                               // outwards
  const char* side_name[2] = {"left", "right"};
  for (int side = 0; side < 2; ++side) {
    const double sx = side == 0 ? 1.0 : -1.0;
    const int arm = int(side == 0 ? BodyPart::arm_left : BodyPart::arm_right);
    const int leg = int(side == 0 ? BodyPart::leg_left : BodyPart::leg_right);
    const std::string sn = side_name[side];
    const Eigen::Vector3d arm_dir(sx * std::cos(arm_angle), -std::sin(arm_angle), 0);
    s.shoulder[side] = P(sx * 0.098 * g, 0.80, 0);
    s.elbow[side] = s.shoulder[side] + 0.17 * H * arm_dir;
    s.wrist[side] = s.elbow[side] + 0.15 * H * arm_dir;
    prims.push_back(Primitive::round_cone(s.shoulder[side], s.elbow[side], 0.029 * H * g,
                                          0.021 * H * g, arm, "upper_arm_" + sn));
    prims.push_back(Primitive::round_cone(s.elbow[side], s.wrist[side], 0.020 * H * g,
                                          0.015 * H * g, arm, "forearm_" + sn));
    prims.push_back(Primitive::round_cone(s.wrist[side], s.wrist[side] + 0.06 * H * arm_dir,
                                          0.016 * H, 0.012 * H, arm, "hand_" + sn));

    const Eigen::Vector3d leg_dir(sx * std::sin(leg_angle), -std::cos(leg_angle), 0);
    // Hip joints further apart than the thigh radius: tangent thigh caps would pinch the surface at
    // the midplane, and marching tetrahedra would then make a handle at some grid spacings.
    s.hip[side] = P(sx * 0.056 * g, 0.50, 0);
    s.knee[side] = s.hip[side] + 0.225 * H * leg_dir;
    s.ankle[side] = s.knee[side] + 0.23 * H * leg_dir;
    prims.push_back(Primitive::round_cone(s.hip[side], s.knee[side], 0.05 * H * g, 0.031 * H * g,
                                          leg, "thigh_" + sn));
    prims.push_back(Primitive::round_cone(s.knee[side], s.ankle[side], 0.03 * H * g, 0.019 * H * g,
                                          leg, "shin_" + sn));
    prims.push_back(Primitive::round_cone(s.ankle[side] + P(0, -0.02, -0.012),
                                          s.ankle[side] + P(0, -0.032, 0.09), 0.02 * H, 0.014 * H,
                                          leg, "foot_" + sn));
  }
}

BodyPart BodyShape::part_at(const Eigen::Vector3d& p) const {
  return static_cast<BodyPart>(field_.primitives[field_.nearest(p)].part);
}

TriangleMesh make_mannequin(const BodyShape& body) {
  const double edge = body.options().edge_length;
  TriangleMesh mesh = mesh_implicit(body.field(), edge, feature_spacing(body.options().height));
  const TopologyReport t = analyse_topology(mesh);
  if (!t.closed || !t.outward || t.num_components != 1 || t.euler_characteristic != 2) {
    // The shape is designed to be a sphere topologically; anything else is a bug to report.
    throw std::logic_error("procedural mannequin is not a closed genus-0 surface (Euler " +
                           std::to_string(t.euler_characteristic) + ", " +
                           std::to_string(t.num_components) + " components)");
  }
  mesh.label_names = body_part_names();
  mesh.labels.resize(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    mesh.labels(i) = int(body.part_at(mesh.V.row(i).transpose()));
  }
  return mesh;
}

}  // namespace dresskit::mannequin
