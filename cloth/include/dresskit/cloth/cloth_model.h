#pragma once
// A cloth as particles and springs, in flat arrays (structure of arrays): particles are the mesh
// vertices; springs are structural (mesh edges, quad sides), shear (quad diagonals) and bending
// (across every interior edge, between the two opposite vertices). Stiffness from the fabric:
// docs/cloth.md.
#include <cstdint>
#include <vector>

#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/stiffness_law.h"
#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::cloth {

/// layer_structural / layer_shear join the two layers of a double-layer garment (cloth/layers.h).
enum class SpringType : std::uint8_t {
  structural = 0,
  shear = 1,
  bending = 2,
  layer_structural = 3,
  layer_shear = 4
};

/// #S springs, one entry per spring in every array.
struct SpringSet {
  std::vector<int> i, j;                ///< end particles
  std::vector<double> rest_length;      ///< [m]
  std::vector<double> k_rest, k_knee;   ///< stiffness at rest and at the knee strain [N/m]
  std::vector<SpringType> type;
  /// Springs whose length is held inside [min, max] by the strain-limiting correction whether or
  /// not strain limiting is switched on (the inter-layer springs of a double layer): spring index,
  /// shortest and longest length [m]. A sparse list: most springs have none.
  std::vector<int> limited;
  std::vector<double> limit_min, limit_max;
  int size() const { return static_cast<int>(i.size()); }
  StiffnessLaw law(int s) const { return StiffnessLaw::fitted(k_rest[s], k_knee[s], kKneeStrain); }
  int count(SpringType t) const;
};

/// Seams (methods.md §3): stitches, each pulling particle a to the point (1 − t) x_b0 + t x_b1 of
/// an edge b0–b1 (b1 = b0 and t = 0 for a particle-to-particle stitch). With c = x_a − that point,
/// the pull is methods.md's F = k (p2 − p1) = −k c, its magnitude capped at max_force so that a seam
/// that starts far apart does not tear its panel's edge: energy ½ k |c|² up to |c| = c0 = max_force / k,
/// max_force (|c| − c0/2) beyond (convex, C¹). Darts and pleats are seams within one panel
/// (cloth/seams.h).
struct SeamSet {
  std::vector<int> a, b0, b1;
  std::vector<double> t;          ///< position along b0–b1, in [0, 1]
  std::vector<double> stiffness;  ///< k [N/m]
  std::vector<double> max_force;  ///< [N]
  int size() const { return static_cast<int>(a.size()); }
};

struct ClothBuildOptions {
  /// The fabric's warp direction in space; projected onto each face's plane [unitless].
  Eigen::Vector3d warp_direction = Eigen::Vector3d::UnitX();
  bool bending_springs = true;
  /// Total mass [kg]; 0 = areal density × area.
  double total_mass = 0.0;
};

struct ClothModel {
  Eigen::MatrixX3d rest_positions;  ///< #V×3 [m]
  Eigen::VectorXd mass;             ///< #V [kg]
  Eigen::MatrixX3i faces;           ///< #F×3, the faces kept (zero-area ones are skipped)
  SpringSet springs;
  SeamSet seams;
  /// #V, the layer of each particle from the body outwards (0 for a single-layer cloth).
  Eigen::VectorXi layer;
  /// Per layer: the distance kept from colliders beyond the collision margin [m] — the thickness of
  /// the layers beneath, so that a layer rests on the ones below it (cloth/layers.h).
  std::vector<double> layer_offset{0.0};
  /// Per layer: the least distance the layer-order guard keeps it above the layer beneath [m] — the
  /// separation between garments; half the compression limit between a double layer's two layers.
  std::vector<double> layer_min_gap{0.0};
  int skipped_zero_area_faces = 0;     ///< faces of zero area: no mass, no springs
  int skipped_zero_length_springs = 0; ///< coincident ends: never divided by
};

/// Builds particles and springs from a mesh (quads kept as quads: their diagonals are shear springs).
/// Throws InputError when the fabric's density or the total mass is not positive.
ClothModel build_cloth(const mesh::TriangleMesh& mesh, const Fabric& fabric,
                       const ClothBuildOptions& options = {});

/// A flat rectangular grid of quads: size [m] along two in-plane axes, resolution = vertices per
/// side (≥ 2), centred at `center`, facing `normal`. Vertex (i, j) is index j·nx + i; the first axis
/// is the normal's perpendicular closest to +X. Throws InputError for a bad size or resolution.
mesh::TriangleMesh make_grid(const Eigen::Vector2d& size, const Eigen::Vector2i& resolution,
                       const Eigen::Vector3d& center, const Eigen::Vector3d& normal);

}  // namespace dresskit::cloth
