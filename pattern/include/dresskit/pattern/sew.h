#pragma once
// Sewing: the cut panels, placed around the body, pulled together by their stitches' seam forces in
// the cloth simulator (methods.md §3: F = k (p2 − p1) up to a cap) with the body as a collider,
// until every stitch pair is within the tolerance; then welded into one garment mesh.
//
//   const Pattern p = read_pattern("shirt_specification.json");
//   const SewResult r = sew_pattern(p, cut_pattern(p), body);
//   // r.garment: one mesh [m], labels = panels; r.max_gap ≤ 1 mm when r.closed
#include <Eigen/Core>
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/pattern/cut.h"

namespace dresskit::pattern {

struct SewOptions {
  std::string fabric = "gray-interlock";  ///< a built-in fabric (docs/cloth.md)
  /// A stitch pair is closed, then held and welded, within this distance [m].
  double tolerance = 0.001;
  /// Each stitch's pairs together pull with at most this acceleration × the whole cloth's mass
  /// [m/s²]; at 40 a seam closes 30 cm in about a third of a simulated second.
  double stitch_acceleration = 40.0;
  /// Gravity while sewing [m/s²]: none by default, so that panels keep the places the pattern gives
  /// them while their seams close (settling afterwards drapes them).
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  double air_damping = 2.0;  ///< [1/s], damps the seams' pull so that panels do not overshoot
  double max_seconds = 2.0;  ///< simulated time at most [s]
  /// Steps at most: where seams cannot close the adaptive step shrinks, and this bounds the time
  /// spent (600: two and a half times the steps of max_seconds at the simulator's full 1/120 s).
  int max_steps = 600;
  /// The simulator's adaptive step (SimulationOptions::max_strain_change): while seams pull edges
  /// across the body, strain changes fast by design, and the default 0.05 shrank the step to
  /// 3e-5 s; at 1 the step stays at 1/120 s and strain limiting keeps the fabric within 10 %.
  double max_strain_change = 1.0;
  bool body_collider = true;  ///< the body keeps the panels out while they close around it
  double friction = 0.5;      ///< between the panels and the body while sewing [unitless]
  /// Cloth–cloth collisions while sewing: panels pulled across each other do not pass through.
  bool self_collision = true;
};

struct SewResult {
  bool closed = false;   ///< every stitch pair within the tolerance
  int stitch_pairs = 0;  ///< matching point pairs sewn
  int closed_pairs = 0;
  double max_gap = 0.0;            ///< largest stitch pair distance at the end [m]
  double mean_gap = 0.0;           ///< [m]
  std::vector<double> stitch_gap;  ///< per stitch of the pattern, its largest pair distance [m]
  int steps = 0;
  double simulated_seconds = 0.0;
  double seconds = 0.0;   ///< wall-clock, the body's distance field included
  std::string stopped;    ///< "closed", "time limit", "step limit" or the simulator's failure
  Eigen::MatrixX3d sewn;  ///< #V×3 every cut vertex at the end (CutPattern's order) [m]
  /// The welded garment [m]: closed pairs joined into single vertices, faces turning as cut;
  /// labels: the panel of each vertex (label_names: the panel names).
  mesh::TriangleMesh garment;
  std::vector<int> welded_vertex;  ///< #V of the cut: its vertex in garment
};

/// Sews the cut pattern around the body (any mesh in metres; with body_collider false it may be
/// empty). Throws InputError for an unknown fabric.
SewResult sew_pattern(const Pattern& pattern, const CutPattern& cut, const mesh::TriangleMesh& body,
                      const SewOptions& options = {});

}  // namespace dresskit::pattern
