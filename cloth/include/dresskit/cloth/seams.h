#pragma once
// Seams, darts and pleats (methods.md §3): stitches from particle pairs or from two edge chains
// (resampled to match), their energy and forces, the gaps that say whether a seam is closed, and
// welding closed seams into single vertices on output. The simulator pulls stitches together with
// their zero-length springs and holds a stitch that has come within the seam tolerance.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "dresskit/cloth/cloth_model.h"

namespace dresskit::cloth {

/// A stitch's pull: stiffness k [N/m] up to max_force [N].
struct StitchLaw {
  double stiffness = 0.0;
  double max_force = 0.0;
};

/// Particle-to-particle stitches. Throws InputError naming the pair for an index
/// outside [0, particles) or a pair that joins a particle to itself.
void add_seam_pairs(SeamSet& seams, const std::vector<std::array<int, 2>>& pairs, int particles,
                    StitchLaw law);

/// Sews chain `a` to chain `b` (particle indices along two boundary polylines, a[0] meeting b[0]):
/// every particle of either chain is stitched to the point at the same fraction of arc length on
/// the other chain (to a particle when the point lies on one, else to a point of an edge), so
/// chains of different resolutions match; a particle-to-particle stitch found from both sides is
/// kept once, and one that would join a particle to itself (a dart's tip) is left out. Lengths at
/// positions x. Throws InputError for a chain of fewer than two particles or of zero length, or an
/// index out of range.
void add_seam_chains(SeamSet& seams, const Eigen::MatrixX3d& x, const std::vector<int>& a,
                     const std::vector<int>& b, StitchLaw law);

/// The default stiffness of a cloth's stitches: the mean rest stiffness of its structural springs
/// [N/m].
double default_stitch_stiffness(const SpringSet& springs);
/// Default caps for the stitches [first, size) of one seam: together they pull with at most
/// acceleration [m/s²] × the cloth's whole mass, so a far seam moves its garment at a bounded
/// acceleration however stiff the fabric, and can still lift the garment's weight. (Capping each
/// stitch by the fabric's tension — 5 % strain of a structural spring — pulled a 0.36 m
/// gray-interlock panel at about 10⁵ m/s² and tore it in the first step; by 50 m/s² × the stitch
/// particle's own mass, the seams could not hold up the panel hanging from them.)
void cap_stitches_by_acceleration(SeamSet& seams, int first, const Eigen::VectorXd& mass,
                                  double acceleration);

/// The stitch's particles (a, b0, b1) and their weights (1, −(1 − t), −t) in c = Σ weight x.
void seam_weights(const SeamSet& seams, int s, int idx[3], double weight[3]);
/// c = x_a − ((1 − t) x_b0 + t x_b1) [m].
Eigen::Vector3d seam_gap(const SeamSet& seams, int s, const Eigen::MatrixX3d& x);
double seam_energy(const SeamSet& seams, const Eigen::MatrixX3d& x);  ///< [J] (cloth_model.h)
/// Adds each stitch's force wᵢ F(c) to its particles, F = −k c capped at max_force (f is #V×3) [N].
void add_seam_forces(const SeamSet& seams, const Eigen::MatrixX3d& x, Eigen::MatrixX3d& f);
/// The stitch's pull F(c) [N] (on the particle a; its weights spread it) and −∂F/∂c (3×3, positive
/// semi-definite): k I within the cap, max_force/|c| (I − ĉĉᵀ) beyond.
Eigen::Vector3d stitch_force(const SeamSet& seams, int s, const Eigen::Vector3d& c,
                             Eigen::Matrix3d* stiffness = nullptr);
/// Projective dynamics' target for the stitch: the d minimising ½ k |c − d|² + max_force |d| (a
/// soft threshold of c), so that k (c − d) is the capped pull.
Eigen::Vector3d stitch_target(const SeamSet& seams, int s, const Eigen::Vector3d& c);

struct SeamGaps {
  int stitches = 0;
  int closed = 0;                ///< stitches with |c| ≤ the tolerance
  double max = 0.0, mean = 0.0;  ///< |c| [m]
};
SeamGaps seam_gaps(const SeamSet& seams, const Eigen::MatrixX3d& x, double tolerance);

/// A representative particle for each of `particles`: particles joined by stitches share one (a
/// point-to-edge stitch joins the particle with both ends of the edge). Contacts between primitives
/// that share a representative are not collisions (the two sides of a seam meet on purpose).
std::vector<int> seam_representatives(const SeamSet& seams, int particles);

/// The cloth with its closed particle-to-particle stitches (|c| ≤ tolerance) welded: each group of
/// particles so joined becomes one vertex at their mean; faces that collapse are dropped. V: the
/// welded vertices; F: faces; to: for each particle its vertex in V.
void weld_seams(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, const SeamSet& seams,
                double tolerance, Eigen::MatrixX3d& V, Eigen::MatrixX3i& F, std::vector<int>& to);

}  // namespace dresskit::cloth
