#pragma once
// Sewing: the cut panels, placed around the body (carried to it from the body the pattern is
// placed for, where that stands elsewhere or is of another height), drawn together along their
// stitches in the cloth simulator at a set closing speed, each pair towards its midpoint or the
// nearest way around the body between its two sides, with the body as a collider, until every
// stitch pair has come within the tolerance (and is held there); then welded into one garment mesh.
//
//   const Pattern p = read_pattern("shirt_specification.json");
//   const SewResult r = sew_pattern(p, cut_pattern(p), body);
//   // r.garment: one mesh [m], labels = panels; every pair sewn when r.closed (and welded, but
//   // for r.unwelded)
#include <Eigen/Core>
#include <array>
#include <memory>
#include <functional>
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/pattern/cut.h"

namespace dresskit::cloth {
class MeshDistance;
}

namespace dresskit::pattern {

/// Where a body stands: GarmentCode places a pattern's panels around a body standing on y = 0 with
/// its torso centred on x = z = 0, facing +z, 1.72 m tall (its mean body).
struct BodyFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< the floor below the torso's centre [m]
  double height = 1.72;                              ///< [m]
};

/// A body's frame (+Y up, facing +z): the origin below the centre of the bounding box of the body's
/// vertices between 55 % and 70 % of its height (the torso, and what the pose holds of the arms and
/// hands at that height; all its vertices where none lies there), on the level of its lowest point.
BodyFrame body_frame(const mesh::TriangleMesh& body);

struct SewOptions {
  std::string fabric = "gray-interlock";  ///< a built-in fabric (docs/cloth.md)
  /// A stitch pair is sewn, then held and welded, once it comes within this distance [m].
  double tolerance = 0.001;
  /// Each stitch pair not yet sewn is drawn together at this speed [m/s], towards its midpoint or,
  /// where that lies inside the body, the nearest way around it
  /// (SimulationOptions::seam_closing_speed): at 0.5 a seam 40 cm open closes in under a second.
  double closing_speed = 0.5;
  /// Gravity while sewing [m/s²]: none by default, so that panels keep the places the pattern gives
  /// them while their seams close (settling afterwards drapes them).
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  double air_damping = 2.0;  ///< [1/s], so that panels do not overshoot
  double max_seconds = 3.0;  ///< simulated time at most [s]
  /// Steps at most: where the adaptive step shrinks, this bounds the time spent (600: one and a
  /// half times the steps of max_seconds at the simulator's full 1/120 s).
  int max_steps = 600;
  /// Cloth–cloth contacts a try may handle, at most, per particle and step of max_steps (0: no
  /// bound): where panels tangle, a step's collision passes handle thousands of contacts and can
  /// take a second, so a try also ends once its contacts (SewResult::contacts) reach max_steps ×
  /// particles × this (the shared patterns sew with 0.08–0.64 a particle and step). The bound
  /// follows from the pattern, never from the machine: the same pattern sews the same way anywhere.
  double max_contacts_per_step = 1.0;
  /// The simulator's adaptive step (SimulationOptions::max_strain_change): while seams are drawn
  /// across the body, strain changes fast by design, and the default 0.05 shrank the step to
  /// 3e-5 s; at 1 the step stays near 1/120 s and strain limiting keeps the fabric within 10 %.
  double max_strain_change = 1.0;
  bool body_collider = true;  ///< the body keeps the panels out while they close around it
  /// Between the panels and the body while sewing [unitless]: none, so that panels slide into
  /// place around the body (at 0.5 the shirt's shoulder seams stayed 2 cm open).
  double friction = 0.0;
  /// Cloth–cloth collisions while sewing: panels drawn across each other do not pass through.
  bool self_collision = true;
  /// Where drawing leaves pairs unsewn, some farther apart than weld_gap (closer ones are welded),
  /// the panels are sewn again from their places by seam forces instead, each stitch's pairs
  /// together pulling with at most this acceleration × the cloth's mass [m/s²], with
  /// fallback_friction against the body; the closer of the two results is kept (0: no second try).
  double fallback_acceleration = 40.0;
  double fallback_friction = 0.5;  ///< [unitless]
  /// Pairs that sewing leaves open but within this distance of each other are welded too, their
  /// two sides joined at their midpoint (settling then relaxes the triangles around them), unless
  /// that makes the garment cross itself; farther ones stay open. 0: only sewn pairs are welded.
  /// One triangle edge of the default cut (dress sets it to the cut's edge length) [m].
  double weld_gap = 0.02;
  /// The pattern's placement must suit the body: more than this share of the placed panels' points
  /// deeper than inside_depth [m] inside the body is an InputError (a pattern placed for another
  /// body; sewing from inside a body does not close and takes minutes).
  double max_inside_fraction = 0.01;
  double inside_depth = 0.01;
  /// The body the pattern's panels are placed for. Where the body to sew on stands elsewhere (its
  /// origin more than frame_tolerance away) or is of another height (by more than 2 %), the panels
  /// are first moved together: by the difference of the origins, and up or down so that their
  /// centroid's height over the floor scales with the bodies' heights (the pattern carried to this
  /// body, its panels keeping their sizes and their places relative to each other).
  BodyFrame pattern_body;
  double frame_tolerance = 0.01;  ///< [m]
  /// Stitches whose points lie on average above this share of the body's height over its floor
  /// (body_frame) are sewn first, the others once those are, where some lie below: a dress hangs
  /// from its shoulders while its skirt is sewn (sewn at once, the skirt's seams closing around the
  /// narrowing legs dragged the bodice down and its straps off the shoulders). 0: all at once.
  double first_above = 0.5;
  /// Panels so carried that come closer to the body than this [m] (a larger body) are moved out
  /// along their normals, in steps of it, until every point of them is that far outside.
  double clearance = 0.005;
  /// Each panel's rigid move onto this body (one 4×4 transform per panel, in the pattern's order),
  /// found by the caller from the parts of the body the pattern is placed for and of this one
  /// (dress: docs/pattern.md). Given, it replaces the move by frames (pattern_body); the panels
  /// are then moved out of the body as there (clearance).
  std::vector<Eigen::Matrix4d> panel_moves;
  /// Called after every sewing step with the simulated seconds so far (both tries: drawing, then
  /// seam forces) and max_seconds; may be empty.
  std::function<void(double simulated, double limit)> on_step;
};

struct SewResult {
  bool closed = false;   ///< every stitch pair sewn (came within the tolerance, then held)
  int stitch_pairs = 0;  ///< matching point pairs to sew
  int closed_pairs = 0;  ///< of those, sewn (and welded)
  int welded_open = 0;   ///< pairs not sewn but welded, their sides within SewOptions::weld_gap
  /// Largest stitch pair distance at the end, before welding [m]: a sewn pair is held together by
  /// the simulator's constraint phase, and the collision passes after it may leave it slightly
  /// apart.
  double max_gap = 0.0;
  double mean_gap = 0.0;           ///< [m]
  std::vector<double> stitch_gap;  ///< per stitch of the pattern, its largest pair distance [m]
  int steps = 0;                   ///< of both tries when the fallback ran
  double simulated_seconds = 0.0;  ///< of the result kept
  double seconds = 0.0;   ///< wall-clock, the body's distance field included
  /// Cloth–cloth contacts handled while sewing, both tries: proximity pairs, contacts on the
  /// paths and particles in impact zones, summed over the steps (SewOptions::max_contacts_per_step).
  long long contacts = 0;
  /// "closed", "time limit", "step limit", "contact limit" or the simulator's failure
  std::string stopped;
  std::string method;     ///< "drawn" (at the closing speed) or "seam forces" (the fallback)
  /// How far the panels were moved from where the pattern places them, to this body
  /// (SewOptions::pattern_body; with SewOptions::panel_moves, the mean move of their points) [m];
  /// zero where the body stands where the pattern's does.
  Eigen::Vector3d moved_by = Eigen::Vector3d::Zero();
  /// Of those, the panels then moved out of the body (SewOptions::clearance).
  int panels_moved_out = 0;
  Eigen::MatrixX3d sewn;  ///< #V×3 every cut vertex at the end (CutPattern's order) [m]
  /// The welded garment [m]: sewn pairs joined into single vertices, faces turning as cut;
  /// labels: the panel of each vertex (label_names: the panel names).
  mesh::TriangleMesh garment;
  std::vector<int> welded_vertex;  ///< #V of the cut: its vertex in garment
  /// Sewn pairs left unwelded because welding them made the garment cross itself (a fold of cloth
  /// between their sides), as garment vertex pairs: to be held together by seams while settling.
  std::vector<std::array<int, 2>> unwelded;
};

/// Sews the cut pattern around the body (any mesh in metres; with body_collider false it may be
/// empty). body_distance, when given, is the body's distance already built (it must be of this
/// body); otherwise it is built here when body_collider asks for it. Throws InputError for an
/// unknown fabric, or panels placed inside the body (SewOptions::max_inside_fraction).
SewResult sew_pattern(const Pattern& pattern, const CutPattern& cut, const mesh::TriangleMesh& body,
                      const SewOptions& options = {},
                      std::shared_ptr<const cloth::MeshDistance> body_distance = nullptr);

}  // namespace dresskit::pattern
