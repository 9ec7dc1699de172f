#pragma once
// Label clean-up on the vertex graph (pure kernels): one connected patch per label, smooth
// boundaries.
#include <Eigen/Core>
#include <vector>

#include "dresskit/segmentation/graph.h"

namespace dresskit::segmentation {

/// Keeps the largest connected patch (by vertex area) of every label and gives each other patch to
/// the neighbouring label that shares the most affinity with it, until every label present is one
/// patch. Labels −1 are left alone. Returns the number of vertices relabelled.
int merge_orphan_patches(const MeshGraph& graph, const Adjacency& adjacency,
                         const Eigen::VectorXd& vertex_area, Eigen::VectorXi& labels);

/// Boundary smoothing: `iterations` sweeps in which a vertex on a label boundary takes the label
/// with the largest total affinity among itself (weight: its mean edge affinity) and its
/// neighbours. Returns the number of label changes.
int smooth_label_boundaries(const MeshGraph& graph, const Adjacency& adjacency, int iterations,
                            Eigen::VectorXi& labels);

/// Merges adjacent parts until `target` labels remain (labels ≥ 0 of the vector, which must be
/// 0..q−1 with every label present): each step takes the merge that leaves the most leaf parts
/// (parts that touch exactly one other part: limbs, sleeves, trouser legs), then the lowest
/// normalised cut. A body over-segmented into head, chest, belly and limbs thus merges chest and
/// belly, not head and chest. Relabels to 0..target−1 and returns the number of leaf parts at the
/// end.
int merge_parts_towards_star(const MeshGraph& graph, int target, Eigen::VectorXi& labels);

/// Number of leaf parts (touching exactly one other part) of a labelling (labels ≥ 0).
int count_leaf_parts(const MeshGraph& graph, const Eigen::VectorXi& labels);

/// Boundary refinement by a random walker (Grady 2006) in a band around every part boundary: the
/// vertices of a label closer to its boundary with label b than `band` × the radius of that
/// junction (the mean distance of the junction's boundary vertices from their centroid), and
/// closer than half the label's depth (its largest distance to a boundary, so every label keeps
/// seeds), are freed; the other vertices are seeds of their label, and each freed vertex takes the
/// label whose seeds a random walk on the affinities most likely reaches first. The cut thus moves
/// to the junction's concave crease or narrowest place within the band, whatever the mesh
/// resolution. V is #V×3. Returns the number of vertices relabelled.
int refine_boundaries_random_walker(const MeshGraph& graph, const Adjacency& adjacency,
                                    const Eigen::MatrixX3d& V, double band,
                                    Eigen::VectorXi& labels);

/// Reshapes the cuts between a hub (the part touching every other; of several, the one sharing the
/// most affinity with the others) and its limbs along isolines of harmonic fields: seeds are each
/// part's far end (vertices at least `tip_fraction` of the part's depth from its boundary: a limb's
/// tip, the hub's core), the random walker gives each vertex the probability u_l of reaching limb
/// l's tip first, and a vertex joins the limb with the largest u_l / c_l ≥ 1, else the hub. c_l is
/// the mean of u_l on limb l's current cut, except for two limbs that touch each other (trouser
/// legs at the crotch): their c is the crotch's level, the largest min(u_a, u_b) over the
/// vertices, so that both legs start at the crotch. Each cut follows the field: it leans where the
/// limbs meet (lower between two legs than at the outer hip). Components that are no star are left
/// alone. Returns the number of vertices relabelled.
///
/// With a mirror map (mirror[v] = the vertex at v's mirror image, −1 for none: mirror_vertices),
/// the decision is made mirror-symmetric: each limb's field is averaged with its mirror limb's
/// field at the mirror vertex, and the two levels with each other (the mirror limb of l: the label
/// that most mirror images of l's vertices carry). A symmetric garment then gets symmetric cuts,
/// whatever asymmetry k-means left in the cuts before.
int reshape_limb_cuts(const MeshGraph& graph, const Adjacency& adjacency, double tip_fraction,
                      Eigen::VectorXi& labels, const std::vector<int>& mirror = {});

/// Mirror symmetry across the plane through the area centroid of `vertices` with normal `normal`:
/// returns #V entries, mirror[v] = the vertex nearest to v's mirror image when it lies within
/// `tolerance` [m], else −1 (and −1 for vertices not listed); empty when fewer than `share` of the
/// vertices have a mirror vertex (the component is not symmetric).
std::vector<int> mirror_vertices(const Eigen::MatrixX3d& V, const Eigen::VectorXd& vertex_area,
                                 const std::vector<int>& vertices, const Eigen::Vector3d& normal,
                                 double tolerance, double share = 0.9);

/// For each label (0..max): its depth (the largest geodesic distance, within the label, from its
/// boundary with other labels) divided by the radius of that boundary (the mean distance of the
/// boundary vertices from their centroid): a limb, a sleeve or a head sticks out further than its
/// junction is wide (≥ 1), a collar or a hem band does not. 0 for a label without a boundary.
Eigen::VectorXd part_elongation(const MeshGraph& graph, const Adjacency& adjacency,
                                const Eigen::MatrixX3d& V, const Eigen::VectorXi& labels);

/// #F face labels: the label that at least two corners share, else the first corner's.
Eigen::VectorXi face_labels_from_vertices(const Eigen::MatrixX3i& F, const Eigen::VectorXi& labels);

}  // namespace dresskit::segmentation
