#pragma once
// What the dressing pipeline does to one garment (dress.cpp): its rest shape, the regions its
// placement made cross rebuilt, its kind, and its waistband.
#include <vector>

#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/inside.h"

namespace dresskit::dressing::detail {

/// The garment's rest shape for settling: as made, graded by the placement's size change.
mesh::TriangleMesh rest_shape(const DressedGarment& g);

/// Rebuilds the regions where the placed garment k crosses itself more often than as authored
/// (garments.cpp); updates its placed positions and crossings_placed.
void untangle(std::vector<DressedGarment>& garments, std::size_t k, const cloth::MeshDistance& body, double clearance);

/// Where garment k still crosses itself more often than as authored: moves it onto its placed
/// positions from a shape crossing itself as authored, its parts kept apart on the way
/// (garments.cpp); updates its placed positions and crossings_placed.
void untangle_along_path(std::vector<DressedGarment>& garments, std::size_t k);

/// Edge–triangle crossings between different garments at their positions `at` (placed or dressed).
int crossings_between(const std::vector<DressedGarment>& garments, Eigen::MatrixX3d DressedGarment::*at);

/// Part names of a garment's legs (trouser legs, skirt parts) and of its sleeves.
bool names_legs(const std::string& part);
bool names_sleeves(const std::string& part);

/// A garment with sleeves, or with no legs or skirt (a top, a dress, a jumpsuit); otherwise a bottom.
bool is_top(const DressedGarment& g);

/// The rows of the waistband of each bottom among a garment's pieces (garments.cpp).
std::vector<int> waistband(const DressedGarment& g, const Eigen::MatrixX3d& rest, double band, double max_strain,
                           const mesh::InsideTest& inside);

}  // namespace dresskit::dressing::detail
