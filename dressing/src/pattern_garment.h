#pragma once
// Garments given as sewing patterns (dress.cpp): read, cut, sewn around the body and welded into
// one mesh, which the pipeline then treats as a garment mesh; and their panels' areas once dressed.
#include <memory>
#include <string>

#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/dressing/dress.h"

namespace dresskit::dressing::detail {

/// Whether the garment file is a sewing pattern (a .json file) rather than a mesh.
bool is_pattern_garment(const GarmentFile& g);

/// Reads the pattern of g, cuts it, sews it around the body (metres; body_distance is its
/// distance) in g's fabric and welds it: fills d.mesh (the sewn garment, its rest shape) and
/// d.pattern. Throws InputError naming the file and the panel, edge or stitch for a bad pattern.
void sew_pattern_garment(const GarmentFile& g, const mesh::TriangleMesh& body,
                         const std::shared_ptr<const cloth::MeshDistance>& body_distance,
                         const DressOptions& options, DressedGarment& d);

/// Each panel's area at the garment's dressed positions into d.pattern.panel_area_dressed (nothing
/// when the cleaning stage changed the sewn mesh's vertices).
void measure_dressed_panels(DressedGarment& d);

}  // namespace dresskit::dressing::detail
