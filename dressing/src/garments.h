#pragma once
// What the dressing pipeline does to one garment (dress.cpp): its rest shape, the regions its
// placement made cross rebuilt, its kind, and its waistband.
#include <memory>
#include <vector>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/inside.h"

namespace dresskit::dressing::detail {

/// The garment's rest shape for settling: DressedGarment::rest where placement set one, else as made.
mesh::TriangleMesh rest_shape(const DressedGarment& g);

/// A rest shape, for a garment of rest positions `rest` and faces F, that positions `placed` stretch
/// by at most (1 + strain_limit) where that needs no edge to grow more than `largest` times: each
/// edge's rest vector grown by its placed length over (1 + strain_limit) × its rest length, between
/// 1 and `largest`, and the positions whose edges best match the grown vectors (least squares,
/// each edge's relative change weighted alike). The garment grows where the body is larger than
/// its wearer; edges the placement does not stretch keep their lengths where the shape allows, and
/// near a grown region take a share of its growth. `grown`: the number of edges given a growth.
/// Returns `rest` when none is stretched.
Eigen::MatrixX3d loosened_rest(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3i& F, const Eigen::MatrixX3d& placed,
                               double strain_limit, double largest, int* grown = nullptr);

/// The garment's cloth for settling: built from its rest shape in its fabric; a sewn pattern's
/// stretch springs take the flat pattern's lengths (the sewing strains the fabric; the garment's
/// rest is its pattern), their stiffness kept per unit strain.
cloth::ClothModel garment_cloth(const DressedGarment& g, const cloth::Fabric& fabric);

/// Rebuilds the regions where the placed garment k crosses itself more often than as authored
/// (garments.cpp); updates its placed positions and crossings_placed.
void untangle(std::vector<DressedGarment>& garments, std::size_t k, const cloth::MeshDistance& body, double clearance);

/// Where garment k still crosses itself more often than as authored: moves it onto its placed
/// positions from a shape crossing itself as authored, its parts kept apart on the way
/// (garments.cpp); updates its placed positions and crossings_placed.
void untangle_along_path(std::vector<DressedGarment>& garments, std::size_t k);

/// Edge–triangle crossings between different garments at their positions `at` (placed or dressed;
/// dressed: a padded garment's two shells).
int crossings_between(const std::vector<DressedGarment>& garments, Eigen::MatrixX3d DressedGarment::*at);

/// How grade_layers moved one garment: vertices moved out and the largest move [m].
struct Grading {
  int vertices = 0;
  double largest = 0.0;
};

/// Each garment worn over others (garments in layer order, inside to outside) moved out where it
/// lies under those beneath it, at their placed positions: a vertex over them (cloth::match_layers,
/// the highest face beneath along the body's normal) lower than their height over the body plus
/// `separation` is moved out along the body's normal to it. The moves spread to the vertex's
/// neighbours (a bulge over what lies beneath, not a tent), and every sheet of the garment over one
/// place of the body moves as far as the lowest (a lapel keeps its side of the front). The
/// vertices of crossings still left with the garments beneath then move 2 mm farther out, along the
/// body's normal or, where that does not lead out of the garments beneath (an armpit, the crotch),
/// along the nearest face beneath, up to thirty rounds. Updates placed positions; returns the
/// moves per garment.
std::vector<Grading> grade_layers(std::vector<DressedGarment>& garments, const std::shared_ptr<const cloth::MeshDistance>& body,
                                  double separation);

/// What the dressed garment got wrong (DressedGarment::warnings), from its counts and panel areas:
/// crossing itself more often than as authored (as sewn), vertices inside the body, a panel's area
/// changed by more than kPanelAreaChange, and for a padded garment a padding that stalled
/// (`padding_stalled`: why, as the padding settle's stopped reason; "" when it did not).
std::vector<std::string> dressed_warnings(const DressedGarment& g, const std::string& padding_stalled = "");

/// Part names of a garment's legs (trouser legs, skirt parts) and of its sleeves.
bool names_legs(const std::string& part);
bool names_sleeves(const std::string& part);

/// A garment with sleeves, or with no legs or skirt (a top, a dress, a jumpsuit); otherwise a bottom.
/// A sewn pattern: a top when one of its panels is a bodice or a sleeve.
bool is_top(const DressedGarment& g);

/// A garment with legs or a skirt (trousers, a skirt, a suit of top and trousers, a dress): by its
/// parts' names, or a sewn pattern's panels' ("…skirt…", "…pant…", "…leg…").
bool covers_legs(const DressedGarment& g);

/// The rows of the waistband of each bottom among a garment's pieces (garments.cpp).
std::vector<int> waistband(const DressedGarment& g, const Eigen::MatrixX3d& rest, double band, double max_strain,
                           const mesh::InsideTest& inside, double shoulders);

}  // namespace dresskit::dressing::detail
