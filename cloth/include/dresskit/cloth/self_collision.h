#pragma once
// Cloth–cloth collisions: self-contact of one cloth and contact between layers and garments
// (Bridson, Fedkiw & Anderson 2002, "Robust treatment of collisions, contact and friction for cloth
// animation"). After a step has moved the particles from x0 (intersection-free) to x1:
//   1. proximity: vertex–triangle and edge–edge pairs closer than the cloth thickness at x0 are
//   kept
//      from approaching and eased apart towards the thickness, with Coulomb friction;
//   2. continuous collision detection on the straight paths x0 → x1: each contact gets an inelastic
//      correction, a few passes;
//   3. rigid impact zones (Provot 1997) for what is left: the particles of the pairs still in
//   contact
//      are merged into zones that move rigidly from x0 (an invertible path: no zone can cut
//      itself), merging until no contact is left; as a last resort every free particle stays at x0.
// So a state that starts without intersections never gains one. A bounding volume hierarchy over
// the triangles (refitted with swept boxes each pass) finds the candidate pairs.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "dresskit/cloth/triangle_bvh.h"

namespace dresskit::cloth {

struct SelfCollisionOptions {
  /// Distance kept between parts of the cloth that are not neighbours [m] (the proximity zone).
  double thickness = 0.001;
  /// Coulomb friction between cloth surfaces in proximity [unitless].
  double friction = 0.3;
  /// Continuous-collision passes with corrections before impact zones take over.
  int impulse_passes = 6;
  /// Impact-zone merges before every free particle is held at its start position.
  int zone_passes = 64;
};

struct SelfCollisionResult {
  int proximity_pairs = 0;  ///< vertex–triangle and edge–edge pairs within the thickness at x0
  int repulsions = 0;       ///< of those, corrected (approaching or closer than the thickness)
  int ccd_collisions = 0;   ///< contacts on the paths corrected by the collision passes
  int ccd_passes = 0;
  int zones = 0;           ///< rigid impact zones at the end (0 when the passes sufficed)
  int zone_particles = 0;  ///< particles in them
  bool held = false;       ///< the last resort was used: every free particle stayed at x0
  /// Particles of edge–triangle pairs that cross at x0; a pair with one on each side is left out
  /// (the cloth started tangled; a state without crossings never gains one).
  int tangled_particles = 0;
};

/// Edges of a triangle list, each once (i < j), with one owning triangle each.
struct EdgeList {
  std::vector<int> i, j, owner;
  Eigen::MatrixX3i face_edges;  ///< #F×3: edge k of face f joins its corners k and (k + 1) mod 3
};
EdgeList triangle_edges(const Eigen::MatrixX3i& F);

class SelfCollision {
 public:
  SelfCollision() = default;
  /// faces: the cloth's triangles; joined: a representative particle for each particle (#V) —
  /// particles with the same representative count as one (a sewn seam), so primitives sharing one
  /// are neighbours and never tested; empty = every particle its own.
  SelfCollision(const Eigen::MatrixX3i& faces, int particles, std::vector<int> joined,
                SelfCollisionOptions options = {});

  /// Moves x1 so that no pair of non-neighbouring primitives comes closer than the thickness on the
  /// way from x0 (see the file comment). inverse_mass: 0 for pinned particles (they never move).
  SelfCollisionResult resolve(const Eigen::MatrixX3d& x0, Eigen::MatrixX3d& x1,
                              const Eigen::VectorXd& inverse_mass);

  const SelfCollisionOptions& options() const { return options_; }
  /// The candidate list of the last resolve(), each pair as (kind, a, b): 0 = vertex a – face b,
  /// 1 = edge a – edge b with a < b (edges numbered as triangle_edges(faces) numbers them). For
  /// tests.
  std::vector<std::array<int, 3>> listed_pairs() const;
  bool empty() const { return faces_.rows() == 0; }
  const std::vector<int>& joined() const { return rep_; }

 private:
  struct Pair {
    int kind;  ///< 0 vertex–triangle (a = vertex, b = face), 1 edge–edge (a, b edges)
    int a, b;
    double d0;  ///< distance of the two primitives at the step's start (x0)
  };
  Eigen::Vector3d closest(const Pair& pair, const Eigen::MatrixX3d& x, double w[4]) const;
  /// The candidate list made anew for the paths x0 → x1 (see the .cpp).
  void candidates(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, std::vector<Pair>& out);
  /// A pair within the thickness at the step's start: closest points' weights, distance, normal.
  struct Close {
    Pair pair;
    double w[4];
    double d;
    Eigen::Vector3d normal;
    bool touching = false;  ///< closer than 1e-6 h: normal = the surface's, turned at use
  };
  /// The list brought up to date for the particles flagged in stale_ (see the .cpp).
  void update_candidates(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                         std::vector<Pair>& out);
  /// Distances at x0 for the pairs from first on; drops those that cannot come within the
  /// thickness while their particles stay in their listed boxes.
  void keep_reachable(const Eigen::MatrixX3d& x0, std::vector<Pair>& out, std::size_t first);
  void find_close_pairs(const Eigen::MatrixX3d& x0, const std::vector<Pair>& pairs);
  /// Flags (tangled_) the particles of the edge–triangle pairs that cross at x0.
  void find_tangles(const Eigen::MatrixX3d& x0);
  bool vertex_in_face(int v, int f) const;
  bool edges_touch(int e1, int e2) const;
  void indices(const Pair& p, int idx[4]) const;

  Eigen::MatrixX3i faces_;
  EdgeList edges_;
  std::vector<int> rep_;
  std::vector<int> vertex_owner_;
  /// Per face, what the whole candidate list reads of it, side by side (candidates() visits every
  /// pair of neighbouring faces): its corners' representatives, and its k-th corner and k-th edge
  /// where it owns them (−1 where not).
  struct FaceRecord {
    int rep[3], vertex[3], edge[3];
  };
  std::vector<FaceRecord> face_records_;
  std::vector<std::array<int, 2>> edge_reps_;  ///< per edge: its ends' representatives
  std::vector<int> vertex_faces_start_, vertex_faces_;  ///< faces around each particle (CSR)
  std::vector<char> stale_;  ///< per particle: its path has left its listed box grown by h/2
  Eigen::MatrixX3d lb_lo_, lb_hi_;  ///< per particle: its listed box (its path's when listed)
  Eigen::VectorXd reach_;           ///< per particle: farthest point of that box grown by h/2 from x0
  std::vector<Pair> pairs_;         ///< the candidate list
  std::vector<char> tangled_;       ///< per particle: in a crossing at the step's start
  int tangled_count_ = 0;
  std::vector<Close> close_;        ///< the pairs within the thickness at step_x0_
  Eigen::MatrixX3d step_x0_;        ///< the start of the step of the last resolve()
  Eigen::MatrixX3d verified_;  ///< x1 at the end of the last resolve() for step_x0_: every pair clear
  SelfCollisionOptions options_;
  TriangleBvh bvh_;
};

/// Edge–triangle crossings at x of a triangle mesh (faces F), neighbours (sharing a particle, or
/// one with the same representative in joined) excluded; brute force over a BVH, for reports and
/// tests.
int count_intersections(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& F,
                        const std::vector<int>& joined = {});
/// The vertices of those crossings (both ends of each crossing edge and the corners of the
/// triangle it crosses), sorted, each once. With `group` (one entry per vertex: a garment, a layer),
/// only the crossings of an edge and a triangle of different groups.
std::vector<int> crossing_vertices(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& F,
                                   const std::vector<int>& group = {});

}  // namespace dresskit::cloth
