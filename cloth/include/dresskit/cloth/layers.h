#pragma once
// Multi-layer garments (docs/cloth.md, "Layers"): a garment with thickness is a double layer — its
// surface and a copy offset along the normals by the thickness, joined vertex to vertex by
// structural springs and across each edge by shear springs with the layer's own coefficients (no
// bending springs between layers), rest length = thickness, length held inside [min, max]. Several
// garments are stacked as ordered layers from the body outwards.
#include <vector>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/collider.h"

namespace dresskit::cloth {

struct LayerThickness {
  double thickness = 0.0;  ///< rest distance between the layers [m], > 0
  double min = 0.0;        ///< shortest allowed [m], 0 < min ≤ thickness
  double max = 0.0;        ///< longest allowed [m], ≥ thickness
};

/// Area-weighted vertex normals of the model's faces at its rest positions (#V×3, unit; zero rows
/// for vertices without faces).
Eigen::MatrixX3d rest_vertex_normals(const ClothModel& model);

/// The double layer of a single-layer model: particles 0..V−1 are the inner layer (as given),
/// V..2V−1 the outer one at x + thickness · n. Each layer keeps the whole model's springs and mass
/// (two shells of the fabric). Between them: per vertex one layer_structural spring (stiffness =
/// the mean of that vertex's structural springs), per structural edge two layer_shear springs
/// (the edge's own constant); the structural ones are listed as limited to [min, max]. Faces:
/// inner reversed, outer, and the rim quads joining boundary edges, so the output is closed.
/// Throws InputError for a bad thickness interval or a model that already has several layers.
ClothModel make_double_layer(const ClothModel& single, const LayerThickness& thickness);

/// Stacks models (first = innermost) into one: particles, springs, faces and layers concatenated in
/// order; layer_offset accumulates each layer's thickness (double layers) plus `separation` [m]
/// between garments, and layer_min_gap is `separation` for each garment's innermost layer.
ClothModel stack_layers(const std::vector<ClothModel>& garments, double separation);

/// First particle of each stacked garment (and the total at the end), to map per-garment indices.
std::vector<int> garment_offsets(const std::vector<ClothModel>& garments);

struct LayerGap {
  int springs = 0;                          ///< layer_structural springs measured
  double min = 0.0, mean = 0.0, max = 0.0;  ///< their lengths [m]
};
/// Distances between the two layers of every double layer at positions x.
LayerGap layer_gap(const ClothModel& model, const Eigen::MatrixX3d& x);

/// For each particle p of a layer ≥ 1, the face of the layer beneath it: the one whose projection
/// onto p's nearest collider contains p's projection (of several, where the layer beneath folds,
/// the one nearest to p in space), with p's barycentric weights in it; −1 when none (beyond the
/// layer's border). Also each
/// particle's nearest collider, distance and normal.
struct LayerContacts {
  std::vector<int> below_face;     ///< index into ClothModel::faces, −1 none
  Eigen::MatrixX3d below_weights;  ///< barycentric weights of p in that face
  std::vector<int> collider;       ///< −1 without colliders
  Eigen::VectorXd distance;        ///< signed, to that collider [m]
  Eigen::MatrixX3d normal;         ///< its outward normal at the particle
  /// The layer beneath's distance from p's collider, interpolated at p (needs below_face[p] ≥ 0).
  double height_below(int p, const ClothModel& model, const Eigen::MatrixX3d& x,
                      const std::vector<Collider>& colliders) const;
};
/// With `highest`, of several faces beneath p the one highest over the collider at p's
/// projection (the outermost sheet where the layer beneath folds or overlaps itself).
LayerContacts match_layers(const ClothModel& model, const Eigen::MatrixX3d& x,
                           const std::vector<Collider>& colliders, bool highest = false);

struct LayerOrder {
  int checked = 0;     ///< particles of layers ≥ 1 lying over or under the layer beneath, near it
  int violations = 0;  ///< of those, the ones on its inner side
};
/// Layer order: each particle p of layer ℓ ≥ 1 within 10 layer spacings (the two layers' offset
/// difference) of the layer beneath is compared with its nearest point q there: p violates the
/// order when it lies on the layer's inner side, (p − q)·n(q) < −spacing/4, with n the layer's
/// angle-weighted pseudo-normal at q (the face's normal inside a face, the sum of the two faces'
/// normals on an edge, the angle-weighted sum around a vertex), turned to the side the layer lies
/// on at rest. Particles whose
/// nearest point is on the layer's border lie beside it and are not checked. A local test: where
/// hanging layers curl and fold together, a ray or a height along a collider's normal can cross the
/// layer beneath in order (measured: such a test flagged 1–3 particles of curled hems in 7 of 8
/// slightly shifted three-layer drops with no crossing at all); the side of the nearest point
/// cannot. The colliders are not needed (kept for the callers).
LayerOrder layer_order(const ClothModel& model, const Eigen::MatrixX3d& x,
                       const std::vector<Collider>& colliders);

}  // namespace dresskit::cloth
